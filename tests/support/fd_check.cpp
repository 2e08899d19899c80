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

}  // namespace wl::test
