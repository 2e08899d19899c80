// Randomized scenes: seeded mutations of two valid scenes (one per model) —
// a key dropped, or a value replaced by NaN, ±inf, zero, a negative, a huge
// number or a value of the wrong type. Every mutation must end in exit 0, 1 or
// 2 (README: exit codes), never a crash, a hang or exit 3; an exit 2 names the
// scene file and line. Mutations the parser rejects are judged in-process
// (a SceneError is the CLI's exit 2); the ones it accepts run through the CLI
// for 4 ms of simulated time (--duration, so that a dropped duration_s does not
// run the default 0.5 s).
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>

#include "models/scene/scene.h"
#include "tests/output/output_test_util.h"

namespace {

namespace fs = std::filesystem;
using wl::test::shell_quote;

// Every table of the scene format, on a 5×5 cloth (runs take milliseconds).
const std::string kYarnScene = R"([cloth]
warps = 5
wefts = 5
spacing_m = 0.001
radius_m = 0.0005
sliding = true
warp_yarn_types = ["a", "b"]
weft_yarn_types = ["a"]
[cloth.pattern]
kind = "twill"
over = 2
under = 2
shift = 1
[yarn_types.a]
density_kg_per_m = 0.002
stretch_modulus_Pa = 500000.0
bending_modulus_Pa = 0.00014
[yarn_types.b]
density_kg_per_m = 0.0025
stretch_modulus_Pa = 170000.0
bending_modulus_Pa = 0.00011
[contact]
shear_model = "gong"
friction_model = "gong"
shear_modulus_Pa = 1000.0
friction_coefficient = 0.5
friction_stiffness_N_per_m = 1000.0
friction_damping_Ns_per_m = 1000.0
tanh_sharpness_per_m = 10.0
parallel_stiffness_N_per_m2 = 1.0
lock_exponent = 3.0
lock_sigma = 0.6
[pose]
kind = "upright"
height_m = 0.02
[[pins]]
node = [4, 0]
[[handles]]
node = [0, 0]
stiffness_N_per_m = 10000.0
[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.8]
[wind]
velocity_m_per_s = [0.0, 5.0, 0.0]
air_density_kg_per_m3 = 1.225
drag_Ns_per_m3 = 0.5
[time]
duration_s = 0.004
dt_s = 0.001
output_interval_s = 0.002
integrator = "be-linear"
adaptive = false
rtol = 0.000001
atol = 0.000000001
[terms]
stretch = true
bending = true
shear = true
parallel_contact = true
friction = true
gravity = true
wind = true
handles = true
inertia = true
)";

const std::string kFemScene = R"([cloth]
warps = 5
wefts = 5
spacing_m = 0.001
radius_m = 0.0004
[pose]
kind = "flat"
height_m = 0.0
[[pins]]
node = [0, 0]
[[handles]]
node = [4, 0]
stiffness_N_per_m = 10000.0
[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.8]
[time]
duration_s = 0.004
dt_s = 0.001
output_interval_s = 0.002
[fem]
stride = 2
areal_density_kg_per_m2 = 4.5
warp_stretch_N_per_m = 300.0
weft_stretch_N_per_m = 120.0
shear_N_per_m = 0.8
shear_lock_angle_rad = 0.5
shear_lock_exponent = 3.0
warp_bending_N_m = 0.0000001
weft_bending_N_m = 0.00000008
)";

// Invalid for most keys, or valid but extreme (1e-300, 1e30, 1e300 for a density or a stiffness).
const std::vector<std::string> kReplacements = {"nan",      "inf",  "-inf",   "0",    "0.0",   "-1",
                                                "-0.5",     "1",    "1e-300", "1e30", "1e300", "9223372036854775807",
                                                "\"text\"", "true", "[1, 2]", "{}"};

// One to three mutations of `base` (one in 70 %): each drops a `key = value` line or replaces its value.
std::string mutate(const std::string& base, std::mt19937& rng) {
  std::vector<std::string> lines;
  std::istringstream in(base);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::vector<size_t> assignments;
  for (size_t k = 0; k < lines.size(); ++k)
    if (lines[k].find(" = ") != std::string::npos) assignments.push_back(k);
  const int count = std::discrete_distribution<int>({0, 7, 2, 1})(rng);  // mostly one mutation
  for (int m = 0; m < count; ++m) {
    std::string& line = lines[assignments[std::uniform_int_distribution<size_t>(0, assignments.size() - 1)(rng)]];
    const size_t choice = std::uniform_int_distribution<size_t>(0, kReplacements.size())(rng);
    if (choice == kReplacements.size()) line = "";  // the key dropped
    else if (!line.empty()) line = line.substr(0, line.find(" = ")) + " = " + kReplacements[choice];
  }
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

TEST(SceneMutation, EveryMutationEndsInExit0To2NeverACrash) {
  wl::test::ScratchDir dir;
  std::mt19937 rng(20261123);
  const int per_scene = 150, max_cli_runs = 120;
  int tried = 0, rejected_in_process = 0, cli_runs = 0, skipped = 0;
  std::map<int, int> exits;
  int located = 0;
  for (const auto& [base, model] : {std::pair{kYarnScene, "yarn"}, std::pair{kFemScene, "fem"}}) {
    for (int k = 0; k < per_scene; ++k) {
      const std::string text = mutate(base, rng);
      ++tried;
      try {
        (void)wl::parse_scene(text, "mutated.toml");
      } catch (const wl::SceneError& e) {
        ++rejected_in_process;
        ++exits[2];
        const bool has_line = std::string(e.what()).rfind("mutated.toml:", 0) == 0 && e.line > 0;
        located += has_line;
        EXPECT_TRUE(has_line) << e.what() << "\n" << text;
        continue;
      } catch (const std::exception& e) {
        ADD_FAILURE() << "parse threw a non-scene error: " << e.what() << "\n" << text;
        continue;
      }
      if (cli_runs >= max_cli_runs) {
        ++skipped;
        continue;
      }
      ++cli_runs;
      const fs::path scene = dir / "mutated.toml", out = dir / ("out" + std::to_string(tried));
      std::ofstream(scene) << text;
      const auto r =
          wl::test::run_command("timeout 60 " + std::string(WEAVELAB_CLI) + " run " + shell_quote(scene.string()) +
                                " --model " + model + " --duration 0.004 --quiet --out " + shell_quote(out.string()));
      ++exits[r.exit_code];
      EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == 2)
          << "exit " << r.exit_code << ": " << r.output << "\n"
          << text;
      if (r.exit_code == 2) {
        located += r.output.find("mutated.toml:") != std::string::npos;
        EXPECT_NE(r.output.find("mutated.toml:"), std::string::npos) << "exit 2 without file and line: " << r.output;
        EXPECT_FALSE(fs::exists(out)) << "exit 2 wrote output: " << r.output;
      }
      fs::remove_all(out);
    }
  }
  std::cout << "scene mutations tried " << tried << ": rejected by the parser " << rejected_in_process
            << ", run through the CLI " << cli_runs << " (beyond the cap, not run: " << skipped << "); exits:";
  for (const auto& [code, n] : exits) std::cout << " " << code << "→" << n;
  std::cout << "; exit 2 naming the file " << located << "\n";
  EXPECT_EQ(exits[0] + exits[1] + exits[2], tried - skipped);
  EXPECT_GT(exits[0], 0) << "no mutation ran: the base scenes or the runs are broken";
  EXPECT_GT(exits[2], tried / 2) << "most mutations are invalid";
}

}  // namespace
