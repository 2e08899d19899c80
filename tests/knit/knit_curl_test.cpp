// Edge curl of free knit patches (docs/models.md §11.6, README "Knits"): with
// contact compression a stockinette's wale (side) edges roll towards the back
// while garter's stay nearly flat. A short, small version of
// the knits study's curl (experiments/knits/): 8 courses × 10 wales for 40 ms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "driver/run.h"
#include "models/scene/scene.h"

namespace wl {
namespace {

constexpr int kCourses = 8, kWales = 10;

// The mean over the two wale edges of the angle [deg] of (edge column − the
// column three inside) above the cloth's plane (+z the face), as
// experiments/knits/scripts/plot_knits.py measures it.
double wale_edge_curl(const Frame& f) {
  Vec3 sum[kWales];
  int count[kWales] = {};
  for (auto& s : sum) s.setZero();
  for (int k = 0; k < f.points.rows(); ++k) {
    const int c = (k / 2 / 2) % kWales;
    sum[c] += f.points.row(k).transpose();
    ++count[c];
  }
  auto mean = [&](int c) { return Vec3(sum[c] / count[c]); };
  auto angle = [](const Vec3& v) { return std::atan2(v.z(), std::abs(v.x())) * 180.0 / M_PI; };
  return 0.5 * (angle(mean(0) - mean(3)) + angle(mean(kWales - 1) - mean(kWales - 4)));
}

double curl_after_release(const std::string& kind) {
  const Scene s = parse_scene(
      "[cloth]\nspacing_m = 0.002\nradius_m = 0.0002\nsliding = true\n"
      "[cloth.pattern]\nkind = \"" +
          kind + "\"\ncourses = " + std::to_string(kCourses) + "\nwales = " + std::to_string(kWales) +
          "\ncourse_spacing_m = 0.0016\n"
          "[pose]\nkind = \"flat\"\n[gravity]\nacceleration_m_per_s2 = [0, 0, 0]\n"
          "[damping]\nyarn_viscosity_Pa_s = 10.0\n"
          "[time]\nduration_s = 0.04\ndt_s = 0.0005\noutput_interval_s = 0.04\n"
          "integrator = \"be-newton\"\n",
      "knit_curl.toml");
  RunOptions options;
  options.progress = false;
  double curl = NAN;
  options.on_frame = [&](const Frame& f) { curl = wale_edge_curl(f); };
  const RunReport r = run_scene(s, options);
  EXPECT_EQ(r.result.outcome, Outcome::ok) << kind << ": " << r.result.message;
  return curl;
}

TEST(KnitCurl, StockinetteWaleEdgesRollToTheBackGarterStaysFlat) {
  const double stockinette = curl_after_release("stockinette"), garter = curl_after_release("garter");
  std::printf("wale-edge curl at 40 ms: stockinette %.3f deg, garter %.3f deg\n", stockinette, garter);
  EXPECT_LT(stockinette, -1.0);
  EXPECT_GT(garter, -0.2);
  EXPECT_LT(std::abs(garter), 0.5 * std::abs(stockinette));
}

}  // namespace
}  // namespace wl
