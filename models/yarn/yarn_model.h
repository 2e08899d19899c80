// The yarn-level woven model (docs/models.md §2–§3): crossing nodes with position
// and, inside the outer ring, sliding coordinates u (along the warp) and v
// (along the weft). Built from a Scene; only the terms the scene turns on exist.
#pragma once
#include <memory>
#include <optional>

#include "models/common/obstacle_contact.h"
#include "models/core/sliding_coordinates.h"
#include "models/core/term_model.h"
#include "models/scene/scene.h"
#include "models/yarn/contact_chain.h"
#include "models/yarn/contact_normals.h"
#include "models/yarn/woven_grid.h"
#include "models/yarn/yarn_region.h"

namespace wl {

// What a mixed cloth's continuum brings to the yarn level's DoFs (docs/models.md §12): its terms,
// and what the obstacle contact over the crossings needs of it (§12.7).
struct ContinuumPart {
  std::vector<std::unique_ptr<Term>> terms;
  std::vector<double> node_mass;          // per crossing: the mass the continuum lumps on it [kg]
  std::vector<std::array<int, 2>> edges;  // the crossings a continuum triangle's edge joins
};

class YarnModel : public TermModel, public SlidingCoordinates {
 public:
  explicit YarnModel(const Scene& scene);
  std::unique_ptr<Model> clone() const override { return std::make_unique<YarnModel>(*this); }
  std::string name() const override { return "yarn"; }
  bool mass_depends_on_q() const override { return scene_.sliding; }
  Frame frame(double t, const Vec& q, const Vec& v) const override;
  // SlidingCoordinates: the nodes' positions, and the friction anchors' dū/dp below.
  double max_node_speed(const Vec& v) const override;
  // Sliding coordinates of neighbouring crossings that meet or cross (Δu ≤ 0 on
  // a segment, docs/models.md §2.2, §5.10), naming the yarn and the crossings.
  std::string invalid_state(const Vec& q) const override;
  Frame obstacle_frame(double t) const override;
  std::map<std::string, std::string> describe() const override;
  // With time.exact_contact_jacobian, ∂f/∂p includes what passes through F_n and
  // F_u (docs/models.md §3.6.1, §9.1).
  bool force_parameter_derivative(const std::string& key, double t, const Vec& q, const Vec& v,
                                  Vec& dfdp) const override;
  bool exact_contact_jacobian() const { return chain_.has_value(); }
  // With exact_contact_jacobian the readers of F_n (Gong's shear) are asymmetric too.
  std::vector<std::string> asymmetric_terms() const override;
  // dū/dp of Gong's friction anchors over the step (docs/models.md §9.2):
  //   dū/dp += h (dσ/dp u̇ + σ S_u̇),  dσ/dp = σ′ (sign F_u dF_u/dp − μ dF_n/dp − F_n dμ/dp),
  // with dF_u/dp, dF_n/dp total derivatives along (S_q, S_v) (exact with
  // exact_contact_jacobian; without it only σ S_u̇ and the μ term).
  void accept_step_sensitivities(const std::vector<std::string>& keys, const Vec& q, const Vec& v,
                                 const Eigen::MatrixXd& dq_dp, const Eigen::MatrixXd& dv_dp, double h) override;

  const WovenGrid& grid() const { return grid_; }
  // The crossings simulated at yarn level: the whole grid, or a mixed cloth's region.
  const YarnRegion& region() const { return region_; }
  // Position of node (i, j) and its current material coordinates in state q.
  Vec3 position(const Vec& q, int i, int j) const;
  double coordinate(const Vec& q, int index) const;

 protected:
  // The yarn level of a mixed cloth (docs/models.md §12): sliding only at the
  // region's yarn-interior crossings, every element's coefficient times its yarn
  // share (elements of share 0 and terms without elements are not built), and
  // the continuum's terms (on the same DoFs) after the yarn level's, before the
  // obstacles'. A scene with self-contact or exact_contact_jacobian is the caller's to refuse.
  YarnModel(const Scene& scene, const YarnRegion& region, ContinuumPart continuum);

  // The contact normals and F_n at q (docs/models.md §3.6), handed to the terms in ctx.
  void prepare_auxiliary(double t, const Vec& q, const Vec& v, EvalContext& ctx) override;
  // The chain of ∂F_n/∂q and ∂F_u/∂q into the Jacobians (exact_contact_jacobian).
  void after_stage(int stage, const Vec& q, const Vec& v, const AssemblyRequest& req, Evaluation& out) override;
  bool single_pass_step() const override { return !chain_; }

 private:
  struct Segment {
    int a, b;          // node ids
    bool warp;         // along u (warp) or v (weft)
    double share;      // of the cloth it stands for at yarn level (docs/models.md §12.3)
    double ks;         // stretch stiffness of its yarn [N]
    double rho;        // linear density of its yarn [kg/m]
    std::string type;  // its yarn type's name (scene yarn_types)
  };
  struct YarnConstants {              // per warp j or weft i
    std::vector<double> ks, kb, rho;  // k_s = Y·πR² [N], k_b = B·πR² [N·m²], ρ [kg/m]
  };

  // Construction, one step per idea; each add_* builds one term when the scene turns it on.
  void set_rest_state();
  void set_yarn_constants();
  void build_segments();
  void add_inertia();
  void add_stretch();
  void add_gravity();
  void add_bending();
  void add_shear();
  void add_parallel_contact();
  void add_friction();
  void add_wind();
  void add_handles();
  void add_damping();
  void add_pins();
  void add_obstacles(const ContinuumPart& continuum);
  void add_self_contact();

  std::array<int, 8> segment_stencil(const Segment& s) const;
  double cross_section() const;  // πR² [m²]
  const YarnType& yarn_type(const std::string& name) const { return scene_.yarn_types.at(name); }

  // Appends a term the builders made, unless it has no elements.
  void push_term(std::unique_ptr<Term> term);

  Scene scene_;
  YarnRegion region_;
  WovenGrid grid_;
  YarnConstants warp_, weft_;
  std::vector<Segment> segments_;
  std::optional<ContactNormals> normals_;  // only when a term needs F_n
  std::optional<ContactChain> chain_;      // only with exact_contact_jacobian and F_n
  std::vector<std::string> anchor_keys_;   // keys of anchor_dp_'s columns
  Eigen::MatrixXd anchor_dp_;              // dū/dp per friction element (rows) and key
  // ∂F_n/∂p per node for the parameter `key` at the last evaluation (needs chain_).
  std::vector<double> normal_force_parameter_derivative(const std::string& key) const;
  int friction_term_ = -1;                          // index of the friction term in terms_, −1 without friction
  std::vector<int> friction_node_, friction_axis_;  // per friction element: node id, 0 = u / 1 = v
  ObstacleContact obstacles_;                       // rigid obstacles of the scene (docs/models.md §3.11)
};

}  // namespace wl
