#include "models/fem/terms/tile_bending.h"

#include "models/fem/terms/hinge_bending.h"
#include "models/fem/terms/membrane_strains.h"

namespace wl {

using Mat18 = Eigen::Matrix<double, 18, 18>;

struct TileBendingTerm::Strains {
  std::array<double, 6> theta{};      // ε_u, ε_v, γ, κ_u, κ_v, κ_uv
  Eigen::Matrix<double, 18, 6> grad;  // ∇θ6_j, column j
  std::array<Mat18, 6> hess;          // ∇²θ6_j (when asked)
};

TileBendingTerm::TileBendingTerm(std::shared_ptr<const TileBendingLaw> law) : law_(std::move(law)) {}

void TileBendingTerm::add(const std::array<int, 6>& vertices, const std::array<Vec2, 3>& uv) {
  Rest r;
  r.triangle = triangle_rest(uv[0], uv[1], uv[2]);
  std::array<int, 18> s;
  for (int v = 0; v < 6; ++v) {
    // A border edge takes its own triangle's apex in the stencil; it adds nothing.
    const int vertex = v < 3 || vertices[v] >= 0 ? vertices[v] : vertices[(v - 3 + 2) % 3];
    for (int c = 0; c < 3; ++c) s[3 * v + c] = 3 * vertex + c;
  }
  for (int k = 0; k < 3; ++k) {
    r.hinge[k] = vertices[3 + k] >= 0;
    const Vec2 e = uv[(k + 1) % 3] - uv[k];
    const double l = e.norm();
    const Vec2 t(e.y() / l, -e.x() / l);
    const double w = -l / (2.0 * r.triangle.area);  // B = −Σ θ_k ‖ē_k‖/(2A) t_k t_kᵀ
    r.a[k] = {w * t.x() * t.x(), w * t.y() * t.y(), w * t.x() * t.y()};
  }
  stencils_.push_back(s);
  rest_.push_back(r);
}

bool TileBendingTerm::strains(int e, const double* q, bool second, Strains& s) const {
  const Rest& r = rest_[e];
  const MembraneStrains m = membrane_strains(warp_vector(r.triangle, q), weft_vector(r.triangle, q), second);
  if (!m.valid) return false;
  s.grad.setZero();
  const Eigen::Matrix<double, 6, 9> C = column_map(r.triangle);
  for (int j = 0; j < 3; ++j) {
    s.theta[j] = m.m[j];
    Eigen::Matrix<double, 6, 1> g;
    g << m.gu[j], m.gv[j];
    s.grad.col(j).head<9>() = C.transpose() * g;
    if (!second) continue;
    Eigen::Matrix<double, 6, 6> h;
    h << m.huu[j], m.huv[j], m.huv[j].transpose(), m.hvv[j];
    s.hess[j].setZero();
    s.hess[j].topLeftCorner<9, 9>() = C.transpose() * h * C;
  }
  for (int j = 3; j < 6; ++j) {
    s.theta[j] = 0.0;
    if (second) s.hess[j].setZero();
  }
  for (int k = 0; k < 3; ++k) {
    if (!r.hinge[k]) continue;
    const std::array<int, 4> slot{k, (k + 1) % 3, (k + 2) % 3, 3 + k};  // (x_k, x_{k+1}, x_{k+2}, o_k)
    double qh[12];
    for (int v = 0; v < 4; ++v)
      for (int c = 0; c < 3; ++c) qh[3 * v + c] = q[3 * slot[v] + c];
    double angle;
    HingeBendingTerm::Vec12 g;
    HingeBendingTerm::Mat12 h;
    if (!HingeBendingTerm::dihedral_derivatives(qh, &angle, &g, second ? &h : nullptr)) return false;
    for (int c = 0; c < 3; ++c) {
      const double a = r.a[k][c];
      s.theta[3 + c] += a * angle;
      for (int v = 0; v < 4; ++v) {
        s.grad.col(3 + c).segment<3>(3 * slot[v]) += a * g.segment<3>(3 * v);
        if (!second) continue;
        for (int w = 0; w < 4; ++w)
          s.hess[3 + c].block<3, 3>(3 * slot[v], 3 * slot[w]) += a * h.block<3, 3>(3 * v, 3 * w);
      }
    }
  }
  return true;
}

std::array<double, 3> TileBendingTerm::curvature(int e, const double* q) const {
  Strains s;
  if (!strains(e, q, false, s)) return {0.0, 0.0, 0.0};
  return {s.theta[3], s.theta[4], s.theta[5]};
}

double TileBendingTerm::energy(int e, const double* q) const {
  Strains s;
  if (!strains(e, q, false, s)) return 0.0;
  double w;
  law_->evaluate(s.theta, &w, nullptr, nullptr);
  return rest_[e].triangle.area * w;
}

void TileBendingTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  Strains s;
  if (!strains(e, q, out.dfdq != nullptr, s)) return;  // collapsed or folded: no force
  double w;
  std::array<double, 6> g;
  std::array<double, 36> h;
  law_->evaluate(s.theta, &w, &g, out.dfdq ? &h : nullptr);
  const double area = rest_[e].triangle.area;
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>> gv(g.data());
  VecMap(out.force) = -area * s.grad * gv;
  if (!out.dfdq) return;
  const Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> hm(h.data());
  Mat18 k = s.grad * hm * s.grad.transpose();
  for (int j = 0; j < 6; ++j) k += g[j] * s.hess[j];
  MatMap(out.dfdq) = -area * k;
}

std::unique_ptr<TileBendingTerm> TileBendingTerm::with_law(std::shared_ptr<const TileBendingLaw> law) const {
  auto t = std::make_unique<TileBendingTerm>(*this);
  t->law_ = std::move(law);
  return t;
}

std::vector<std::string> TileBendingTerm::parameter_keys() const {
  std::vector<std::string> keys;
  for (int i = 0; i < law_->size(); ++i) keys.push_back("fem.tile_law." + law_->name(i));
  return keys;
}

void TileBendingTerm::parameter_derivative(int e, int k, const double* q, const double*, double* dfdp) const {
  Strains s;
  if (!strains(e, q, false, s)) return;
  double w;
  std::array<double, 6> g;
  law_->evaluate_unit(k, s.theta, &w, &g);
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>> gv(g.data());
  VecMap(dfdp) -= rest_[e].triangle.area * s.grad * gv;
}

}  // namespace wl
