// The mixed cloth (docs/models.md §12): the yarn level on the scene's [mixed]
// region of crossings, the continuum (the stride-1 grid mesh, vertex v =
// crossing v) on the other cells, one Model. It is the yarn model over the
// region (models/yarn/yarn_region.h: sliding at yarn-interior crossings, yarn
// elements scaled by their yarn share) with the continuum's terms added as
// RegionTerms (their elements with a continuum share, scaled by it). A region
// covering the cloth gives the yarn model, an empty one the continuum.
#pragma once
#include <memory>

#include "models/yarn/yarn_model.h"

namespace wl {

class MixedModel : public YarnModel {
 public:
  // Throws SceneError (located) for a scene the mixed model cannot take: no
  // [mixed] table, [fem] stride ≠ 1 or a mesh file, self-contact,
  // time.exact_contact_jacobian.
  explicit MixedModel(const Scene& scene);
  std::unique_ptr<Model> clone() const override { return std::make_unique<MixedModel>(*this); }
  std::string name() const override { return "mixed"; }
  // Only sliding coordinates make the mass depend on q (docs/models.md §3.1.1).
  bool mass_depends_on_q() const override { return sliding_; }
  // The yarn model's frame with point data "yarn_level" (1 in the region, 0 outside).
  Frame frame(double t, const Vec& q, const Vec& v) const override;
  std::map<std::string, std::string> describe() const override;

 private:
  MixedModel(const Scene& scene, const YarnRegion& region);
  bool sliding_ = false;
  std::string rectangles_;  // the scene's yarn_region, for describe()
};

// The continuum's terms on the mixed cloth's DoFs (the grid over `region`):
// each element with its continuum share (docs/models.md §12.3), the terms without one left out;
// per crossing the mass the continuum lumps on it, and its triangles' edges (§12.7).
ContinuumPart continuum_part(const Scene& scene, const YarnRegion& region);

}  // namespace wl
