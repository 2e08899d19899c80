#include "tests/support/fd_check.h"

#include <cmath>
#include <sstream>

namespace wl::test {
namespace {

struct Eval {
  Eigen::VectorXd f;
  Eigen::MatrixXd k, d;
};

Eval evaluate(const Term& term, int e, const std::vector<double>& q, const std::vector<double>& v) {
  const int n = term.stencil_size();
  Eval r{Eigen::VectorXd::Zero(n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  ElementOutput out{r.f.data(), r.k.data(), term.has_velocity_jacobian() ? r.d.data() : nullptr,
                    term.provides_mass() ? m.data() : nullptr};
  term.evaluate(e, q.data(), v.data(), out);
  return r;
}

// The element's mass block at q (v = 0).
Eigen::MatrixXd mass_block(const Term& term, int e, const std::vector<double>& q) {
  const int n = term.stencil_size();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  const std::vector<double> v(n, 0.0);
  term.evaluate(e, q.data(), v.data(), ElementOutput{f.data(), nullptr, nullptr, m.data()});
  return m;
}

double rel_error(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& fd, double floor) {
  return (analytic - fd).norm() / (std::max(analytic.norm(), fd.norm()) + floor);
}

}  // namespace

FdReport check_element(const Term& term, int e, const std::vector<LocalState>& states, const FdOptions& opt) {
  FdReport rep;
  std::ostringstream why;
  const int n = term.stencil_size();
  const double h = opt.step;
  for (size_t s = 0; s < states.size(); ++s) {
    const auto& st = states[s];
    Eval base = evaluate(term, e, st.q, st.v);
    Eigen::MatrixXd fd_k(n, n), fd_d(n, n);
    Eigen::VectorXd fd_force(n);
    for (int j = 0; j < n; ++j) {
      auto qp = st.q, qm = st.q;
      qp[j] += h;
      qm[j] -= h;
      fd_k.col(j) = (evaluate(term, e, qp, st.v).f - evaluate(term, e, qm, st.v).f) / (2 * h);
      if (term.conservative()) fd_force[j] = -(term.energy(e, qp.data()) - term.energy(e, qm.data())) / (2 * h);
      auto vp = st.v, vm = st.v;
      vp[j] += h;
      vm[j] -= h;
      fd_d.col(j) = (evaluate(term, e, st.q, vp).f - evaluate(term, e, st.q, vm).f) / (2 * h);
    }
    auto record = [&](const char* what, double err, double& worst, const Eigen::MatrixXd& a,
                      const Eigen::MatrixXd& fd) {
      worst = std::max(worst, err);
      if (!(err <= opt.rtol)) {
        rep.ok = false;
        why << term.name() << " element " << e << " state " << s << ": " << what << " relative error " << err
            << "\n analytic:\n" << a << "\n finite differences:\n" << fd << "\n";
      }
    };
    if (term.conservative())
  {
      // Velocity-dependent parts (damping, inertia) vanish at v = 0.
      const Eigen::VectorXd f_static = evaluate(term, e, st.q, std::vector<double>(n, 0.0)).f;
      record("force(v=0) vs -grad(energy)", rel_error(f_static, fd_force, opt.floor), rep.force_error, f_static,
             fd_force);
    }
    record("df/dq", rel_error(base.k, fd_k, opt.floor), rep.dfdq_error, base.k, fd_k);
    if (term.has_velocity_jacobian())
      record("df/dv", rel_error(base.d, fd_d, opt.floor), rep.dfdv_error, base.d, fd_d);
    else if (fd_d.norm() > opt.floor + opt.rtol * base.f.norm())
      record("df/dv (term declares none)", rel_error(Eigen::MatrixXd::Zero(n, n), fd_d, opt.floor),
             rep.dfdv_error, Eigen::MatrixXd::Zero(n, n), fd_d);
  }
  rep.detail = why.str();
  return rep;
}

FdReport check_parameter_derivative(const std::function<std::unique_ptr<Term>(double)>& make, double p, int k,
                                    int e, const std::vector<LocalState>& states, const FdOptions& opt) {
  FdReport rep;
  const double h = 1e-4 * p;  // relative step: truncation O(1e-8), roundoff well below
  const std::unique_ptr<Term> term = make(p), hi = make(p + h), lo = make(p - h);
  const int n = term->stencil_size();
  double largest = 0.0;
  for (size_t s = 0; s < states.size(); ++s) {
    const auto& st = states[s];
    Eigen::VectorXd exact = Eigen::VectorXd::Zero(n);
    term->parameter_derivative(e, k, st.q.data(), st.v.data(), exact.data());
    const Eigen::VectorXd fd = (evaluate(*hi, e, st.q, st.v).f - evaluate(*lo, e, st.q, st.v).f) / (2 * h);
    const double err = rel_error(exact, fd, opt.floor);
    largest = std::max(largest, exact.norm());
    rep.force_error = std::max(rep.force_error, err);
    if (err > opt.rtol) {
      rep.ok = false;
      std::ostringstream why;
      why << term->name() << " parameter " << term->parameter_keys().at(k) << " element " << e << " state " << s
          << ": df/dp relative error " << err << " (|analytic| " << exact.norm() << ", |fd| " << fd.norm() << ")\n";
      rep.detail += why.str();
    }
    if (!term->provides_mass()) continue;
    // ∂M/∂p against differences of the mass block in p.
    Eigen::MatrixXd dm = Eigen::MatrixXd::Zero(n, n);
    term->mass_parameter_derivative(e, k, st.q.data(), dm.data());
    const Eigen::MatrixXd dm_fd = (mass_block(*hi, e, st.q) - mass_block(*lo, e, st.q)) / (2 * h);
    const double merr = rel_error(dm.reshaped(), dm_fd.reshaped(), opt.floor);
    largest = std::max(largest, dm.norm());
    rep.force_error = std::max(rep.force_error, merr);
    if (merr > opt.rtol || !(dm.norm() > opt.floor)) {
      rep.ok = false;
      rep.detail += term->name() + " parameter " + term->parameter_keys().at(k) + " state " + std::to_string(s) +
                    ": dM/dp relative error " + std::to_string(merr) + " (|analytic| " + std::to_string(dm.norm()) +
                    ")\n";
    }
  }
  if (!(largest > opt.floor)) {
    rep.ok = false;
    rep.detail += term->name() + ": df/dp is zero at every state\n";
  }
  return rep;
}

}  // namespace wl::test
