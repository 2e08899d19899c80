#include "tests/support/fd_check.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "models/yarn/frozen_input_reader.h"

namespace wl::test {
namespace {

struct Eval {
  Eigen::VectorXd f;
  Eigen::MatrixXd k, d, m;
};

Eval evaluate(const Term& term, int e, const std::vector<double>& q, const std::vector<double>& v) {
  const int n = term.stencil_size();
  Eval r{Eigen::VectorXd::Zero(n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n),
         Eigen::MatrixXd::Zero(n, n)};
  ElementOutput out{r.f.data(), r.k.data(), term.has_velocity_jacobian() ? r.d.data() : nullptr,
                    term.provides_mass() ? r.m.data() : nullptr};
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

// Extent of a local vector (max − min); max(|x|, 1) when all entries are equal
// (a single coordinate says nothing of the scale of the term's constants).
double extent(const std::vector<double>& x) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  if (*hi > *lo) return *hi - *lo;
  return std::max({std::abs(*lo), std::abs(*hi), 1.0});
}

bool all_zero(const std::vector<double>& x) {
  return std::all_of(x.begin(), x.end(), [](double a) { return a == 0.0; });
}

// The given states followed by opt.random_states seeded perturbations of each.
std::vector<LocalState> with_random_states(const std::vector<LocalState>& given, const FdOptions& opt) {
  std::vector<LocalState> all = given;
  std::mt19937 rng(opt.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const LocalState& s : given)
    for (int r = 0; r < opt.random_states; ++r) {
      LocalState p = s;
      const double sq = opt.jitter * extent(s.q), sv = opt.jitter * extent(s.v);
      for (double& x : p.q) x += sq * u(rng);
      if (!all_zero(s.v))
        for (double& x : p.v) x += sv * u(rng);
      all.push_back(std::move(p));
    }
  return all;
}

}  // namespace

FdReport check_element(const Term& term, int e, const std::vector<LocalState>& given, const FdOptions& opt) {
  FdReport rep;
  std::ostringstream why;
  const int n = term.stencil_size();
  const std::vector<LocalState> states = with_random_states(given, opt);
  double largest_f = 0.0, largest_k = 0.0, largest_d = 0.0, largest_m = 0.0;
  for (size_t s = 0; s < states.size(); ++s) {
    const auto& st = states[s];
    const double hq = opt.rel_step * extent(st.q), hv = opt.rel_step * extent(st.v);
    Eval base = evaluate(term, e, st.q, st.v);
    Eigen::MatrixXd fd_k(n, n), fd_d(n, n);
    Eigen::VectorXd fd_force(n);
    for (int j = 0; j < n; ++j) {
      auto qp = st.q, qm = st.q;
      qp[j] += hq;
      qm[j] -= hq;
      fd_k.col(j) = (evaluate(term, e, qp, st.v).f - evaluate(term, e, qm, st.v).f) / (2 * hq);
      if (term.conservative()) fd_force[j] = -(term.energy(e, qp.data()) - term.energy(e, qm.data())) / (2 * hq);
      auto vp = st.v, vm = st.v;
      vp[j] += hv;
      vm[j] -= hv;
      fd_d.col(j) = (evaluate(term, e, st.q, vp).f - evaluate(term, e, st.q, vm).f) / (2 * hv);
    }
    auto record = [&](const char* what, double err, double& worst, const Eigen::MatrixXd& a,
                      const Eigen::MatrixXd& fd) {
      worst = std::max(worst, err);
      if (!(err <= opt.rtol)) {
        rep.ok = false;
        why << term.name() << " element " << e << " state " << s << ": " << what << " relative error " << err
            << "\n analytic:\n"
            << a << "\n finite differences:\n"
            << fd << "\n";
      }
    };
    largest_f = std::max(largest_f, base.f.norm());
    largest_k = std::max({largest_k, base.k.norm(), fd_k.norm()});
    if (term.conservative()) {
      // Velocity-dependent parts (damping, inertia) vanish at v = 0.
      const Eigen::VectorXd f_static = evaluate(term, e, st.q, std::vector<double>(n, 0.0)).f;
      record("force(v=0) vs -grad(energy)", rel_error(f_static, fd_force, opt.floor), rep.force_error, f_static,
             fd_force);
    }
    record("df/dq", rel_error(base.k, fd_k, opt.floor), rep.dfdq_error, base.k, fd_k);
    if (term.has_velocity_jacobian()) {
      largest_d = std::max({largest_d, base.d.norm(), fd_d.norm()});
      record("df/dv", rel_error(base.d, fd_d, opt.floor), rep.dfdv_error, base.d, fd_d);
    } else if (fd_d.norm() > opt.floor + opt.rtol * base.f.norm()) {
      record("df/dv (term declares none)", rel_error(Eigen::MatrixXd::Zero(n, n), fd_d, opt.floor), rep.dfdv_error,
             Eigen::MatrixXd::Zero(n, n), fd_d);
    }
    if (term.provides_mass()) {
      // Inertial force ∂T/∂q − Ṁq̇ with T = ½ q̇ᵀM(q)q̇ (docs/models.md §3.1.2), M differenced in q and along q̇.
      largest_m = std::max(largest_m, base.m.norm());
      record("mass symmetry", rel_error(base.m, base.m.transpose(), opt.floor), rep.mass_error, base.m,
             base.m.transpose());
      const Eigen::Map<const Eigen::VectorXd> v(st.v.data(), n);
      Eigen::VectorXd inertial(n);
      for (int j = 0; j < n; ++j) {
        auto qp = st.q, qm = st.q;
        qp[j] += hq;
        qm[j] -= hq;
        inertial[j] = 0.5 * v.dot((evaluate(term, e, qp, st.v).m - evaluate(term, e, qm, st.v).m) * v) / (2 * hq);
      }
      const double vmax = v.lpNorm<Eigen::Infinity>();
      if (vmax > 0.0) {
        const double eps = hq / vmax;
        auto qp = st.q, qm = st.q;
        for (int j = 0; j < n; ++j) {
          qp[j] += eps * v[j];
          qm[j] -= eps * v[j];
        }
        inertial -= (evaluate(term, e, qp, st.v).m - evaluate(term, e, qm, st.v).m) / (2 * eps) * v;
      }
      const Eigen::VectorXd f_velocity = base.f - evaluate(term, e, st.q, std::vector<double>(n, 0.0)).f;
      record("f(q,v) - f(q,0) vs inertial force from differences of M", rel_error(f_velocity, inertial, opt.floor),
             rep.mass_error, f_velocity, inertial);
    }
  }
  auto require_nonzero = [&](const char* what, double largest) {
    if (largest > opt.floor) return;
    rep.ok = false;
    why << term.name() << " element " << e << ": " << what << " is zero at every state (a check of nothing)\n";
  };
  if (term.provides_mass()) {
    // Its force is the inertial force, checked against M above (zero for a constant M).
    require_nonzero("the mass", largest_m);
  } else if (opt.constant_force) {
    require_nonzero("the force", largest_f);
    if (largest_k > opt.floor) {
      rep.ok = false;
      why << term.name() << " element " << e << ": df/dq is not zero for a constant force\n";
    }
  } else {
    require_nonzero("the force", largest_f);
    require_nonzero("df/dq", largest_k);
  }
  if (term.has_velocity_jacobian()) require_nonzero("df/dv", largest_d);
  rep.detail = why.str();
  return rep;
}

namespace {

// df/da of element e at each state against central differences of the force
// in a (terms built by make), with a relative step; `label` names a.
double check_force_derivative(const Term& term, const Term& hi, const Term& lo, double h, int e,
                              const std::vector<LocalState>& states, const FdOptions& opt, const std::string& label,
                              const std::function<void(const LocalState&, double*)>& analytic, FdReport& rep,
                              size_t s) {
  const int n = term.stencil_size();
  const auto& st = states[s];
  Eigen::VectorXd exact = Eigen::VectorXd::Zero(n);
  analytic(st, exact.data());
  const Eigen::VectorXd fd = (evaluate(hi, e, st.q, st.v).f - evaluate(lo, e, st.q, st.v).f) / (2 * h);
  const double err = rel_error(exact, fd, opt.floor);
  rep.force_error = std::max(rep.force_error, err);
  if (err > opt.rtol) {
    rep.ok = false;
    std::ostringstream why;
    why << term.name() << " " << label << " element " << e << " state " << s << ": relative error " << err
        << " (|analytic| " << exact.norm() << ", |fd| " << fd.norm() << ")\n";
    rep.detail += why.str();
  }
  return exact.norm();
}

}  // namespace

FdReport check_frozen_input_derivative(const std::function<std::unique_ptr<Term>(double)>& make, double a, int input,
                                       int e, const std::vector<LocalState>& states, const FdOptions& opt) {
  FdReport rep;
  const double h = 1e-4 * std::abs(a);
  const std::unique_ptr<Term> term = make(a), hi = make(a + h), lo = make(a - h);
  const int n = term->stencil_size();
  const std::string label = input == 0 ? "df/dF_n" : "df/dF_u";
  const FrozenInputReader* reader = frozen_input_reader(*term);
  if (!reader) {
    rep.ok = false;
    rep.detail += term->name() + ": reads no frozen input (not a FrozenInputReader)\n";
    return rep;
  }
  double largest = 0.0;
  for (size_t s = 0; s < states.size(); ++s)
    largest = std::max(largest, check_force_derivative(
                                    *term, *hi, *lo, h, e, states, opt, label,
                                    [&](const LocalState& st, double* out) {
                                      std::vector<double> other(n, 0.0);
                                      reader->frozen_input_derivatives(e, st.q.data(), st.v.data(),
                                                                       input == 0 ? out : other.data(),
                                                                       input == 0 ? other.data() : out);
                                    },
                                    rep, s));
  if (!(largest > opt.floor)) {
    rep.ok = false;
    rep.detail += term->name() + ": " + label + " is zero at every state\n";
  }
  return rep;
}

FdReport check_jacobian_columns(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                const Eigen::VectorXd& x, const std::function<Eigen::VectorXd(int)>& analytic_column,
                                const std::vector<int>& cols, const FdOptions& opt) {
  FdReport rep;
  const double h = opt.rel_step * std::max(x.maxCoeff() - x.minCoeff(), 1e-300);
  double diff2 = 0.0, ref2 = 0.0, analytic2 = 0.0;
  for (int c : cols) {
    Eigen::VectorXd xp = x, xm = x;
    xp[c] += h;
    xm[c] -= h;
    const Eigen::VectorXd fd = (f(xp) - f(xm)) / (2 * h);
    const Eigen::VectorXd exact = analytic_column(c);
    diff2 += (exact - fd).squaredNorm();
    ref2 += std::max(exact.squaredNorm(), fd.squaredNorm());
    analytic2 += exact.squaredNorm();
  }
  rep.dfdq_error = std::sqrt(diff2) / (std::sqrt(ref2) + opt.floor);
  if (rep.dfdq_error > opt.rtol) {
    rep.ok = false;
    rep.detail += "jacobian columns: relative error " + std::to_string(rep.dfdq_error) + "\n";
  }
  if (!(std::sqrt(analytic2) > opt.floor)) {
    rep.ok = false;
    rep.detail += "jacobian columns: the analytic columns are all zero\n";
  }
  return rep;
}

FdReport check_parameter_derivative(const std::function<std::unique_ptr<Term>(double)>& make, double p, int k, int e,
                                    const std::vector<LocalState>& states, const FdOptions& opt) {
  FdReport rep;
  const double h = 1e-4 * p;  // relative step: truncation O(1e-8), roundoff well below
  const std::unique_ptr<Term> term = make(p), hi = make(p + h), lo = make(p - h);
  const int n = term->stencil_size();
  double largest = 0.0;
  for (size_t s = 0; s < states.size(); ++s) {
    const auto& st = states[s];
    largest = std::max(largest, check_force_derivative(
                                    *term, *hi, *lo, h, e, states, opt, "parameter " + term->parameter_keys().at(k),
                                    [&](const LocalState& state, double* out) {
                                      term->parameter_derivative(e, k, state.q.data(), state.v.data(), out);
                                    },
                                    rep, s));
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
