// `weavelab fidelity` end to end on a 5×5 cloth: bad input exits 2 with a
// clear message and writes nothing; a run writes the CSV and JSON, names the
// cheapest variant within the tolerance, and the Pareto chart script draws them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/output/output_test_util.h"
#include "tests/support/test_scenes.h"

namespace {

namespace fs = std::filesystem;
using Result = wl::test::CommandResult;

class FidelityCli : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = dir_ / "tiny.toml";
    std::ofstream(scene_) << wl::test::hanging_cloth_toml(5, 0.03);
  }
  Result fidelity(const std::string& options) {
    return wl::test::run_command(std::string(WEAVELAB_CLI) + " fidelity '" + scene_.string() + "' --quiet --out '" +
                                 out().string() + "' " + options);
  }
  void expect_refused(const std::string& options, const std::vector<std::string>& fragments) {
    const Result r = fidelity(options);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    for (const auto& f : fragments)
      EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in: " << r.output;
    EXPECT_FALSE(fs::exists(out())) << "output written for bad input";
  }
  fs::path out() const { return dir_ / "out"; }
  wl::test::ScratchDir dir_;
  fs::path scene_;
};

TEST_F(FidelityCli, UnknownVariantIsRefused) {
  expect_refused("--variants no_friction,fem_s5", {"--variants", "unknown variant 'fem_s5'", "fem_s4"});
}

TEST_F(FidelityCli, ToleranceMustBePositive) {
  expect_refused("--tolerance 0", {"--tolerance", "got 0", "> 0"});
  expect_refused("--tolerance -0.001", {"--tolerance", "-0.001"});
  expect_refused("--tolerance nan", {"--tolerance", "nan"});
}

TEST_F(FidelityCli, ResolutionMustBeKnown) {
  expect_refused("--time-steps fine", {"--time-steps", "'fine'", "'controlled' or 'scene'"});
  expect_refused("--rtol 0", {"--rtol", "got 0"});
  expect_refused("--rtol 1e-13", {"--rtol: got 1e-13, expected a tolerance ≥ 1e-12"});  // the floor of time.rtol
}

TEST_F(FidelityCli, ContinuumReferenceIsRefused) {
  expect_refused("--reference fem_s1", {"--reference", "fem_s1", "yarn-level variant"});
}

TEST_F(FidelityCli, BadParameterFileIsRefused) {
  std::ofstream(dir_ / "params.toml") << "shear_N_per_m = -1\n";
  expect_refused("--fem-params '" + (dir_ / "params.toml").string() + "'", {"params.toml:1", "shear_N_per_m"});
}

TEST_F(FidelityCli, JobOptionsAreCheckedBeforeAnythingRuns) {
  expect_refused("--reference-from '" + (dir_ / "nowhere").string() + "' --variants frozen_sliding",
                 {"--reference-from", "nowhere", "cannot be read"});
  expect_refused("--reference-only --variants frozen_sliding", {"--reference-only", "--variants"});
  std::ofstream(dir_ / "reference.bin") << "not a reference";
  expect_refused("--reference-from '" + dir_.path().string() + "'", {"reference.bin", "not a fidelity reference"});
  // --list-variants names the planned rungs and writes nothing
  const Result r = fidelity("--time-steps scene --list-variants");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("frozen_sliding\n"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("full\n"), std::string::npos) << "the reference is not a rung: " << r.output;
  EXPECT_FALSE(fs::exists(out()));
}

TEST_F(FidelityCli, WritesTheLadderAndNamesTheCheapestVariant) {
  const Result r = fidelity("--variants frozen_sliding,fem_first_guess --tolerance 1 --repeats 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // A 1 m tolerance admits every variant, so the cheapest run of the three is named.
  EXPECT_NE(r.output.find("cheapest within 1e+03 mm"), std::string::npos) << r.output;
  std::ifstream csv(out() / "fidelity.csv");
  std::string line;
  std::vector<std::string> variants;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("variant,model,dofs,steps,cpu_s,wall_s,rms_m,worst_frame_rms_m,max_m,energy_diff_J", 0), 0u);
  std::string cheapest;
  double least = 1e300;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    variants.push_back(cells[0]);
    if (std::stod(cells[4]) < least) least = std::stod(cells[4]), cheapest = cells[0];
  }
  EXPECT_EQ(variants, (std::vector<std::string>{"full", "frozen_sliding", "fem_first_guess"}));
  EXPECT_NE(r.output.find("cloth): " + cheapest + ","), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(out() / "fidelity.json"));
  // Each row carries its own time error; the record says at which time steps the rungs ran.
  std::stringstream json;
  json << std::ifstream(out() / "fidelity.json").rdbuf();
  for (const char* field :
       {"\"resolution\": \"sdirk2 under error control, rtol 0.0001", "\"time_error\"", "\"method\": \"richardson\""})
    EXPECT_NE(json.str().find(field), std::string::npos) << field;
  const Result plot = wl::test::run_command(std::string(wl::test::python()) + " '" + WEAVELAB_SOURCE_DIR +
                                            "/experiments/fidelity/scripts/plot_fidelity.py' '" + out().string() + "'");
  EXPECT_EQ(plot.exit_code, 0) << plot.output;
  EXPECT_GT(fs::file_size(out() / "fidelity.png"), 1000u);
  EXPECT_GT(fs::file_size(out() / "fidelity.svg"), 1000u);
}

}  // namespace

// A knit's ladder (docs/models.md §11.9): the calibrated continuum on its contact grid at the
// strides that divide it (9 column and 6 row spacings: 1 and 3), measured at the stitch contacts.
class KnitFidelityCli : public FidelityCli {
 protected:
  void SetUp() override {
    scene_ = dir_ / "knit.toml";
    std::ofstream(scene_) << wl::test::hanging_knit_toml(6, 5);
    params_ = dir_ / "params.toml";
    std::ofstream(params_) << "warp_stretch_N_per_m = 40.0\nweft_stretch_N_per_m = 50.0\nshear_N_per_m = 2.0\n"
                              "warp_bending_N_m = 1e-6\nweft_bending_N_m = 2e-6\n";
  }
  std::string with_params() const { return "--fem-params '" + params_.string() + "' "; }
  fs::path params_;
};

TEST_F(KnitFidelityCli, RefusesTheRungsItCannotRun) {
  expect_refused("--variants fem_s1", {"fem_s1", "no calibrated parameters"});
  expect_refused(with_params() + "--variants fem_s2", {"fem_s2", "knit's contact grid", "2·wales − 1"});
  expect_refused(with_params() + "--variants fem_first_guess", {"fem_first_guess", "nothing derives"});
  const Result r = fidelity(with_params() + "--time-steps scene --list-variants");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* rung : {"fem_s1\n", "fem_s3\n"}) EXPECT_NE(r.output.find(rung), std::string::npos) << r.output;
  for (const char* rung : {"fem_s2\n", "fem_s4\n", "fem_first_guess\n", "no_friction\n"})
    EXPECT_EQ(r.output.find(rung), std::string::npos) << rung << " in: " << r.output;
  EXPECT_FALSE(fs::exists(out()));
}

TEST_F(KnitFidelityCli, MeasuresTheContinuumAtTheStitchContacts) {
  // The reference is the knit's yarn level: its model column reads knit (yarn_level_model).
  const Result r = fidelity(with_params() + "--time-steps scene --variants fem_s1,fem_s3 --tolerance 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::stringstream csv;
  csv << std::ifstream(out() / "fidelity.csv").rdbuf();
  for (const char* row : {"\nfull,knit,", "\nfem_s1,fem,", "\nfem_s3,fem,"})
    EXPECT_NE(csv.str().find(row), std::string::npos) << row << " in: " << csv.str();
  std::stringstream json;
  json << std::ifstream(out() / "fidelity.json").rdbuf();
  EXPECT_NE(json.str().find("\"compared_fraction\": 1"), std::string::npos) << json.str();
}
