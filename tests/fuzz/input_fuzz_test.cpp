// Seeded fuzz of the input readers, in process: random mutations of valid
// inputs — scenes (a key deleted, a value replaced by NaN, ±inf, a huge,
// negative or zero number or a value of the wrong type, a table or key
// duplicated, the text truncated, bytes of garbage), continuum parameter files,
// OBJ meshes, run folders (run.pvd and VTU frames: a header count made huge, a
// coordinate NaN, times out of order, a frame naming /dev/zero) and fidelity
// references (reference.bin: bytes flipped, a count made huge, the file cut).
// Each reader must either accept the input or throw its own bad-input error
// (the CLI's exit 2: SceneError, FemParameterError, RunReadError,
// std::invalid_argument) naming the file; anything else — another exception, a
// crash, a sanitizer report — fails. A scene that is accepted is checked as a
// run checks it (run settings, memory) and, when small, its models are built.
// The case counts are fixed and seeded; WEAVELAB_FUZZ_CASES=N multiplies them
// by N for a longer campaign (tests/fuzz/README.md). The command line is fuzzed
// by tests/fuzz/cli_fuzz.py.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>

#include "driver/fidelity_reference.h"
#include "driver/memory_estimate.h"
#include "driver/run_settings.h"
#include "models/fem/fem_material.h"
#include "models/model_factory.h"
#include "models/scene/obstacle_mesh.h"
#include "models/scene/scene.h"
#include "output/pvd_series.h"
#include "output/run_reader.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

// The campaign multiplier (WEAVELAB_FUZZ_CASES, default 1).
int multiplier() {
  const char* m = std::getenv("WEAVELAB_FUZZ_CASES");
  const int n = m ? std::atoi(m) : 1;
  return n > 0 ? n : 1;
}

const std::vector<std::string> kValues = {"nan",
                                          "inf",
                                          "-inf",
                                          "0",
                                          "0.0",
                                          "-1",
                                          "-0.5",
                                          "1",
                                          "1e-300",
                                          "1e30",
                                          "1e300",
                                          "-1e300",
                                          "9223372036854775807",
                                          "-9223372036854775808",
                                          "18446744073709551616",
                                          "\"text\"",
                                          "\"\"",
                                          "true",
                                          "[1, 2]",
                                          "[]",
                                          "{}",
                                          "[nan, nan, nan]",
                                          "[1e308, -1e308, 0]",
                                          "1979-05-27",
                                          "\"/dev/zero\""};

template <class T>
const T& pick(const std::vector<T>& v, std::mt19937& rng) {
  return v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng)];
}

size_t below(size_t n, std::mt19937& rng) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); }

std::string garbage(std::mt19937& rng) {
  std::string g(1 + below(63, rng), '\0');
  for (char& c : g) c = static_cast<char>(below(256, rng));
  return g;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// One mutation of a TOML text: mostly one key's value or presence, now and then the file's form.
std::string mutate_toml_once(const std::string& text, std::mt19937& rng) {
  std::vector<std::string> lines = lines_of(text);
  std::vector<size_t> keys, headers;
  for (size_t k = 0; k < lines.size(); ++k) {
    if (lines[k].find(" = ") != std::string::npos) keys.push_back(k);
    if (!lines[k].empty() && lines[k][0] == '[') headers.push_back(k);
  }
  const int kind = std::discrete_distribution<int>({3, 10, 1, 1, 1, 1, 1, 1})(rng);
  if (kind == 0 && !keys.empty()) lines.erase(lines.begin() + static_cast<long>(pick(keys, rng)));
  if (kind == 1 && !keys.empty()) {
    std::string& l = lines[pick(keys, rng)];
    l = l.substr(0, l.find(" = ")) + " = " + pick(kValues, rng);
  }
  if (kind == 3 && !headers.empty()) {  // a table repeated at the end
    const size_t start = pick(headers, rng);
    size_t end = lines.size();
    for (size_t h : headers)
      if (h > start) end = std::min(end, h);
    std::vector<std::string> copy(lines.begin() + static_cast<long>(start), lines.begin() + static_cast<long>(end));
    lines.insert(lines.end(), copy.begin(), copy.end());
  }
  if (kind == 4 && !keys.empty()) {
    const size_t k = pick(keys, rng);
    lines.insert(lines.begin() + static_cast<long>(k), lines[k]);
  }
  if (kind == 7 && lines.size() > 2) std::swap(lines[below(lines.size(), rng)], lines[below(lines.size(), rng)]);
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  if (kind == 2) out.resize(below(out.size() + 1, rng));
  if (kind == 5) out.insert(below(out.size() + 1, rng), garbage(rng));
  if (kind == 6)
    for (size_t n = 1 + below(8, rng); n > 0 && !out.empty(); --n)
      out[below(out.size(), rng)] = static_cast<char>(below(256, rng));
  return out;
}

std::string mutate_toml(std::string text, std::mt19937& rng) {
  const int count = std::discrete_distribution<int>({0, 6, 2, 1})(rng);
  for (int m = 0; m < count; ++m) text = mutate_toml_once(text, rng);
  return text;
}

// What a reader may throw on bad input: its own error, naming `file`.
void expect_located_refusal(const std::function<void()>& read, const std::string& file, const std::string& input,
                            int& refused) {
  try {
    read();
  } catch (const std::invalid_argument& e) {  // SceneError derives from runtime_error: caught below
    ++refused;
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what() << "\n---\n" << input;
  } catch (const SceneError& e) {
    ++refused;
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what() << "\n---\n" << input;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a bad-input error: " << e.what() << "\n---\n" << input;
  }
}

// ---- scenes ------------------------------------------------------------------------

// A valid input of tests/fuzz/inputs/ (shared with cli_fuzz.py).
std::string input(const std::string& name) {
  std::ifstream in(fs::path(WEAVELAB_SOURCE_DIR) / "tests" / "fuzz" / "inputs" / name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> base_scenes() {
  return {input("woven.toml"), input("flat.toml"), input("continuum.toml"), input("knit.toml"),
          input("obstacles.toml")};
}

// An accepted scene goes on as a run takes it: run settings, memory, and its
// models when small. A model whose construction fails numerically (a knit
// whose rest shape does not converge) throws std::runtime_error: the
// comparisons report it as exit 1, `run` and `info` as exit 3; counted apart.
void check_accepted_scene(const Scene& scene, const std::string& text, int& models_built, int& not_built) {
  try {
    check_run_settings(scene, {});
    for (const std::string& model : {yarn_level_model(scene), std::string("fem")}) {
      if (memory_shortfall(scene, model) || estimate_run_memory(scene, model).dofs > 3000) continue;
      (void)make_model(scene, model)->num_dofs();
      ++models_built;
    }
  } catch (const std::invalid_argument&) {  // the models' own located refusals (exit 2)
  } catch (const SceneError&) {
  } catch (const std::runtime_error&) {
    ++not_built;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "an accepted scene then threw " << e.what() << "\n---\n" << text;
  }
}

TEST(InputFuzz, ScenesAreReadOrRefusedLocated) {
  std::mt19937 rng(20261129);
  const std::vector<std::string> bases = base_scenes();
  for (const std::string& b : bases) ASSERT_NO_THROW((void)parse_scene(b, "base.toml")) << b;
  const int cases = 4000 * multiplier();
  int refused = 0, models_built = 0, not_built = 0;
  for (int k = 0; k < cases; ++k) {
    const std::string text = mutate_toml(bases[k % bases.size()], rng);
    int before = refused;
    expect_located_refusal([&] { (void)parse_scene(text, "fuzz.toml"); }, "fuzz.toml", text, refused);
    if (refused > before) continue;
    check_accepted_scene(parse_scene(text, "fuzz.toml"), text, models_built, not_built);
  }
  std::cout << "scene fuzz: " << cases << " cases, " << refused << " refused, " << models_built << " models built, "
            << not_built << " failed numerically\n";
  EXPECT_GT(refused, cases / 3);  // the mutations mostly break the scene
  EXPECT_GT(models_built, 0);     // and some leave it whole
}

// Table headers that toml++ 3.3's header parser hands on to its key parser
// broken (models/scene/toml_include.h): a located syntax error, in every build.
TEST(InputFuzz, MalformedTableHeadersAreLocatedSyntaxErrors) {
  const Scene scene = parse_scene(input("woven.toml"), "woven.toml");
  for (const std::string header : {"[[[1]]]", "[[[a]]]", "[[[]]", "[[=", "[!]", "[ =a]", "[[+x]]"}) {
    const std::string text = "[cloth]\nwarps = 5\n" + header + "\n";
    try {
      (void)parse_scene(text, "h.toml");
      ADD_FAILURE() << header << ": accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("h.toml:3: key '(syntax)'", 0), 0u) << header << ": " << e.what();
    }
    EXPECT_THROW((void)parse_fem_parameters(header + "\n", "p.toml", default_fem_material(scene)), FemParameterError)
        << header;
  }
}

// ---- continuum parameter files ---------------------------------------------------------

TEST(InputFuzz, ParameterFilesAreReadOrRefusedLocated) {
  std::mt19937 rng(20261130);
  const Scene scene = parse_scene(input("woven.toml"), "woven.toml");
  const FemMaterial base = default_fem_material(scene);
  const std::string params = input("params.toml");
  const int cases = 2000 * multiplier();
  int refused = 0;
  for (int k = 0; k < cases; ++k) {
    const std::string text = mutate_toml(params, rng);
    expect_located_refusal([&] { (void)parse_fem_parameters(text, "params.toml", base); }, "params.toml", text,
                           refused);
  }
  std::cout << "parameter file fuzz: " << cases << " cases, " << refused << " refused\n";
  EXPECT_GT(refused, cases / 3);
}

// ---- OBJ meshes ------------------------------------------------------------------------

TEST(InputFuzz, ObjMeshesAreReadOrRefusedLocated) {
  std::mt19937 rng(20261131);
  test::ScratchDir dir;
  const std::string obj =
      "# a tetrahedron\no tet\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvt 0 0\nf 1 3 2\nf 1 2 4\n"
      "f 2/1 3/1 4/1\nf 1//1 4//1 3//1\n";
  const std::vector<std::string> replacements = {"nan", "inf", "-inf",    "1e308", "-1e308",
                                                 "0",   "-1",  "-5",      "5",     "99999999999999999999",
                                                 "x",   "",    "1/2/3/4", "//",    "-2147483648"};
  const int cases = 1000 * multiplier();
  int refused = 0;
  const fs::path path = dir / "mesh.obj";
  for (int k = 0; k < cases; ++k) {
    std::vector<std::string> lines = lines_of(obj);
    for (size_t m = 1 + below(2, rng); m > 0; --m) {
      std::string& l = lines[below(lines.size(), rng)];
      std::vector<std::string> words;
      std::istringstream w(l);
      for (std::string s; w >> s;) words.push_back(s);
      if (words.empty()) continue;
      words[below(words.size(), rng)] = pick(replacements, rng);
      l.clear();
      for (const std::string& s : words) l += s + " ";
    }
    std::string text;
    for (const std::string& l : lines) text += l + "\n";
    if (below(8, rng) == 0) text.resize(below(text.size() + 1, rng));
    if (below(8, rng) == 0) text.insert(below(text.size() + 1, rng), garbage(rng));
    std::ofstream(path, std::ios::binary) << text;
    const double scale = below(10, rng) == 0 ? pick(std::vector<double>{1e300, 1e-300, 0.0, -1.0}, rng) : 0.01;
    expect_located_refusal([&] { (void)read_obj_mesh(path.string(), scale); }, "mesh.obj", text, refused);
  }
  std::cout << "OBJ fuzz: " << cases << " cases, " << refused << " refused\n";
  EXPECT_GT(refused, cases / 3);
}

// ---- run folders (the target of `fit`) ---------------------------------------------------

// A run folder of three frames of a 4×4 grid as the run writes it (PvdSeries).
void write_base_run(const fs::path& dir) {
  PvdSeries series(dir, "run");
  for (int f = 0; f < 3; ++f) {
    Frame frame;
    frame.time = 0.002 * f;
    frame.points.resize(16, 3);
    DataArray u{"u", 1, {}}, v{"v", 1, {}};
    for (int p = 0; p < 16; ++p) {
      frame.points.row(p) << 0.001 * (p % 4), 0.0, 0.02 - 0.001 * (p / 4) - 1e-4 * f * f;
      u.values.push_back(0.001 * (p % 4));
      v.values.push_back(0.001 * (p / 4));
    }
    frame.cells.push_back(test::quad_grid_cells(4));
    frame.point_data = {u, v};
    series.add(frame);
  }
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Replaces the value of the first `attribute="..."` at or after a random place.
std::string replace_attribute(std::string text, const std::string& attribute, const std::string& value,
                              std::mt19937& rng) {
  size_t at = text.find(attribute + "=\"", below(text.size(), rng));
  if (at == std::string::npos) at = text.find(attribute + "=\"");
  if (at == std::string::npos) return text;
  const size_t start = at + attribute.size() + 2, end = text.find('"', start);
  return text.replace(start, end - start, value);
}

// One mutation of a VTU frame.
std::string mutate_vtu(std::string text, std::mt19937& rng) {
  const std::vector<std::string> counts = {"2000000000", "9223372036854775808", "-1", "0", "1", "nan",
                                           "1e300",      "4294967296",          "17", ""};
  switch (below(6, rng)) {
    case 0: return replace_attribute(text, "NumberOfPoints", pick(counts, rng), rng);
    case 1: return replace_attribute(text, "NumberOfComponents", pick(counts, rng), rng);
    case 2: {  // a number of the data replaced
      const size_t from = text.find("<Points>");
      size_t at = text.find_first_of("0123456789", from == std::string::npos ? 0 : below(text.size(), rng));
      if (at == std::string::npos) return text;
      const size_t end = text.find_first_of(" \n<", at);
      return text.replace(at, end - at, pick(std::vector<std::string>{"nan", "inf", "-inf", "1e308", "x", ""}, rng));
    }
    case 3: text.resize(below(text.size() + 1, rng)); return text;
    case 4: return text.insert(below(text.size() + 1, rng), garbage(rng));
    default: return replace_attribute(text, "Name", pick(std::vector<std::string>{"u", "v", "Points", ""}, rng), rng);
  }
}

// One mutation of run.pvd.
std::string mutate_pvd(std::string text, std::mt19937& rng) {
  switch (below(6, rng)) {
    case 0:
      return replace_attribute(text, "timestep",
                               pick(std::vector<std::string>{"nan", "inf", "-1", "1e300", "x", "", "0", "0.002"}, rng),
                               rng);
    case 1:
      return replace_attribute(
          text, "file",
          pick(std::vector<std::string>{"/dev/zero", "/dev/null", "/", "frames", "../run.pvd", "missing.vtu", ""}, rng),
          rng);
    case 2: {  // a DataSet line repeated or dropped
      std::vector<std::string> lines = lines_of(text);
      std::vector<size_t> sets;
      for (size_t k = 0; k < lines.size(); ++k)
        if (lines[k].find("<DataSet") != std::string::npos) sets.push_back(k);
      if (sets.empty()) return text;
      const size_t k = pick(sets, rng);
      if (below(2, rng)) lines.insert(lines.begin() + static_cast<long>(k), lines[k]);
      else lines.erase(lines.begin() + static_cast<long>(k));
      std::string out;
      for (const std::string& l : lines) out += l + "\n";
      return out;
    }
    case 3: text.resize(below(text.size() + 1, rng)); return text;
    case 4: return text.insert(below(text.size() + 1, rng), garbage(rng));
    default: {  // two frames' times swapped
      const size_t a = text.find("timestep=\""), b = text.rfind("timestep=\"");
      if (a == std::string::npos || a == b) return text;
      const std::string ta = text.substr(a + 10, text.find('"', a + 10) - a - 10),
                        tb = text.substr(b + 10, text.find('"', b + 10) - b - 10);
      text.replace(b + 10, tb.size(), ta);
      return text.replace(a + 10, ta.size(), tb);
    }
  }
}

TEST(InputFuzz, RunFoldersAreReadOrRefusedLocated) {
  std::mt19937 rng(20261132);
  test::ScratchDir base, dir;
  write_base_run(base.path());
  const std::vector<fs::path> files = {"run.pvd", "frames/run_00000.vtu", "frames/run_00001.vtu",
                                       "frames/run_00002.vtu"};
  std::vector<std::string> texts;
  for (const fs::path& f : files) texts.push_back(read_text(base.path() / f));
  ASSERT_EQ(read_run_frames(base.path()).size(), 3u);
  fs::create_directories(dir / "frames");
  const int cases = 1000 * multiplier();
  int refused = 0;
  for (int k = 0; k < cases; ++k) {
    std::vector<std::string> mutated = texts;
    std::string what;
    for (size_t m = 1 + below(2, rng); m > 0; --m) {
      const size_t f = below(files.size(), rng);
      mutated[f] = f == 0 ? mutate_pvd(mutated[f], rng) : mutate_vtu(mutated[f], rng);
      what += files[f].string() + " ";
    }
    for (size_t f = 0; f < files.size(); ++f) std::ofstream(dir / files[f].string(), std::ios::binary) << mutated[f];
    const std::string input = what + "\n" + mutated[0];
    expect_located_refusal(
        [&] {
          for (const RecordedFrame& frame : read_run_frames(dir.path())) {
            EXPECT_TRUE(std::isfinite(frame.time)) << input;
            EXPECT_TRUE(frame.points.allFinite()) << input;
          }
        },
        dir.path().string(), input, refused);
  }
  std::cout << "run folder fuzz: " << cases << " cases, " << refused << " refused\n";
  EXPECT_GT(refused, cases / 3);
}

// ---- fidelity references (fidelity --reference-from) -------------------------------------

TEST(InputFuzz, FidelityReferencesAreReadOrRefusedLocated) {
  std::mt19937 rng(20261133);
  test::ScratchDir dir;
  FidelityReference ref;
  ref.row.variant = "full";
  ref.row.model = "yarn";
  ref.row.outcome = "ok";
  for (int f = 0; f < 3; ++f) {
    ref.frames.times.push_back(0.002 * f);
    FramePoints x(9, 3);
    x.setConstant(0.001 * f);
    ref.frames.x.push_back(x);
    ref.frames.uv.push_back(std::vector<Vec2>(9, Vec2(0.001, 0.002)));
    ref.frames.energy_change.push_back(-1e-6 * f);
  }
  write_fidelity_reference(dir.path(), "key", ref);
  const std::string bytes = read_text(dir / "reference.bin");
  const int cases = 1000 * multiplier();
  int refused = 0;
  for (int k = 0; k < cases; ++k) {
    std::string b = bytes;
    switch (below(5, rng)) {
      case 0:
        for (size_t n = 1 + below(16, rng); n > 0; --n) b[below(b.size(), rng)] = static_cast<char>(below(256, rng));
        break;
      case 1: {  // a u64 count made huge
        const size_t at = 8 + below(b.size() - 16, rng);
        b.replace(at, 8,
                  pick(std::vector<std::string>{std::string(8, '\xff'), std::string("\0\0\0\x80\0\0\0\0", 8),
                                                std::string("\xff\xff\xff\x7f\0\0\0\0", 8)},
                       rng));
        break;
      }
      case 2: b.resize(below(b.size() + 1, rng)); break;
      case 3: b += garbage(rng); break;
      default: b.replace(8 + below(b.size() - 16, rng), 8, std::string("\0\0\0\0\0\0\xf8\x7f", 8));  // a NaN
    }
    std::ofstream(dir / "reference.bin", std::ios::binary) << b;
    expect_located_refusal(
        [&] {
          const FidelityReference read = read_fidelity_reference(dir.path(), "key");
          check_reference_frames(read.frames, ref.frames.times, 9, dir.path());
        },
        "reference.bin", "(binary)", refused);
  }
  std::cout << "reference fuzz: " << cases << " cases, " << refused << " refused\n";
  EXPECT_GT(refused, cases / 3);
}

}  // namespace
}  // namespace wl
