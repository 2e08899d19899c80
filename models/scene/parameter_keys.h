// Scene keys of the material parameters the models differentiate
// (Term::parameter_keys(), docs/models.md §9.1). The continuum's keys are
// "fem." + its [fem] key (models/fem/fem_material.h).
#pragma once
#include <string>

namespace wl {

inline constexpr const char* kShearModulusKey = "contact.shear_modulus_Pa";
inline constexpr const char* kFrictionCoefficientKey = "contact.friction_coefficient";
// Fields of a yarn type that are differentiable parameters.
inline constexpr const char* kDensityField = "density_kg_per_m";
inline constexpr const char* kStretchModulusField = "stretch_modulus_Pa";
inline constexpr const char* kBendingModulusField = "bending_modulus_Pa";

// "yarn_types.<type>.<field>"
inline std::string yarn_type_key(const std::string& type, const std::string& field) {
  return "yarn_types." + type + "." + field;
}

}  // namespace wl
