#include "calibration/scene_parameters.h"

#include <type_traits>

#include "calibration/fit.h"
#include "models/fem/fem_material.h"
#include "models/knit/knit_model.h"
#include "models/scene/parameter_keys.h"

namespace wl {
namespace {

constexpr const char* kYarnFields[] = {kDensityField, kStretchModulusField, kBendingModulusField};

// The yarn type's field addressed by "yarn_types.<type>.<field>", or null
// (S is Scene or const Scene).
template <class S>
auto* yarn_field(S& scene, const std::string& key) {
  using Field = std::conditional_t<std::is_const_v<S>, const double, double>;
  Field* none = nullptr;
  const std::string prefix = "yarn_types.";
  if (key.rfind(prefix, 0) != 0) return none;
  const size_t dot = key.rfind('.');
  if (dot <= prefix.size()) return none;
  const auto it = scene.yarn_types.find(key.substr(prefix.size(), dot - prefix.size()));
  if (it == scene.yarn_types.end()) return none;
  const std::string field = key.substr(dot + 1);
  if (field == kDensityField) return &it->second.density_kg_per_m;
  if (field == kStretchModulusField) return &it->second.stretch_modulus_Pa;
  if (field == kBendingModulusField) return &it->second.bending_modulus_Pa;
  return none;
}

template <class S>
auto* fem_field(S& scene, const std::string& key) {
  auto& f = scene.fem;
  if (key == kFemArealDensity) return &f.areal_density_kg_per_m2;
  if (key == kFemWarpStretch) return &f.warp_stretch_N_per_m;
  if (key == kFemWeftStretch) return &f.weft_stretch_N_per_m;
  if (key == kFemShear) return &f.shear_N_per_m;
  if (key == kFemShearLockAngle) return &f.shear_lock_angle_rad;
  if (key == kFemShearLockExponent) return &f.shear_lock_exponent;
  if (key == kFemWarpBending) return &f.warp_bending_N_m;
  if (key == kFemWeftBending) return &f.weft_bending_N_m;
  if (key == kFemDiagonalBending) return &f.diagonal_bending_N_m;
  if (key == kFemStretchCoupling) return &f.stretch_coupling_N_per_m;
  if (key == kFemWarpStretchQuartic) return &f.warp_stretch_quartic_N_per_m;
  if (key == kFemWeftStretchQuartic) return &f.weft_stretch_quartic_N_per_m;
  if (key == kFemArealStretchQuartic) return &f.areal_stretch_quartic_N_per_m;
  for (int i = 0; i < FemSettings::kMaxShearKnots; ++i)
    if (key == "fem." + shear_knot_key(i)) return &f.shear_knot_N_per_m[i];
  return decltype(&f.shear_N_per_m){nullptr};
}

// The knit's stiffness addressed by "knit.<[knit] key>" in a knit scene, or null.
template <class S>
auto* knit_field(S& scene, const std::string& key) {
  using Field = std::conditional_t<std::is_const_v<S>, const double, double>;
  Field* none = nullptr;
  if (!scene.knit) return none;
  auto& k = *scene.knit;
  if (key == kRollStiffnessKey) return &k.roll_stiffness_N;
  if (key == kStitchLengthStiffnessKey) return &k.stitch_length_stiffness_N;
  if (key == kCompressionStiffnessKey) return &k.compression_stiffness_N_per_m;
  return none;
}

[[noreturn]] void unknown(const Scene& scene, const std::string& key) {
  std::string known;
  for (const std::string& k : scene_parameter_keys(scene)) known += (known.empty() ? "" : ", ") + k;
  throw ParameterKeyError("unknown parameter key '" + key + "', expected one of " + known);
}

}  // namespace

std::vector<std::string> scene_parameter_keys(const Scene& scene) {
  std::vector<std::string> keys;
  for (const auto& [name, type] : scene.yarn_types)
    for (const char* field : kYarnFields) keys.push_back(yarn_type_key(name, field));
  if (scene.knit)
    for (const char* k : {kRollStiffnessKey, kStitchLengthStiffnessKey, kCompressionStiffnessKey}) keys.push_back(k);
  keys.push_back(kShearModulusKey);
  keys.push_back(kFrictionCoefficientKey);
  for (const std::string& k : fittable_parameters()) keys.push_back("fem." + k);
  keys.push_back(kFemArealDensity);
  return keys;
}

double scene_parameter(const Scene& scene, const std::string& key) {
  if (const double* y = yarn_field(scene, key)) return *y;
  if (const double* k = knit_field(scene, key)) return *k;
  if (key == kShearModulusKey) return scene.contact.shear_modulus_Pa;
  if (key == kFrictionCoefficientKey) return scene.contact.friction_coefficient;
  if (const std::optional<double>* f = fem_field(scene, key)) {
    if (*f) return **f;
    FemMaterial m = fem_material(scene);
    return key == kFemArealDensity ? m.areal_density_kg_per_m2 : material_value(m, key.substr(4));
  }
  unknown(scene, key);
}

void set_scene_parameter(Scene& scene, const std::string& key, double value) {
  if (double* y = yarn_field(scene, key)) *y = value;
  else if (double* k = knit_field(scene, key)) *k = value;
  else if (key == kShearModulusKey) scene.contact.shear_modulus_Pa = value;
  else if (key == kFrictionCoefficientKey) scene.contact.friction_coefficient = value;
  else if (std::optional<double>* f = fem_field(scene, key)) *f = value;
  else unknown(scene, key);
}

}  // namespace wl
