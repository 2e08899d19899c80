// The differentiable material parameters of a scene, read and written by their
// scene keys (docs/models.md §9.1):
//   yarn_types.<type>.density_kg_per_m | stretch_modulus_Pa | bending_modulus_Pa
//   knit.roll_stiffness_N | stitch_length_stiffness_N | compression_stiffness_N_per_m  (knit scenes)
//   contact.shear_modulus_Pa, contact.friction_coefficient
//   fem.<[fem] key>  (the continuum's material, models/fem/fem_material.h)
// Whether a model built from the scene differentiates a key is the model's
// answer (Model::parameter_keys()); this file only names and moves values.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "models/scene/scene.h"

namespace wl {

class ParameterKeyError : public std::invalid_argument {  // bad input: exit 2
 public:
  using std::invalid_argument::invalid_argument;
};

// Every key above that exists in `scene` (its yarn types by name).
std::vector<std::string> scene_parameter_keys(const Scene& scene);
// The value the scene gives the key (a [fem] key not set in the scene: the
// continuum's computed value); throws ParameterKeyError for an unknown key.
double scene_parameter(const Scene& scene, const std::string& key);
// Sets the key's value in the scene; throws ParameterKeyError for an unknown key.
void set_scene_parameter(Scene& scene, const std::string& key, double value);

}  // namespace wl
