// A Term is one force on a fixed local stencil (a segment, three nodes of a yarn,
// a crossing, a triangle): energy, force and Jacobians over its stencil only
// (docs/design.md §3.2). Shared code (assembly.h) gathers local states,
// calls the term per element and scatters into global vectors and matrices.
#pragma once
#include <array>
#include <memory>
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

// Global state a term may read in prepare(), before its elements are evaluated:
// the auxiliary quantities of this evaluation (contact normal forces) and the
// force already assembled from the other terms, which friction needs as F_u
// (docs/models.md §3.7.1). Terms copy what they need: they keep no reference
// to it (docs/design.md §3.4).
struct EvalContext {
  double t = 0.0;
  const Vec* q = nullptr;
  const Vec* v = nullptr;
  const Vec* force_so_far = nullptr;  // only for terms with stage() == 1
  // Contact normal force F_n per crossing node id [N] (docs/models.md §3.6);
  // empty when the model computes none (then F_n = 0).
  std::span<const double> normal_force = {};
};

class Term {
 public:
  virtual ~Term() = default;
  // An independent copy, history (friction anchors) and frozen inputs included;
  // models clone their terms for concurrent use (docs/design.md §3.4).
  virtual std::unique_ptr<Term> clone() const = 0;
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
  // Whether an integrator's step matrix takes this term's stiffness projected
  // to the positive semi-definite part of −K_e (project_step_stiffness,
  // docs/models.md §3.11.2): only the assembly of a step matrix does it
  // (AssemblyRequest::step, kStepStiffness); the force and every other ∂f/∂q
  // (finite-difference checks, sensitivities, equilibria) stay exact. A term
  // that says true has a symmetric K_e.
  virtual bool projects_step_stiffness() const { return false; }
  // IMEX split (arkode-imex): true for non-stiff external forces (gravity,
  // wind) that an additive Runge–Kutta method treats explicitly.
  virtual bool imex_explicit() const { return false; }

  // Called once per model evaluation before any element, serially: the one
  // place a term freezes inputs for its elements (docs/design.md §3.4).
  virtual void prepare(const EvalContext&) {}
  // Called after every accepted time step (history such as friction anchors).
  virtual void accept_step(const EvalContext&, double /*h*/) {}

  // Admissible states (docs/design.md §3.6): a term that keeps nodes out of a
  // region (obstacle contact) says so, and gives the largest fraction α ∈ [0, 1]
  // of the straight move from the state `from` to `to` (positions linear in α,
  // time from from.t to to.t) that stays admissible; 1: all of it.
  virtual bool constrains_steps() const { return false; }
  virtual double admissible_fraction(const EvalContext& /*from*/, const EvalContext& /*to*/) const { return 1.0; }

  // Element energy (conservative terms only), from local q.
  virtual double energy(int e, const double* q) const = 0;
  // Element force and requested Jacobians, from local q and v. Must be
  // thread-safe for different e (no writes to shared state).
  virtual void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const = 0;
  // Element kinetic energy ½ v_eᵀ M_e(q) v_e [J] (terms that provide mass).
  // The default forms M_e with evaluate(); a term with a closed form gives it.
  virtual double kinetic_energy(int e, const double* q, const double* v) const;

  // Material parameters the force depends on, named by their scene keys
  // (e.g. "fem.warp_stretch_N_per_m"), and ∂f/∂p of one element for the k-th
  // of them (n values, added into dfdp; same thread-safety as evaluate()).
  // Calibration differentiates equilibria through these (docs/calibration.md §3).
  virtual std::vector<std::string> parameter_keys() const { return {}; }
  virtual void parameter_derivative(int /*e*/, int /*k*/, const double* /*q*/, const double* /*v*/,
                                    double* /*dfdp*/) const {}
  // ∂M/∂p of one element (n×n, column-major, added into dmdp) for terms that
  // provide mass; forward sensitivities need it for density (docs/models.md §9.2).
  virtual void mass_parameter_derivative(int /*e*/, int /*k*/, const double* /*q*/, double* /*dmdp*/) const {}
  // A term whose mass block depends on q offers its derivative through the
  // separate capability PositionDependentMass below.

  // Terms that read frozen inputs (F_n, F_u) offer their derivatives through a
  // separate capability of the yarn model: models/yarn/frozen_input_reader.h.
};

// A capability of the mass terms whose block depends on q (the yarn models'
// segment inertia with sliding coordinates, docs/models.md §3.1.1): such a term
// derives from this interface besides Term, and the assembly asks for it with
// position_dependent_mass(term) where forward sensitivities need ((∂M/∂q)·dq)·w
// (Model::mass_directional_product, docs/models.md §9.2). Every other mass
// block is constant in q.
class PositionDependentMass {
 public:
  virtual ~PositionDependentMass() = default;
  // Directional derivative of element e's mass block, (∂M/∂q)·dq (n×n,
  // column-major, added into dm), at local q.
  virtual void mass_directional_derivative(int e, const double* q, const double* dq, double* dm) const = 0;
};

// The term's PositionDependentMass capability; null for a term whose mass (if
// any) does not depend on q.
inline const PositionDependentMass* position_dependent_mass(const Term& term) {
  return dynamic_cast<const PositionDependentMass*>(&term);
}

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

// A term whose every element is proportional to one scene parameter p:
// f_e = p·g_e(q, v) and M_e = p·m_e(q) (stretch ∝ Y, bending ∝ B, shear ∝ S,
// inertia and gravity ∝ ρ), so ∂f_e/∂p = f_e/p and ∂M_e/∂p = M_e/p
// (docs/models.md §9.1). The model names each element's parameter with tag_last().
template <int N>
class ProportionalParameterTerm : public StencilTerm<N> {
 public:
  // The element added last is proportional to the parameter `key` of value
  // `value` (> 0; a zero parameter leaves the element untagged: not differentiable).
  void tag_last(const std::string& key, double value) {
    element_key_.resize(this->stencils_.size(), -1);
    if (!(value > 0.0) || element_key_.empty()) return;
    int k = 0;
    while (k < static_cast<int>(keys_.size()) && keys_[k] != key) ++k;
    if (k == static_cast<int>(keys_.size())) {
      keys_.push_back(key);
      values_.push_back(value);
    }
    element_key_.back() = k;
  }
  std::vector<std::string> parameter_keys() const override { return keys_; }
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override {
    if (!tagged(e, k)) return;
    typename StencilTerm<N>::LVec f = StencilTerm<N>::LVec::Zero();
    this->evaluate(e, q, v, ElementOutput{f.data()});
    for (int a = 0; a < N; ++a) dfdp[a] += f[a] / values_[k];
  }
  void mass_parameter_derivative(int e, int k, const double* q, double* dmdp) const override {
    if (!this->provides_mass() || !tagged(e, k)) return;
    typename StencilTerm<N>::LVec f = StencilTerm<N>::LVec::Zero(), v = f;
    typename StencilTerm<N>::LMat m = StencilTerm<N>::LMat::Zero();
    this->evaluate(e, q, v.data(), ElementOutput{f.data(), nullptr, nullptr, m.data()});
    for (int a = 0; a < N * N; ++a) dmdp[a] += m.data()[a] / values_[k];
  }

 private:
  bool tagged(int e, int k) const { return e < static_cast<int>(element_key_.size()) && element_key_[e] == k; }
  std::vector<std::string> keys_;
  std::vector<double> values_;
  std::vector<int> element_key_;  // per element: index into keys_, −1 untagged
};

}  // namespace wl
