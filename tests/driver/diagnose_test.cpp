// `weavelab diagnose` (docs/design.md §7.6): every term's power is the rate of
// its energy; the energy ledger closes (kinetic plus potential energy change by
// the work of the other forces); the distance files cover every crossing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "driver/diagnose.h"
#include "models/core/term_model.h"
#include "models/model_factory.h"
#include "models/scene/scene.h"
#include "tests/support/test_scenes.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

// A 5×5 cloth at two corners in the wind, yarns sliding without friction, with
// yarn viscosity: every kind of term (conservative, wind, damping) is present.
std::string scene_text() {
  return test::hanging_cloth_toml(5, 0.05) + "[terms]\nfriction = false\n[damping]\nyarn_viscosity_Pa_s = 10.0\n";
}

TEST(TermReadings, EachConservativeTermsPowerIsTheRateOfItsEnergy) {
  const Scene scene = parse_scene(scene_text(), "test.toml");
  std::mt19937 rng(7);
  std::normal_distribution<double> n01;
  for (const char* name : {"yarn", "fem"}) {
    SCOPED_TRACE(name);
    auto model = make_model(scene, name);
    auto& terms = dynamic_cast<TermModel&>(*model);
    Vec q = model->initial_q(), v = model->initial_v();
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      q[i] += 2e-5 * n01(rng);
      v[i] = 0.05 * n01(rng);
    }
    for (int d : model->fixed_dofs()) v[d] = 0;
    const double eps = 1e-7;
    const auto now = terms.term_readings(0.0, q, v);  // the frozen inputs (F_n) at q, kept for the energies below
    const auto ahead = terms.term_readings(0.0, q + eps * v, v, false);
    const auto behind = terms.term_readings(0.0, q - eps * v, v, false);
    int checked = 0;
    for (size_t k = 0; k < now.size(); ++k) {
      if (!now[k].conservative) continue;
      const double rate = (ahead[k].energy_J - behind[k].energy_J) / (2 * eps);
      SCOPED_TRACE(now[k].name);
      EXPECT_GT(std::abs(now[k].power_W), 0.0);  // a non-trivial check
      EXPECT_NEAR(now[k].power_W, -rate, 1e-6 * std::abs(rate) + 1e-15);
      ++checked;
    }
    EXPECT_GE(checked, 4);  // stretch, shear, bending, gravity, handles
  }
}

TEST(Diagnose, TheEnergyLedgerClosesAndTheDistanceCoversEveryCrossing) {
  const fs::path dir = fs::temp_directory_path() / ("weavelab_diagnose_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  DiagnoseConfig c;
  c.scene_path = "test.toml";
  c.scene = parse_scene(scene_text(), "test.toml");
  c.time_steps.rtol = 1e-7;
  c.error_estimate = false;
  c.out_dir = dir;
  c.progress = false;
  const DiagnoseResult r = run_diagnosis(c);
  EXPECT_GT(r.mean_rms_m, 0.0);
  EXPECT_EQ(r.verdict, "time error unknown");

  // ΔT + ΔV = W_wind + W_damping per model at the last frame, where the wind has done its work.
  std::ifstream in(dir / "energies.csv");
  std::string line;
  std::getline(in, line);
  std::map<std::string, std::map<std::string, std::pair<double, double>>> first_last;  // model → quantity → (t=0, last)
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string t, model, quantity, value;
    std::getline(ss, t, ',');
    std::getline(ss, model, ',');
    std::getline(ss, quantity, ',');
    std::getline(ss, value, ',');
    auto [it, fresh] = first_last[model].try_emplace(quantity, std::stod(value), std::stod(value));
    if (!fresh) it->second.second = std::stod(value);
  }
  for (const char* model : {"yarn", "fem"}) {
    SCOPED_TRACE(model);
    double stored = 0, work = 0;
    for (const auto& [quantity, fl] : first_last[model])
      (quantity.rfind("work of ", 0) == 0 ? work : stored) += fl.second - fl.first;
    const double wind = first_last[model]["work of wind"].second,
                 damping = first_last[model]["work of yarn_damping"].second;
    ASSERT_GT(wind, 0.0);
    ASSERT_LT(damping, 0.0);
    EXPECT_NEAR(stored, work, 0.1 * std::abs(damping));  // a ledger that drops the damping misses by 10×
  }

  int lines = 0;
  for (std::ifstream rows(dir / "rows.csv"); std::getline(rows, line);) ++lines;
  EXPECT_EQ(lines, 1 + 5);  // header and the five rows of crossings
  EXPECT_TRUE(fs::exists(dir / "distance.pvd"));
  EXPECT_TRUE(fs::exists(dir / "diagnosis.json"));
  fs::remove_all(dir);
}

// One frame after t = 0 is a valid run: its distance is that frame's RMS, as
// distance.csv holds it, not NaN.
TEST(Diagnose, OneFrameGivesTheFramesFiniteDistance) {
  const fs::path dir = fs::temp_directory_path() / ("weavelab_diagnose_one_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  DiagnoseConfig c;
  c.scene_path = "test.toml";
  c.scene = parse_scene(test::hanging_cloth_toml(5, 0.01), "test.toml");
  c.time_steps.scene = true;
  c.error_estimate = false;
  c.out_dir = dir;
  c.progress = false;
  const DiagnoseResult r = run_diagnosis(c);
  std::ifstream in(dir / "distance.csv");
  std::string header, row, extra;
  std::getline(in, header);
  ASSERT_TRUE(std::getline(in, row));
  EXPECT_FALSE(std::getline(in, extra)) << "one frame only";
  const std::string rms = row.substr(row.find(',') + 1, row.find(',', row.find(',') + 1) - row.find(',') - 1);
  EXPECT_TRUE(std::isfinite(r.mean_rms_m));
  EXPECT_GT(r.mean_rms_m, 0.0);
  EXPECT_NEAR(r.mean_rms_m, std::stod(rms), 1e-9 * r.mean_rms_m) << row;  // csv_number's digits
  fs::remove_all(dir);
}

}  // namespace
}  // namespace wl
