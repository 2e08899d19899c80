// The one generic finite-difference checker (docs/design.md §10):
// central differences of a term's element at given local states and at seeded
// random perturbations of them. Checks
//   force at v = 0 against −∂energy/∂q (conservative terms),
//   ∂f/∂q  against differences of force in q,
//   ∂f/∂v  against differences of force in v (terms with velocity Jacobians),
//   mass   (terms that provide one): symmetric, and the velocity-dependent force
//          f(q, v) − f(q, 0) equal to the inertial force ∂T/∂q − Ṁq̇ built from
//          differences of M (docs/models.md §3.1.2),
// with steps relative to the state's extent. A check of nothing fails: the force
// and ∂f/∂q (or, for a term with a mass, the mass), and ∂f/∂v when the term has
// one, must each be non-zero at some state.
// The term must already be prepared (auxiliary quantities frozen).
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "models/core/term.h"

namespace wl::test {

struct LocalState {
  std::vector<double> q, v;
};

struct FdOptions {
  // Step of coordinate j: rel_step × the extent (max − min) of the state's q
  // (of v for velocity steps; max(|x|, 1) when all entries are equal).
  double rel_step = 1e-6;
  double rtol = 1e-5;    // relative error allowed (Frobenius norms)
  double floor = 1e-10;  // absolute scale below which quantities count as zero
  // Seeded random states added per given state: q (and v when not all zero)
  // moved by up to `jitter` × their extent.
  int random_states = 3;
  double jitter = 1e-3;
  unsigned seed = 1;
  // The force does not depend on q (gravity): ∂f/∂q must vanish instead.
  bool constant_force = false;
};

struct FdReport {
  bool ok = true;
  double force_error = 0.0;  // worst relative errors over the states
  double dfdq_error = 0.0;
  double dfdv_error = 0.0;
  double mass_error = 0.0;
  std::string detail;  // what failed, where
};

FdReport check_element(const Term& term, int element, const std::vector<LocalState>& states, const FdOptions& opt = {});

// Parameter derivative (Term::parameter_derivative) of the term's k-th parameter
// against central differences of the force in p, with a relative step:
// `make(p)` builds the term (element `element` prepared) at parameter value p.
// Terms that provide mass also have ∂M/∂p (Term::mass_parameter_derivative)
// checked against differences of the mass block. The derivative must not be
// zero at every state (a check of nothing).
FdReport check_parameter_derivative(const std::function<std::unique_ptr<Term>(double)>& make, double p, int k,
                                    int element, const std::vector<LocalState>& states, const FdOptions& opt = {});

// Derivatives of a term's element with respect to its frozen inputs
// (FrozenInputReader::frozen_input_derivatives, models/yarn/frozen_input_reader.h;
// input 0 = F_n, 1 = F_u; a term without that capability fails) against central
// differences of the force in that input, with a relative step: `make(a)`
// builds the term with element `element` prepared at input value a (≠ 0). The
// derivative must not be zero at every state.
FdReport check_frozen_input_derivative(const std::function<std::unique_ptr<Term>(double)>& make, double a, int input,
                                       int element, const std::vector<LocalState>& states, const FdOptions& opt = {});

// A derivative outside any term (a model's auxiliary quantity, its assembled
// Jacobian): the columns `cols` of the analytic ∂f/∂x against central
// differences of f, with step opt.rel_step × the extent of x. Reports the
// relative (Frobenius) error over the columns; it fails above opt.rtol or when
// the analytic columns are all zero.
FdReport check_jacobian_columns(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                const Eigen::VectorXd& x, const std::function<Eigen::VectorXd(int)>& analytic_column,
                                const std::vector<int>& cols, const FdOptions& opt = {});

}  // namespace wl::test
