// The yarn-level woven model (docs/models.md §2–§3): crossing nodes with position
// and, inside the outer ring, sliding coordinates u (along the warp) and v
// (along the weft). Built from a Scene; only the terms the scene turns on exist.
#pragma once
#include <memory>

#include "models/core/term_model.h"
#include "models/scene/scene.h"
#include "models/yarn/contact_normals.h"
#include "models/yarn/woven_grid.h"

namespace wl {

class FrictionTerm;

class YarnModel : public TermModel {
 public:
  explicit YarnModel(const Scene& scene);
  std::string name() const override { return "yarn"; }
  bool mass_depends_on_q() const override { return scene_.sliding; }
  Frame frame(double t, const Vec& q, const Vec& v) override;
  double max_node_speed(const Vec& v) const override;
  // Sliding coordinates of neighbouring crossings that meet or cross (Δu ≤ 0 on
  // a segment, docs/models.md §2.2, §5.10), naming the yarn and the crossings.
  std::string invalid_state(const Vec& q) const override;
  std::map<std::string, std::string> describe() const override;

  const WovenGrid& grid() const { return grid_; }
  // Position of node (i, j) and its current material coordinates in state q.
  Vec3 position(const Vec& q, int i, int j) const;
  double coordinate(const Vec& q, int index) const;

 protected:
  void update_auxiliary(double t, const Vec& q, const Vec& v) override;

 private:
  struct Segment {
    int a, b;          // node ids
    bool warp;         // along u (warp) or v (weft)
    double ks;         // stretch stiffness of its yarn [N]
    std::string type;  // its yarn type's name (scene yarn_types)
  };
  std::array<int, 8> segment_stencil(const Segment& s) const;

  Scene scene_;
  WovenGrid grid_;
  std::vector<Segment> segments_;
  std::unique_ptr<ContactNormals> normals_;  // only when a term needs F_n
  const FrictionTerm* friction_ = nullptr;
  std::vector<int> friction_node_, friction_axis_;  // per friction element: node id, 0 = u / 1 = v
};

}  // namespace wl
