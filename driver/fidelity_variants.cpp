#include "driver/fidelity_variants.h"

#include <stdexcept>

#include "driver/calibrate.h"
#include "models/fem/knit_contact_mesh.h"
#include "models/model_factory.h"

namespace wl {
namespace {

// Whether the continuum's grid takes a stride k: k divides wefts − 1 and warps − 1 (a knit: its
// contact grid's spacings) and every pin and handle lies on the lattice (the scene rule of
// fem.stride, models/scene/scene.cpp).
bool stride_fits(const Scene& s, int k) {
  if (s.knit) return knit_stride_fits(s, k);
  return (s.wefts - 1) % k == 0 && (s.warps - 1) % k == 0 && boundary_on_lattice(s, k);
}

}  // namespace

const std::vector<std::string>& fidelity_variant_names() {
  static const std::vector<std::string> names{"full",
                                              "no_friction",
                                              "no_parallel_contact",
                                              "linear_shear",
                                              "frozen_sliding",
                                              "fem_s1",
                                              "fem_s2",
                                              "fem_s3",
                                              "fem_s4",
                                              "fem_first_guess",
                                              "scene_step",
                                              "half_step",
                                              "quarter_step",
                                              "sdirk2_rtol_1e-3"};
  return names;
}

VariantScene variant_scene(const Scene& scene, const std::string& name, const std::optional<FemMaterial>& calibrated) {
  VariantScene v{scene, yarn_level_model(scene), "", ""};
  Scene& s = v.scene;
  if (name == "full") return v;
  // A knit has no friction, parallel contact or shear term (docs/models.md §11.4).
  if (s.knit && (name == "no_friction" || name == "no_parallel_contact" || name == "linear_shear")) {
    v.same_as_full = "a knit has no friction, parallel contact or shear term (docs/models.md §11.4)";
    return v;
  }
  if (name == "no_friction") {
    // The yarn model builds friction only on sliding coordinates (docs/models.md §3.7).
    if (!(s.terms.friction && s.sliding)) v.same_as_full = "the scene has no friction (off, or sliding frozen)";
    s.terms.friction = false;
    return v;
  }
  if (name == "no_parallel_contact") {
    if (!(s.terms.parallel_contact && s.sliding))
      v.same_as_full = "the scene has no parallel contact (off, or sliding frozen)";
    s.terms.parallel_contact = false;
    return v;
  }
  if (name == "linear_shear") {
    if (!(s.terms.shear && s.contact.shear_model == ContactParams::ShearModel::gong))
      v.same_as_full = "the scene has no shear lock (shear off, or already Cirio's linear shear)";
    s.contact.shear_model = ContactParams::ShearModel::cirio;
    return v;
  }
  if (name == "scene_step" || name == "half_step" || name == "quarter_step" || name == "sdirk2_rtol_1e-3") {
    v.time_rung = true;
    if (name == "sdirk2_rtol_1e-3") {
      s.integrator = "sdirk2";
      s.adaptive = true;
      s.rtol = 1e-3;
      s.atol = 1e-6;
    } else if (name != "scene_step") {
      if (s.adaptive) v.impossible = "the scene's integrator runs under error control, without a fixed step";
      s.dt_s /= name == "half_step" ? 2.0 : 4.0;
    }
    return v;
  }
  if (name == "frozen_sliding") {
    if (!s.sliding) v.same_as_full = "sliding is already frozen in the scene";
    s.sliding = false;
    return v;
  }
  const bool first_guess = name == "fem_first_guess";
  int stride = 1;
  if (name == "fem_s2") stride = 2;
  if (name == "fem_s3") stride = 3;
  if (name == "fem_s4") stride = 4;
  if (!first_guess && name != "fem_s1" && stride == 1) {
    std::string known;
    for (const std::string& n : fidelity_variant_names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown variant '" + name + "', expected one of " + known);
  }
  v.model = "fem";
  s.fem.mesh_file.clear();
  s.fem.stride = stride;
  if (!stride_fits(scene, stride))
    v.impossible = "stride " + std::to_string(stride) +
                   (scene.knit ? " does not fit the knit's contact grid (it must divide 2·wales − 1, odd for every "
                                 "knit, and courses, and hit every pin and handle)"
                               : " does not fit the grid (it must divide wefts − 1 and warps − 1 and hit every pin "
                                 "and handle)");
  if (scene.knit && scene.yarn_viscosity_Pa_s > 0)
    v.impossible = "a knit's continuum has no yarn damping (damping.yarn_viscosity_Pa_s > 0, docs/models.md §11.9)";
  if (first_guess) {
    if (scene.knit) {
      v.impossible = "nothing derives a knit's continuum from its yarn (docs/models.md §11.9)";
      return v;
    }
    v.scene = with_material(s, default_fem_material(scene), false);
    return v;
  }
  if (!calibrated) {
    v.impossible =
        "no calibrated parameters: give --fem-params FILE (written by `weavelab calibrate`) or a scene "
        "with [fem] parameter_file";
    return v;
  }
  v.scene = with_material(s, *calibrated, s.fem.border_strip);
  return v;
}

}  // namespace wl
