// The start of the continuum fit, from the scene and the yarn-level curves
// (docs/calibration.md §6.7 and §8): the [fem] values a woven scene derives
// from its yarns, or for a knit each stiffness a test informs at that test's
// secant; then the extras the fit is asked to free (45° hinge bending, the
// stretch law's coupling and stiffening, the spline shear law's knots).
#pragma once
#include <vector>

#include "calibration/fit.h"
#include "models/fem/fem_material.h"
#include "models/scene/scene.h"

namespace wl {

// What the fit frees beyond the scene's law (the calibrate options of the same names).
struct FirstGuessOptions {
  bool diagonal_bending = false;        // start at the mean of the warp and weft bending when off
  bool stretch_coupling = false;        // stretch_law_first_guess
  bool stretch_stiffening = false;      // stretch_law_first_guess
  std::vector<double> shear_knots_rad;  // non-empty: the spline shear law, each knot at shear_N_per_m
};

// `scene` is the calibrated scene, `test_scene` its material test patch, `curves`
// the yarn level's responses (a knit's measured from its rest shape).
FemMaterial continuum_first_guess(const Scene& scene, const Scene& test_scene, const std::vector<FitCurve>& curves,
                                  const FirstGuessOptions& options);

// A knit's first guess (docs/calibration.md §8): nothing derives a knit's membrane stiffness
// from its yarn, so each stiffness a test informs starts at that test's secant at its first
// load, R(λ₁)/λ₁ (the biaxial test's shared between warp and weft when no uniaxial test
// informs them); the rest is default_fem_material's.
FemMaterial knit_first_guess(const Scene& test_scene, const std::vector<FitCurve>& curves);

}  // namespace wl
