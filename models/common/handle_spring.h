// A zero-rest-length penalty spring holding a point at a target (scene
// handles, docs/models.md §3.10). Model agnostic:
// local stencil x[3] of any point (yarn node or mesh vertex).
//   V = ½ k ‖x − a(t)‖²,  a(t) = a₀ + w·(clamp(t, t_start, t_stop) − t_start)
// The target a(t) moves with the time of the evaluation (prepare) and does
// not depend on any material parameter.
#pragma once
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "models/core/term.h"
#include "models/scene/scene.h"

namespace wl {

// Prescribed motion of a target: velocity w [m/s] from start_s until stop_s.
struct HandleMotion {
  Vec3 velocity = Vec3::Zero();
  double start_s = 0.0;
  double stop_s = std::numeric_limits<double>::infinity();
  // Displacement of the target from its initial position at time t [m].
  Vec3 displacement(double t) const;
};

class HandleSpringTerm : public StencilTerm<3> {
 public:
  // One handle; anchor a₀ in m, stiffness k in N/m (≥ 0); throws
  // std::invalid_argument for a non-finite anchor or velocity, or stop_s ≤ start_s.
  void add(const std::array<int, 3>& stencil, const Vec3& anchor, double k, const HandleMotion& motion = {});
  // The scene's handle, its target starting at `anchor`.
  void add(const std::array<int, 3>& stencil, const Vec3& anchor, const Handle& handle);

  std::string name() const override { return "handles"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<HandleSpringTerm>(*this); }
  void prepare(const EvalContext& ctx) override { t_ = ctx.t; }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // Target of element e at time t [m].
  Vec3 target(int e, double t) const { return anchor_[e] + motion_[e].displacement(t); }

 private:
  std::vector<Vec3> anchor_;
  std::vector<double> k_;
  std::vector<HandleMotion> motion_;
  double t_ = 0.0;  // time of the last evaluation
};

}  // namespace wl
