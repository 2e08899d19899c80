// Material parameters of the continuum model (docs/models.md §6.7). Sources, later
// overriding earlier:
//   1. defaults derived from the yarn parameters (a first guess only, to be
//      replaced by calibration):
//        warp_stretch_N_per_m = k_s/L  (k_s = Y·πR², mean over the warp yarns)
//        weft_stretch_N_per_m = k_s/L  (mean over the weft yarns)
//        shear_N_per_m        = S·πR²/L (contact.shear_modulus_Pa; small-angle
//                               match of the yarn V = ½k_sh L(φ−π/2)² per crossing)
//        shear_lock_angle_rad = π/2 − 2·arcsin(R/L)  (the shear angle where the
//                               yarn model locks, docs/models.md §3.4.3 φ_l; no locking
//                               when R/L ≥ 1/√2)
//        shear_lock_exponent  = contact.lock_exponent (c)
//        warp_bending_N_m     = k_b/L  (k_b = B·πR², mean over warps), weft likewise
//        diagonal_bending_N_m = absent (0): the 45° hinges bend with the mean of
//                               warp and weft; > 0 their own stiffness
//                               (terms/hinge_bending.h, docs/models.md §6.5.1)
//        stretch_coupling_N_per_m, warp_stretch_quartic_N_per_m,
//        weft_stretch_quartic_N_per_m, areal_stretch_quartic_N_per_m
//                             = absent (0): the linear stretch; > 0 the
//                               warp–weft coupling k_c (k_c² < k_u·k_v) and the
//                               quartic stiffening (docs/models.md §6.3.1)
//        areal_density_kg_per_m2 = (ρ_warp + ρ_weft)/L  (means over yarns), so that
//                               both models carry the same mass per area (up to
//                               the yarn ends at the border);
//   2. the parameter file scene.fem.parameter_file, if given (calibrated values);
//   3. values given explicitly in the scene's [fem] table (Scene::fem), so a
//      scene can override single calibrated values (experiments/scenes/README.md:
//      "an absent value is computed, or taken from the parameter file").
//
// Parameter file format (TOML, written by calibration): top-level keys equal to
// the [fem] key names above (and shear_knot<i>_N_per_m for the knots of the
// scene's spline shear law), each a number > 0, any subset, e.g.
//   warp_stretch_N_per_m = 612.5
//   shear_N_per_m = 0.8
// plus an optional free-form table [provenance] (ignored). Any other key, or a
// value that is not a number > 0, is an error "<file>:<line>: key '<key>': got
// <value>, expected <what>".
#pragma once
#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "models/fem/terms/warp_weft_stretch.h"
#include "models/scene/scene.h"

namespace wl {

struct FemMaterial {
  double areal_density_kg_per_m2 = 0.0;
  double warp_stretch_N_per_m = 0.0, weft_stretch_N_per_m = 0.0;
  double shear_N_per_m = 0.0;
  double shear_lock_angle_rad = 0.0;  // 0: no locking
  double shear_lock_exponent = 0.0;   // ≤ 0: no locking
  double warp_bending_N_m = 0.0, weft_bending_N_m = 0.0;
  double diagonal_bending_N_m = 0.0;  // ≤ 0: off (45° hinges take the mean of warp and weft)
  // Stretch law (docs/models.md §6.3.1), each 0 = off: coupling k_c, quartic stiffening q_u, q_v, q_a.
  double stretch_coupling_N_per_m = 0.0;
  double warp_stretch_quartic_N_per_m = 0.0, weft_stretch_quartic_N_per_m = 0.0, areal_stretch_quartic_N_per_m = 0.0;
  std::string stretch_coupling_source;  // "<file>:<line>" the coupling was read from (for errors)
  // Shear law (docs/models.md §6.4.1): empty = linear then lock; else the spline law's knot angles
  // γ_1 < … < γ_n (from [fem] shear_knots_rad) and the tangent stiffness at each (≤ 0: shear_N_per_m).
  std::vector<double> shear_knots_rad;
  std::array<double, FemSettings::kMaxShearKnots> shear_knot_N_per_m{};
};

// Every numeric parameter of the continuum by its [fem] key (without "fem."), in the order of the
// parameter file, areal density first; shared by the parameter file and the fit.
struct FemParameterKey {
  std::string name;
  std::string expected;  // for error messages
  double& (*value)(FemMaterial&);
};
const std::vector<FemParameterKey>& fem_parameter_keys();

// Scene keys of the material parameters, as terms name them in
// Term::parameter_keys() ("fem." + the [fem] key).
inline constexpr const char* kFemWarpStretch = "fem.warp_stretch_N_per_m";
inline constexpr const char* kFemWeftStretch = "fem.weft_stretch_N_per_m";
inline constexpr const char* kFemShear = "fem.shear_N_per_m";
inline constexpr const char* kFemShearLockAngle = "fem.shear_lock_angle_rad";
inline constexpr const char* kFemShearLockExponent = "fem.shear_lock_exponent";
inline constexpr const char* kFemWarpBending = "fem.warp_bending_N_m";
inline constexpr const char* kFemWeftBending = "fem.weft_bending_N_m";
inline constexpr const char* kFemDiagonalBending = "fem.diagonal_bending_N_m";
inline constexpr const char* kFemStretchCoupling = "fem.stretch_coupling_N_per_m";
inline constexpr const char* kFemWarpStretchQuartic = "fem.warp_stretch_quartic_N_per_m";
inline constexpr const char* kFemWeftStretchQuartic = "fem.weft_stretch_quartic_N_per_m";
inline constexpr const char* kFemArealStretchQuartic = "fem.areal_stretch_quartic_N_per_m";
inline constexpr const char* kFemArealDensity = "fem.areal_density_kg_per_m2";
// The spline shear law's knot values: "fem." + shear_knot_key(i).

class FemParameterError : public std::invalid_argument {  // bad input: exit 2
 public:
  using std::invalid_argument::invalid_argument;
};

// The stretch law's parameters; the coupling is admissible when k_c² < k_u·k_v (convex in the strains).
StretchLaw stretch_law(const FemMaterial& m);
bool stretch_law_admissible(const FemMaterial& m);

// Step 1 alone.
FemMaterial default_fem_material(const Scene& scene);
// Overrides `base` with the values present in a parameter file; throws FemParameterError.
FemMaterial read_fem_parameter_file(const std::string& path, FemMaterial base);
FemMaterial parse_fem_parameters(const std::string& toml_text, const std::string& source_name, FemMaterial base);
// Writes all values in the parameter-file format (atomic: temporary name, then rename).
// `provenance`: (key, text) pairs written as strings into the [provenance] table.
void write_fem_parameter_file(const std::string& path, const FemMaterial& m,
                              const std::vector<std::pair<std::string, std::string>>& provenance = {});
// Steps 1–3.
FemMaterial fem_material(const Scene& scene);

}  // namespace wl
