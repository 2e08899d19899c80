// The Model interface: everything an integrator may know about a simulated
// system (docs/design.md §3.1). Generalized coordinates q and
// velocities v live in contiguous vectors; mass, ∂f/∂q and ∂f/∂v share one
// fixed sparsity pattern; f includes inertial forces where M depends on q.
#pragma once
#include <algorithm>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "models/core/frame.h"
#include "models/core/types.h"

namespace wl {

enum EvalFlags : unsigned {
  kForce = 1u,
  kDfdq = 2u,
  kDfdv = 4u,
  kMass = 8u,
  // IMEX split: restrict force and Jacobians to the explicit (gravity, wind:
  // Term::imex_explicit()) or the implicit (all other) terms. Mass is not
  // split: request it without these bits.
  kExplicitTerms = 16u,
  kImplicitTerms = 32u,
  // ∂f/∂q for an integrator's step (or Newton) matrix: the terms that project
  // their step stiffness (Term::projects_step_stiffness) give it projected.
  kStepStiffness = 64u,
};

struct Evaluation {
  Vec force;          // f(t, q, v), generalized
  SparseMatrix dfdq;  // ∂f/∂q
  SparseMatrix dfdv;  // ∂f/∂v
  SparseMatrix mass;  // M(q)
};

// What Model::evaluate_step forms in one assembly pass (docs/design.md §3.3):
//   A = mass·M + dfdv·∂f/∂v + dfdq·∂f/∂q   (pattern()-shaped),
//   r = f + rhs_dfdq·(∂f/∂q)·w.
// With constant_mass (a model whose M does not depend on q, assembled before)
// A starts from mass·constant_mass's values and the terms' mass blocks are not formed.
struct StepWeights {
  double mass = 1.0, dfdv = 0.0, dfdq = 0.0, rhs_dfdq = 0.0;
  const Vec* w = nullptr;  // required when rhs_dfdq ≠ 0
  const SparseMatrix* constant_mass = nullptr;
};

// What only the yarn-level models offer (the largest node speed over positions
// beside sliding coordinates, the derivative of the friction anchors) is a
// separate capability: models/core/sliding_coordinates.h.
//
// State (docs/design.md §3.4): a model holds its history (friction anchors,
// changed only by accept_step) and the auxiliaries of its last evaluation
// (contact normals, friction's frozen F_u and F_n, changed only by evaluate).
// Every other member is const and reads them. A model is not safe to share
// between threads: give each thread its own clone().
class Model {
 public:
  virtual ~Model() = default;
  // An independent copy with the same history and auxiliaries: evaluating the
  // clone and the original at the same state gives identical results.
  virtual std::unique_ptr<Model> clone() const = 0;
  virtual std::string name() const = 0;
  virtual int num_dofs() const = 0;
  virtual Vec initial_q() const = 0;
  virtual Vec initial_v() const = 0;
  // DoFs held fixed (pinned): the integrators keep their q and v unchanged and
  // remove them from every solve.
  virtual std::span<const int> fixed_dofs() const = 0;
  // Whether M depends on q (then f contains ∂T/∂q − Ṁq̇, docs/models.md §3.1.2).
  virtual bool mass_depends_on_q() const = 0;

  // The terms whose Jacobians make the step matrix M − hD − h²K non-symmetric
  // (docs/design.md §6.3), e.g. inertia, friction, wind; empty: symmetric.
  virtual std::vector<std::string> asymmetric_terms() const = 0;

  // Sparsity shared by mass, dfdq and dfdv (fixed for the model's lifetime).
  virtual const SparseMatrix& pattern() const = 0;
  // Fills what `flags` asks for; matrices keep pattern()'s structure. With
  // kMass alone only M(q) is formed (the force is then not meaningful).
  // Otherwise it first prepares the auxiliaries at (t, q, v), which the
  // members documented as "of the last evaluation" then read.
  virtual void evaluate(double t, const Vec& q, const Vec& v, unsigned flags, Evaluation& out) = 0;
  // The implicit step's matrix `a` and right-hand side `r` at (t, q, v) with
  // the weights `w` (StepWeights); `scratch` is reused between calls and
  // holds the force f afterwards (its matrices are not meaningful). The
  // default evaluates M, ∂f/∂q (kStepStiffness) and ∂f/∂v and combines them (form_step).
  virtual void evaluate_step(double t, const Vec& q, const Vec& v, const StepWeights& w, Evaluation& scratch,
                             SparseMatrix& a, Vec& r);
  // Whether kStepStiffness (and evaluate_step) changes ∂f/∂q: some term
  // projects its step stiffness. Forward sensitivities need the exact one.
  virtual bool projects_step_stiffness() const { return false; }
  // Potential energy of the conservative terms.
  virtual double potential_energy(const Vec& q) const = 0;
  // Kinetic energy ½ vᵀ M(q) v [J]; the default assembles M(q) into `scratch`
  // (reused between calls).
  virtual double kinetic_energy(double t, const Vec& q, const Vec& v, Evaluation& scratch);
  // History update after an accepted step of size h ending at (t, q, v).
  virtual void accept_step(double t, const Vec& q, const Vec& v, double h) = 0;

  // Why the model cannot represent state q (e.g. sliding coordinates that meet),
  // naming the node or yarn; empty when it can. Integrators check every accepted
  // state (Outcome::invalid_state). Only finite values are judged: NaN is check_state's.
  virtual std::string invalid_state(const Vec& q) const { return {}; }

  // Admissible states (docs/design.md §3.6). A model whose states are
  // restricted beyond invalid_state (nodes outside rigid obstacles) declares it
  // here; an integrator that honours it (IntegratorCapabilities::admissible_steps)
  // accepts no step whose move from (t0, q0) to (t1, q1) is not admissible in
  // full, and keeps its Newton iterates inside the fraction, and an integrator
  // that cannot refuses the model (Outcome::not_offered).
  virtual bool constrains_steps() const { return false; }
  // The largest fraction α ∈ [0, 1] of the straight move from q0 at t0 to q1 at
  // t1 that stays admissible; 1 when all of it does.
  virtual double admissible_fraction(double /*t0*/, const Vec& /*q0*/, double /*t1*/, const Vec& /*q1*/) const {
    return 1.0;
  }
  // The rigid obstacles at time t as a surface for the writers (a second
  // series beside the cloth's); empty points when the model has none.
  virtual Frame obstacle_frame(double t) const {
    Frame f;
    f.time = t;
    return f;
  }

  // Output frame for the writers at (t, q, v); friction's sliding state is that
  // of the last evaluation.
  virtual Frame frame(double t, const Vec& q, const Vec& v) const = 0;
  // Material parameters (scene keys) whose force derivative the model provides.
  virtual std::vector<std::string> parameter_keys() const { return {}; }
  // Sets dfdp = ∂f/∂p at (t, q, v) for the parameter `key`; false (dfdp zero)
  // when the force does not depend on it. Auxiliary quantities are those of
  // the last evaluate(), so evaluate at the same state first.
  virtual bool force_parameter_derivative(const std::string& key, double t, const Vec& q, const Vec& v,
                                          Vec& dfdp) const {
    dfdp = Vec::Zero(num_dofs());
    return false;
  }
  // Adds (∂M/∂p)·w for the parameter `key` at q into `out` (sized num_dofs());
  // false when the mass does not depend on it.
  virtual bool mass_parameter_product(const std::string& key, const Vec& q, const Vec& w, Vec& out) const {
    return false;
  }
  // Adds ((∂M/∂q)·dq)·w at q into `out`; only models whose mass depends on q
  // (mass_depends_on_q()) add anything.
  virtual void mass_directional_product(const Vec& q, const Vec& dq, const Vec& w, Vec& out) const {}
  // Short facts for `weavelab info` and the run summary (name -> value).
  virtual std::map<std::string, std::string> describe() const = 0;
};

// Prepares `out` with pattern-shaped matrices and a sized force vector.
void allocate_evaluation(const Model& model, Evaluation& out);
// Largest node speed ‖ẋ‖ [m/s]: over the nodes' positions for a model with
// sliding coordinates (SlidingCoordinates::max_node_speed), otherwise v read as
// consecutive 3-vectors.
double max_node_speed(const Model& model, const Vec& v);
// A and (when r is given) r of StepWeights from an evaluation holding f, ∂f/∂q,
// ∂f/∂v and (unless w.constant_mass is given) M: what Model::evaluate_step
// forms in one pass.
void form_step(const Evaluation& ev, const StepWeights& w, SparseMatrix& a, Vec* r);

}  // namespace wl
