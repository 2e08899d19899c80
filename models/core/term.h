// A Term is one force on a fixed local stencil (a segment, three nodes of a yarn,
// a crossing, a triangle): energy, force and Jacobians over its stencil only
// (docs/design.md §3.2). Shared code (assembly.h) gathers local states,
// calls the term per element and scatters into global vectors and matrices.
#pragma once
#include <array>
#include <span>
#include <string>
#include <vector>

#include "models/core/types.h"

namespace wl {

// Where an element writes its results. Matrices are n×n, column-major; a null
// pointer means "not requested". `force` is never null.
struct ElementOutput {
  double* force = nullptr;  // generalized force, n
  double* dfdq = nullptr;   // ∂f/∂q, n×n
  double* dfdv = nullptr;   // ∂f/∂v, n×n (only terms with has_velocity_jacobian())
  double* mass = nullptr;   // mass block, n×n (only terms with provides_mass())
};

// Global state a term may read before its elements are evaluated (auxiliary
// quantities such as contact normal forces, or the force already assembled from
// the other terms, which friction needs as F_u, docs/models.md §3.7.1).
struct EvalContext {
  double t = 0.0;
  const Vec* q = nullptr;
  const Vec* v = nullptr;
  const Vec* force_so_far = nullptr;  // only for terms with stage() == 1
};

class Term {
 public:
  virtual ~Term() = default;
  virtual std::string name() const = 0;
  virtual int stencil_size() const = 0;
  virtual int num_elements() const = 0;
  // Global DoF index per local entry; entries < 0 are constants (types.h).
  virtual std::span<const int> stencil(int e) const = 0;

  virtual bool conservative() const { return true; }            // energy() is meaningful
  virtual bool has_velocity_jacobian() const { return false; }  // writes dfdv
  virtual bool provides_mass() const { return false; }          // writes mass
  // 0: evaluated first; 1: evaluated after the stage-0 force is assembled.
  virtual int stage() const { return 0; }
  // Whether the term's ∂f/∂q and ∂f/∂v keep the step matrix M − hD − h²K
  // symmetric (docs/design.md §6.3): true for a potential's force (K = −∇²E)
  // that reads nothing frozen from the force of stage 0.
  virtual bool symmetric_jacobian() const { return conservative() && !has_velocity_jacobian() && stage() == 0; }
  // IMEX split (arkode-imex): true for non-stiff external forces (gravity,
  // wind) that an additive Runge–Kutta method treats explicitly.
  virtual bool imex_explicit() const { return false; }

  // Called once per model evaluation before any element, serially.
  virtual void prepare(const EvalContext&) {}
  // Called after every accepted time step (history such as friction anchors).
  virtual void accept_step(const EvalContext&, double /*h*/) {}

  // Element energy (conservative terms only), from local q.
  virtual double energy(int e, const double* q) const = 0;
  // Element force and requested Jacobians, from local q and v. Must be
  // thread-safe for different e (no writes to shared state).
  virtual void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const = 0;

  // Material parameters the force depends on, named by their scene keys
  // (e.g. "fem.warp_stretch_N_per_m"), and ∂f/∂p of one element for the k-th
  // of them (n values, added into dfdp; same thread-safety as evaluate()).
  // Calibration differentiates equilibria through these (docs/calibration.md §3).
  virtual std::vector<std::string> parameter_keys() const { return {}; }
  virtual void parameter_derivative(int /*e*/, int /*k*/, const double* /*q*/, const double* /*v*/,
                                    double* /*dfdp*/) const {}
};

// Helper base for terms whose elements all have N local DoFs: stores stencils
// and exposes fixed-size Eigen views so element code reads like the equations.
template <int N>
class StencilTerm : public Term {
 public:
  using LVec = Eigen::Matrix<double, N, 1>;
  using LMat = Eigen::Matrix<double, N, N>;
  using VecMap = Eigen::Map<LVec>;
  using MatMap = Eigen::Map<LMat>;
  using ConstVecMap = Eigen::Map<const LVec>;

  int stencil_size() const override { return N; }
  int num_elements() const override { return static_cast<int>(stencils_.size()); }
  std::span<const int> stencil(int e) const override { return stencils_[e]; }

 protected:
  std::vector<std::array<int, N>> stencils_;
};

}  // namespace wl
