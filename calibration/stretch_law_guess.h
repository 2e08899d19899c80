// First guesses of the stretch law's extras from the yarn-level curves
// (docs/calibration.md §8). A homogeneous patch answers
//   R_warp = k_u ε + (q_u + q_a)ε³,  R_weft likewise,
//   R_biaxial = (k_u + k_v + 2k_c)ε + (q_u + q_v + 16q_a)ε³   (docs/models.md §6.3.1).
#pragma once
#include <vector>

#include "calibration/fit.h"
#include "models/fem/fem_material.h"

namespace wl {

// The cubic part c of a curve: least squares of R = kε + cε³ over its points;
// 0 when the ladder cannot tell the two apart (fewer than two distinct strains).
double cubic_part(const FitCurve& curve);

// With `coupling`: k_c = ½(biaxial − warp − weft secant at the first load), kept
// within (2 %, 90 %) of √(k_u k_v) (a missing uniaxial curve: m's own k). With
// `stiffening`: q from each uniaxial curve (else half the biaxial's), and with all
// three curves q_a from the biaxial's excess, (c_b − c_u − c_v)/14; each at least
// 1 % of k over the largest strain²; a direction no curve informs keeps no quartic
// (the fit does not free it). Only unrotated curves count.
void stretch_law_first_guess(const std::vector<FitCurve>& curves, bool coupling, bool stiffening, FemMaterial& m);

}  // namespace wl
