#include "calibration/first_guess.h"

#include "calibration/stretch_law_guess.h"

namespace wl {

FemMaterial knit_first_guess(const Scene& test_scene, const std::vector<FitCurve>& curves) {
  FemMaterial m = default_fem_material(test_scene);
  auto secant = [&](TestKind kind) {
    for (const FitCurve& c : curves)
      if (c.test.kind == kind && !c.test.ladder.empty() && c.target[0] > 0) return c.target[0] / c.test.ladder[0];
    return 0.0;
  };
  auto set = [](double& key, double value) {
    if (value > 0) key = value;
  };
  set(m.warp_stretch_N_per_m, 0.5 * secant(TestKind::biaxial));
  set(m.weft_stretch_N_per_m, 0.5 * secant(TestKind::biaxial));
  set(m.warp_stretch_N_per_m, secant(TestKind::uniaxial_warp));
  set(m.weft_stretch_N_per_m, secant(TestKind::uniaxial_weft));
  set(m.shear_N_per_m, secant(TestKind::shear));
  set(m.warp_bending_N_m, secant(TestKind::bending_warp));
  set(m.weft_bending_N_m, secant(TestKind::bending_weft));
  return m;
}

FemMaterial continuum_first_guess(const Scene& scene, const Scene& test_scene, const std::vector<FitCurve>& curves,
                                  const FirstGuessOptions& o) {
  FemMaterial guess = scene.knit ? knit_first_guess(test_scene, curves) : fem_material(scene);
  if (o.diagonal_bending && guess.diagonal_bending_N_m <= 0)  // start where the law is off: the mean
    guess.diagonal_bending_N_m = 0.5 * (guess.warp_bending_N_m + guess.weft_bending_N_m);
  stretch_law_first_guess(curves, o.stretch_coupling, o.stretch_stiffening, guess);
  if (!o.shear_knots_rad.empty()) guess.shear_knots_rad = o.shear_knots_rad;
  for (size_t i = 0; i < guess.shear_knots_rad.size(); ++i)  // start where the law is linear: k_i = k_sh
    if (guess.shear_knot_N_per_m[i] <= 0) guess.shear_knot_N_per_m[i] = guess.shear_N_per_m;
  return guess;
}

}  // namespace wl
