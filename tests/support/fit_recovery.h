// Synthetic recovery, the calibration tests' check of a fit: the continuum's own curves at known
// parameters, fitted from another start (one start), must give those parameters back.
#pragma once
#include <gtest/gtest.h>

#include <vector>

#include "calibration/fit.h"
#include "calibration/virtual_tests.h"
#include "models/fem/fem_material.h"
#include "models/scene/scene.h"

namespace wl::test {

// An n × n material-test patch of the hanging-cloth fabric.
inline Scene hanging_wind_patch(int n) {
  return material_test_scene(load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml"), n);
}

// The responses of `truth` at each test's ladder (every rung must converge).
inline std::vector<FitCurve> synthetic_curves(const Scene& patch, const FemMaterial& truth,
                                              const std::vector<TestSpec>& tests) {
  std::vector<FitCurve> curves;
  for (const TestSpec& t : tests) {
    FitCurve c{t, {}};
    for (const ResponsePoint& p : run_fem_test(patch, truth, t).points) c.target.push_back(p.response);
    EXPECT_EQ(c.target.size(), t.ladder.size()) << test_name(t);
    curves.push_back(c);
  }
  return curves;
}

// Fits `curves` from `start`: converged, `parameters` free ones, each within `rtol` of `truth`.
inline void expect_fit_recovers(const Scene& patch, const std::vector<FitCurve>& curves, const FemMaterial& truth,
                                const FemMaterial& start, size_t parameters, double rtol) {
  const ContinuumTest continuum = [&](const FemMaterial& m, const TestSpec& t, const std::vector<std::string>& keys) {
    return run_fem_test(patch, m, t, keys);
  };
  FitOptions opt;
  opt.starts = 1;
  const FitResult r = fit_continuum(curves, start, continuum, opt);
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_EQ(r.parameters.size(), parameters);
  FemMaterial fitted = r.material, expected = truth;
  for (const FittedParameter& p : r.parameters)
    EXPECT_NEAR(material_value(fitted, p.key) / material_value(expected, p.key), 1.0, rtol) << p.key;
}

}  // namespace wl::test
