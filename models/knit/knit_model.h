// The yarn-level knit model (docs/models.md §11): contact nodes with a position
// and one sliding coordinate per yarn through them (knit_graph.h), the woven
// model's segment kernels along each yarn's path (stretch, bending with a
// straight rest shape, segment inertia, gravity, damping) and the knit terms
// at every stitch contact of n ≥ 2 yarns (stitch-length penalty per yarn; roll
// and contact compression per pair of yarns, stack_pairs.h).
// The initial state is the relaxed tile of the pattern, tiled (knit_rest_shape.h).
#pragma once
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "models/common/intersection_count.h"
#include "models/common/self_contact.h"
#include "models/core/sliding_coordinates.h"
#include "models/core/term_model.h"
#include "models/knit/compression_pairs.h"
#include "models/knit/knit_graph.h"
#include "models/scene/scene.h"

namespace wl {

// The loops' layout of a knit scene: its courses × wales, or with `tile` the
// pattern's smallest repeating tile, periodic.
KnitLayout knit_layout(const Scene& scene, bool tile);

// The parameter key of the contact compression's stiffness κ (docs/models.md §11.6).
inline constexpr const char* kCompressionStiffnessKey = "knit.compression_stiffness_N_per_m";
// The parameter key of the stitch roll's stiffness k_t (docs/models.md §11.4).
inline constexpr const char* kRollStiffnessKey = "knit.roll_stiffness_N";
// The parameter key of the stitch-length penalty's stiffness k_l (docs/models.md §11.4).
inline constexpr const char* kStitchLengthStiffnessKey = "knit.stitch_length_stiffness_N";
// Pieces of yarn closer than this in the generated geometry are kept apart by
// the contact compression (docs/models.md §11.6): the contact distance 2R plus
// half the smaller loop spacing.
inline double knit_compression_cutoff(const KnitLayout& L, double radius) {
  return 2.0 * radius + 0.5 * std::min(L.wale_spacing, L.course_spacing);
}

class KnitModel : public TermModel, public SlidingCoordinates, public IntersectionCount {
 public:
  // The whole cloth of a knit scene (scene.knit set), at the tiled rest shape.
  explicit KnitModel(const Scene& scene);
  // The pattern's periodic tile at the generated geometry with the terms the
  // rest shape relaxes: stretch, bending and the stitch-length penalty (no
  // roll, inertia, loads or damping; docs/models.md §11.3).
  // `period_scale` scales the tile's period, not its loops (docs/models.md §11.3.1).
  static std::unique_ptr<KnitModel> tile(const Scene& scene, const std::array<double, 2>& period_scale = {1.0, 1.0});

  std::unique_ptr<Model> clone() const override { return std::make_unique<KnitModel>(*this); }
  std::string name() const override { return "knit"; }
  bool mass_depends_on_q() const override { return scene_.sliding; }
  Frame frame(double t, const Vec& q, const Vec& v) const override;
  // SlidingCoordinates: the nodes' positions (no friction anchors: no history).
  double max_node_speed(const Vec& v) const override;
  // A yarn segment whose sliding coordinates meet or cross (Δu ≤ 0).
  std::string invalid_state(const Vec& q) const override;
  std::map<std::string, std::string> describe() const override;
  // IntersectionCount: the pairs of yarn pieces that the contact filter keeps
  // whose capsules overlap (gap d − 2R < 0; docs/models.md §11.10), with or without the contact on.
  std::string intersection_column() const override { return "intersecting_segment_pairs"; }
  long intersecting_pairs(const Vec& q) const override { return capsules_ ? capsules_->overlapping_pairs(q) : 0; }

  const KnitGraph& graph() const { return graph_; }
  // Position of node k in state q, and a coordinate (DoF or constant).
  Vec3 position(const Vec& q, int k) const { return q.segment<3>(graph_.node(k).x_dof); }
  double coordinate(const Vec& q, int index) const {
    return is_dof(index) ? q[index] : constants_[constant_slot(index)];
  }
  // Length of yarn y in state q: the span of its coordinates from its first visit to its last.
  double yarn_length(const Vec& q, int y) const {
    const KnitYarn& yarn = graph_.yarns()[y];
    const KnitVisit &first = yarn.visits.front(), &last = yarn.visits.back();
    return coordinate(q, graph_.node(last.node).coord[last.slot]) -
           coordinate(q, graph_.node(first.node).coord[first.slot]);
  }
  // DoFs a static solve of the periodic tile holds: node 0's position and one
  // coordinate per yarn (rigid translation and sliding a whole yarn along itself).
  std::vector<int> gauge_dofs() const;

 private:
  KnitModel(const Scene& scene, bool tile, const std::array<double, 2>& period_scale = {1.0, 1.0});
  void set_generated_state();
  void apply_rest_shape();
  void apply_pose();
  void add_segment_terms();
  void add_bending();
  void add_stitch_terms();
  void add_compression();
  void add_yarn_contact();
  std::vector<YarnPiece> yarn_pieces() const;
  struct Segment {
    int yarn, k0, k1;  // visits
    Vec3 dx0, dx1;     // image shifts of the two ends
    double du1;        // coordinate shift of the second end
  };

  Scene scene_;
  bool tile_;
  KnitGraph graph_;
  std::vector<Segment> segments_;
  std::vector<std::vector<std::pair<int, int>>> visit_of_;  // per node, per slot: (yarn, visit)
  // The yarn–yarn contact's pairs (open cloth), for the intersection count whether the contact is on or not.
  std::shared_ptr<const SelfContactTerm> capsules_;
};

}  // namespace wl
