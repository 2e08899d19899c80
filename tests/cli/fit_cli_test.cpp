// `weavelab fit` end to end: a run of a small scene fitted back from a wrong
// start, and bad input rejected with exit 2 and nothing written.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/support/cli_runner.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

const char* kScene = R"(
[cloth]
warps = 5
wefts = 5
[pose]
kind = "upright"
[[handles]]
node = [0, 0]
[[handles]]
node = [4, 0]
[time]
duration_s = 0.02
dt_s = 0.001
output_interval_s = 0.01
integrator = "be-newton"
)";

class FitCli : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = dir_.path / "small.toml";
    std::ofstream(scene_) << kScene;
    const auto r = test::run_cli("run '" + scene_.string() + "' --quiet --out '" + target().string() + "'", dir_.path);
    ASSERT_EQ(r.code, 0) << r.output;
  }
  fs::path target() const { return dir_.path / "target"; }
  test::CliResult fit(const std::string& args, const fs::path& out) {
    return test::run_cli("fit '" + scene_.string() + "' --target '" + target().string() + "' --quiet --out '" +
                             out.string() + "' " + args,
                         dir_.path);
  }
  test::TestFolder dir_;
  fs::path scene_;
};

TEST_F(FitCli, RecoversTheShearModulusOfItsOwnRun) {
  const fs::path out = dir_.path / "fit";
  const auto r = fit("--free contact.shear_modulus_Pa --start contact.shear_modulus_Pa=1500", out);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* file : {"fit.json", "convergence.csv", "frames.csv"}) EXPECT_TRUE(fs::exists(out / file)) << file;
  std::stringstream json;
  json << std::ifstream(out / "fit.json").rdbuf();
  for (const char* field : {"\"parameters\"", "\"key\": \"contact.shear_modulus_Pa\"", "\"start\": 1500",
                            "\"std_error\"", "\"correlation\"", "\"simulations\"", "\"cpu_s\"", "\"git_revision\""})
    EXPECT_NE(json.str().find(field), std::string::npos) << field << "\n" << json.str();
  EXPECT_NE(r.output.find("contact.shear_modulus_Pa = 1000"), std::string::npos) << r.output;  // the scene default
}

TEST_F(FitCli, BadInputIsExit2AndWritesNothing) {
  const fs::path out = dir_.path / "never";
  const struct {
    std::string args, says;
  } cases[] = {
      {"--free contact.no_such_key", "unknown parameter key 'contact.no_such_key'"},
      {"--free fem.shear_N_per_m", "does not depend on it"},
      {"--free contact.shear_modulus_Pa --frames 9", "--frames"},
      {"--free contact.shear_modulus_Pa --start contact.shear_modulus_Pa=-3", "--start"},
      {"--free contact.shear_modulus_Pa --start contact.friction_coefficient=0.3", "not among the fitted keys"},
      {"--free contact.shear_modulus_Pa --integrator ida", "offers no parameter sensitivities"},
      {"--free contact.shear_modulus_Pa --model fem", "does not depend on it"},
  };
  for (const auto& c : cases) {
    const auto r = fit(c.args, out);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  const auto r = test::run_cli("fit '" + scene_.string() + "' --target '" + (dir_.path / "nothing").string() +
                                   "' --free contact.shear_modulus_Pa --out '" + out.string() + "'",
                               dir_.path);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("nothing"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace wl
