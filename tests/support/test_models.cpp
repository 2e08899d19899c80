#include "tests/support/test_models.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace wl::test {
namespace {

// V = ½ k (q1 − q0 − L)² on a 1-D chain.
class LinearSpring1d : public StencilTerm<2> {
 public:
  LinearSpring1d(std::vector<std::array<int, 2>> s, double k, double l) : k_(k), l_(l) { stencils_ = std::move(s); }
  std::unique_ptr<Term> clone() const override { return std::make_unique<LinearSpring1d>(*this); }
  std::string name() const override { return "linear-spring-1d"; }
  double energy(int, const double* q) const override {
    const double e = q[1] - q[0] - l_;
    return 0.5 * k_ * e * e;
  }
  void evaluate(int, const double* q, const double*, const ElementOutput& out) const override {
    const double f1 = -k_ * (q[1] - q[0] - l_);
    out.force[0] = -f1;
    out.force[1] = f1;
    if (out.dfdq) {
      MatMap K(out.dfdq);
      K << -k_, k_, k_, -k_;
    }
  }

 private:
  double k_, l_;
};

// Lumped point mass per DoF (constant mass block).
class PointMass : public StencilTerm<1> {
 public:
  PointMass(std::vector<std::array<int, 1>> s, double m) : m_(m) { stencils_ = std::move(s); }
  std::unique_ptr<Term> clone() const override { return std::make_unique<PointMass>(*this); }
  std::string name() const override { return "point-mass"; }
  bool provides_mass() const override { return true; }
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int, const double*, const double*, const ElementOutput& out) const override {
    if (out.mass) out.mass[0] = m_;
  }

 private:
  double m_;
};

// Constant force F per DoF (gravity-like): V = −F q. IMEX-explicit.
class ConstantForce : public StencilTerm<1> {
 public:
  ConstantForce(std::vector<std::array<int, 1>> s, double f) : f_(f) { stencils_ = std::move(s); }
  std::unique_ptr<Term> clone() const override { return std::make_unique<ConstantForce>(*this); }
  std::string name() const override { return "constant-force"; }
  bool imex_explicit() const override { return true; }
  double energy(int, const double* q) const override { return -f_ * q[0]; }
  void evaluate(int, const double*, const double*, const ElementOutput& out) const override { out.force[0] = f_; }

 private:
  double f_;
};

// m(q) = m0 (1 + α q²); force ∂T/∂q − ṁ q̇ = ½ m′ v² − m′ v² = −½ m′(q) v², m′ = 2 m0 α q.
class VariableMass : public StencilTerm<1> {
 public:
  VariableMass(double m0, double alpha) : m0_(m0), a_(alpha) { stencils_.push_back({0}); }
  std::unique_ptr<Term> clone() const override { return std::make_unique<VariableMass>(*this); }
  std::string name() const override { return "variable-mass"; }
  bool conservative() const override { return false; }
  bool has_velocity_jacobian() const override { return true; }
  bool provides_mass() const override { return true; }
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int, const double* q, const double* v, const ElementOutput& out) const override {
    out.force[0] = -m0_ * a_ * q[0] * v[0] * v[0];
    if (out.dfdq) out.dfdq[0] = -m0_ * a_ * v[0] * v[0];
    if (out.dfdv) out.dfdv[0] = -2.0 * m0_ * a_ * q[0] * v[0];
    if (out.mass) out.mass[0] = m0_ * (1.0 + a_ * q[0] * q[0]);
  }

 private:
  double m0_, a_;
};

// 3-D spring with rest length L and a dashpot along the spring:
// V = ½ k (ℓ − L)², f₁ = −k (ℓ − L) u − c (u·(v₁ − v₀)) u, u = (x₁ − x₀)/ℓ.
class Spring3d : public StencilTerm<6> {
 public:
  Spring3d(std::vector<std::array<int, 6>> s, std::vector<double> rest, double k, double c)
      : rest_(std::move(rest)), k_(k), c_(c) {
    stencils_ = std::move(s);
  }
  std::unique_ptr<Term> clone() const override { return std::make_unique<Spring3d>(*this); }
  std::string name() const override { return "spring-3d"; }
  bool has_velocity_jacobian() const override { return c_ != 0.0; }
  double energy(int e, const double* q) const override {
    Eigen::Map<const Vec3> x0(q), x1(q + 3);
    const double d = (x1 - x0).norm() - rest_[e];
    return 0.5 * k_ * d * d;
  }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override {
    Eigen::Map<const Vec3> x0(q), x1(q + 3), v0(v), v1(v + 3);
    const Vec3 dx = x1 - x0;
    const double l = dx.norm();
    const Vec3 u = dx / l;
    const Vec3 dv = v1 - v0;
    const double s = u.dot(dv);
    const Vec3 f1 = -k_ * (l - rest_[e]) * u - c_ * s * u;
    VecMap f(out.force);
    f.head<3>() = -f1;
    f.tail<3>() = f1;
    const Mat3 P = Mat3::Identity() - u * u.transpose();
    if (out.dfdq) {
      // ∂f₁/∂x₁ = −k [uuᵀ + (1 − L/ℓ) P] − (c/ℓ) [u dvᵀ P + s P]
      const Mat3 A = -k_ * (u * u.transpose() + (1.0 - rest_[e] / l) * P) - (c_ / l) * (u * dv.transpose() * P + s * P);
      MatMap K(out.dfdq);
      K.topLeftCorner<3, 3>() = A;
      K.bottomRightCorner<3, 3>() = A;
      K.topRightCorner<3, 3>() = -A;
      K.bottomLeftCorner<3, 3>() = -A;
    }
    if (out.dfdv) {
      const Mat3 B = -c_ * u * u.transpose();
      MatMap D(out.dfdv);
      D.topLeftCorner<3, 3>() = B;
      D.bottomRightCorner<3, 3>() = B;
      D.topRightCorner<3, 3>() = -B;
      D.bottomLeftCorner<3, 3>() = -B;
    }
  }

 private:
  std::vector<double> rest_;
  double k_, c_;
};

Frame points_frame(double t, const Vec& q, int dim) {
  Frame f;
  f.time = t;
  const int np = static_cast<int>(q.size()) / dim;
  f.points.setZero(np, 3);
  for (int i = 0; i < np; ++i)
    for (int d = 0; d < dim; ++d) f.points(i, d) = q[dim * i + d];
  return f;
}

}  // namespace

std::unique_ptr<Term> make_linear_spring_1d(std::vector<std::array<int, 2>> stencils, double k, double rest_length) {
  return std::make_unique<LinearSpring1d>(std::move(stencils), k, rest_length);
}
std::unique_ptr<Term> make_spring_3d(std::vector<std::array<int, 6>> stencils, std::vector<double> rest_lengths,
                                     double k, double damping) {
  return std::make_unique<Spring3d>(std::move(stencils), std::move(rest_lengths), k, damping);
}
std::unique_ptr<Term> make_variable_mass_term(double m0, double alpha) {
  return std::make_unique<VariableMass>(m0, alpha);
}

// ---- SpringChain ------------------------------------------------------------

SpringChain::SpringChain(int num_masses, double m, double k, double rest_length, double g)
    : n_(num_masses), m_(m), k_(k), l_(rest_length), g_(g) {
  num_dofs_ = n_ + 1;
  q0_ = Vec::Zero(num_dofs_);
  for (int i = 0; i <= n_; ++i) q0_[i] = i * l_;
  v0_ = Vec::Zero(num_dofs_);
  fixed_ = {0};
  std::vector<std::array<int, 2>> springs;
  std::vector<std::array<int, 1>> nodes;
  for (int i = 0; i < n_; ++i) springs.push_back({i, i + 1});
  for (int i = 1; i <= n_; ++i) nodes.push_back({i});
  terms_.push_back(make_linear_spring_1d(springs, k_, l_));
  terms_.push_back(std::make_unique<PointMass>(nodes, m_));
  terms_.push_back(std::make_unique<ConstantForce>(nodes, m_ * g_));
  finalize();
}

Frame SpringChain::frame(double t, const Vec& q, const Vec&) const { return points_frame(t, q, 1); }

// Free block: m ẍ = −K x + c, K = k·tridiag(−1, 2, −1) with K_NN = k,
// c_i = m g, c_N = m g + k L (pinned end at 0). x(t) = x* + Φ(cos ωt a + sin ωt/ω b).
void SpringChain::exact_state(double t, Vec& q, Vec& v) const {
  const int n = n_;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    K(i, i) = (i == n - 1) ? k_ : 2 * k_;
    if (i > 0) K(i, i - 1) = -k_;
    if (i < n - 1) K(i, i + 1) = -k_;
  }
  Vec c = Vec::Constant(n, m_ * g_);
  c[n - 1] += k_ * l_;
  const Vec xeq = K.ldlt().solve(c);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K / m_);
  const Eigen::MatrixXd& P = es.eigenvectors();
  const Vec w = es.eigenvalues().cwiseSqrt();
  const Vec a = P.transpose() * (q0_.tail(n) - xeq);
  const Vec b = P.transpose() * v0_.tail(n);
  Vec xm(n), vm(n);
  for (int j = 0; j < n; ++j) {
    xm[j] = a[j] * std::cos(w[j] * t) + b[j] * std::sin(w[j] * t) / w[j];
    vm[j] = -a[j] * w[j] * std::sin(w[j] * t) + b[j] * std::cos(w[j] * t);
  }
  q = Vec::Zero(n + 1);
  v = Vec::Zero(n + 1);
  q.tail(n) = xeq + P * xm;
  v.tail(n) = P * vm;
}

double SpringChain::total_energy(const Vec& q, const Vec& v) const {
  return 0.5 * m_ * v.tail(n_).squaredNorm() + potential_energy(q);
}

double SpringChain::equilibrium_energy() const {
  Vec q, v;
  // The closed form started at rest in equilibrium stays there; its mean
  // position is x* = K⁻¹c. Recompute x* directly (as in exact_state).
  const int n = n_;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    K(i, i) = (i == n - 1) ? k_ : 2 * k_;
    if (i > 0) K(i, i - 1) = -k_;
    if (i < n - 1) K(i, i + 1) = -k_;
  }
  Vec c = Vec::Constant(n, m_ * g_);
  c[n - 1] += k_ * l_;
  q = Vec::Zero(n + 1);
  q.tail(n) = K.ldlt().solve(c);
  return potential_energy(q);
}

double SpringChain::max_frequency() const { return 2.0 * std::sqrt(k_ / m_); }

// ---- VariableMassOscillator ---------------------------------------------------

VariableMassOscillator::VariableMassOscillator(double m0, double alpha, double k, double q0, double v0)
    : m0_(m0), alpha_(alpha), k_(k) {
  num_dofs_ = 2;  // DoF 1 is a pinned dummy, so pinned handling is exercised too
  q0_ = Vec(2);
  q0_ << q0, 0.0;
  v0_ = Vec(2);
  v0_ << v0, 0.0;
  fixed_ = {1};
  terms_.push_back(make_linear_spring_1d({{1, 0}}, k, 0.0));
  terms_.push_back(make_variable_mass_term(m0, alpha));
  terms_.push_back(std::make_unique<PointMass>(std::vector<std::array<int, 1>>{{1}}, 1.0));
  finalize();
}

Frame VariableMassOscillator::frame(double t, const Vec& q, const Vec&) const { return points_frame(t, q, 1); }

double VariableMassOscillator::total_energy(const Vec& q, const Vec& v) const {
  return 0.5 * m0_ * (1.0 + alpha_ * q[0] * q[0]) * v[0] * v[0] + 0.5 * k_ * q[0] * q[0];
}

// ---- SpringNet ----------------------------------------------------------------

SpringNet::SpringNet(int rows, int cols, double spacing, double mass_per_node, double k, double damping) {
  const int nn = rows * cols;
  num_dofs_ = 3 * nn;
  q0_ = Vec::Zero(num_dofs_);
  v0_ = Vec::Zero(num_dofs_);
  auto node = [&](int i, int j) { return i * cols + j; };
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      q0_[3 * node(i, j)] = j * spacing;
      q0_[3 * node(i, j) + 1] = i * spacing;
    }
  for (int d = 0; d < 3; ++d) {
    fixed_.push_back(3 * node(rows - 1, 0) + d);
    fixed_.push_back(3 * node(rows - 1, cols - 1) + d);
  }
  std::vector<std::array<int, 6>> st;
  std::vector<double> rest;
  auto add = [&](int a, int b) {
    st.push_back({3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 1, 3 * b + 2});
    rest.push_back((q0_.segment<3>(3 * a) - q0_.segment<3>(3 * b)).norm());
  };
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      if (j + 1 < cols) add(node(i, j), node(i, j + 1));
      if (i + 1 < rows) add(node(i, j), node(i + 1, j));
      if (i + 1 < rows && j + 1 < cols) add(node(i, j), node(i + 1, j + 1));
      if (i + 1 < rows && j > 0) add(node(i, j), node(i + 1, j - 1));
    }
  terms_.push_back(make_spring_3d(st, rest, k, damping));
  std::vector<std::array<int, 1>> dofs, zdofs;
  for (int i = 0; i < num_dofs_; ++i) dofs.push_back({i});
  for (int i = 0; i < nn; ++i) zdofs.push_back({3 * i + 2});
  terms_.push_back(std::make_unique<PointMass>(dofs, mass_per_node));
  terms_.push_back(std::make_unique<ConstantForce>(zdofs, -9.81 * mass_per_node));
  finalize();
}

Frame SpringNet::frame(double t, const Vec& q, const Vec&) const { return points_frame(t, q, 3); }

}  // namespace wl::test
