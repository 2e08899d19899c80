// The fidelity ladder (docs/design.md §7.5): the scene's model with one
// simplification at a time, each a Scene changed in memory.
//   full                 the yarn model as the scene describes it
//   no_friction          yarn, [terms] friction = false          (docs/models.md §3.7)
//   no_parallel_contact  yarn, [terms] parallel_contact = false  (docs/models.md §3.5)
//   linear_shear         yarn, Gong's shear lock → Cirio's linear shear (docs/models.md §3.4)
//   frozen_sliding       yarn, cloth.sliding = false: 3 DoFs per node (docs/models.md §2.1)
//   fem_s1, fem_s2, fem_s3, fem_s4   continuum on every 1st, 2nd, 3rd, 4th crossing, calibrated parameters (§6)
//   fem_first_guess      continuum on every crossing, parameters derived from the yarns (§6.7)
// and the time rungs, the full yarn model at other time resolutions (§7.11):
//   scene_step           the scene's own integrator and step (1 ms, be-linear, in the published scenes)
//   half_step, quarter_step   the scene's integrator at 1/2 and 1/4 of its step
//   sdirk2_rtol_1e-3     sdirk2 under error control at rtol 1e-3
// On a knit the continuum lies on the contact grid (docs/models.md §11.9): fem_sK where K divides its
// spacings and hits every pin and handle, fem_first_guess never (no first guess from the yarn).
// The model rungs run at the comparison's time steps (driver/time_steps.h),
// the time rungs at their own.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "models/fem/fem_material.h"
#include "models/scene/scene.h"

namespace wl {

// Every variant name, most detailed first.
const std::vector<std::string>& fidelity_variant_names();

struct VariantScene {
  Scene scene;
  std::string model;  // the scene's yarn level (yarn_level_model: "yarn" or "knit") or "fem"
  // Why the variant cannot be built for this scene ("" when it can): a stride
  // that does not fit the grid, calibrated variants without parameters.
  std::string impossible;
  // Why the variant is the scene's own yarn model under another name ("" when
  // it simplifies something), e.g. no_friction where sliding is frozen.
  std::string same_as_full;
  bool time_rung = false;  // runs at its own integrator and step, not at the comparison's time steps
};

// The scene of variant `name`; `calibrated` holds the calibrated continuum
// parameters (nullopt: none given). The continuum variants use the crossing
// grid (fem.mesh_file is dropped). Throws std::invalid_argument for an
// unknown name ("unknown variant 'x', expected one of …").
VariantScene variant_scene(const Scene& scene, const std::string& name, const std::optional<FemMaterial>& calibrated);

}  // namespace wl
