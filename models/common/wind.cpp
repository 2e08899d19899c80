#include "models/common/wind.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

namespace wl {
namespace {}  // namespace

WindTerm::WindTerm(const Vec3& wind_velocity, double air_density, double drag)
    : wind_(wind_velocity), rho_(air_density), drag_(drag) {
  std::ostringstream bad;
  if (!wind_velocity.allFinite()) bad << "wind velocity (" << wind_velocity.transpose() << ") is not finite";
  else if (!(air_density >= 0.0)) bad << "air density = " << air_density << " (expected >= 0)";
  else if (!(drag >= 0.0)) bad << "drag = " << drag << " (expected >= 0)";
  if (!bad.str().empty()) throw std::invalid_argument("WindTerm: " + bad.str());
}

void WindTerm::add(const std::array<int, 9>& stencil) { stencils_.push_back(stencil); }

// With N = (x1−x0)×(x2−x0) = 2a n_f and ψ(s) = ρ_w|s|s − d_w s, the force is
//   F_w = d_w a v_rel + a ψ(v_n) n_f                         [docs/models.md §3.9]
// so, with P = I − n_f n_fᵀ, da = ½ n_fᵀ dN and dn_f = P dN / (2a):
//   ∂F_w/∂N = ½ (d_w v_rel + ψ n_f) n_fᵀ + ½ ψ′ n_f v_relᵀ P + ½ ψ P,   ψ′ = 2ρ_w|s| − d_w,
//   ∂N/∂x1 = −[e2]×, ∂N/∂x2 = [e1]×, ∂N/∂x0 = [e2]× − [e1]×  (e1 = x1−x0, e2 = x2−x0),
//   ∂F_w/∂v_rel = a (d_w I + ψ′ n_f n_fᵀ),  ∂v_rel/∂ẋ_i = −I/3.
// Every node gets F_w/3, hence the factors 1/3 and 1/9 below.
void WindTerm::evaluate(int, const double* q, const double* v, const ElementOutput& out) const {
  Eigen::Map<const Vec3> x0(q), x1(q + 3), x2(q + 6), v0(v), v1(v + 3), v2(v + 6);
  const Vec3 e1 = x1 - x0, e2 = x2 - x0;
  const Vec3 N = e1.cross(e2);
  const double Nn = N.norm();
  if (!(Nn > 1e-14 * (e1.squaredNorm() + e2.squaredNorm()))) return;  // degenerate: no force
  const double a = 0.5 * Nn;
  const Vec3 n = N / Nn;
  const Vec3 vr = wind_ - (v0 + v1 + v2) / 3.0;
  const double s = n.dot(vr);
  const double psi = rho_ * std::abs(s) * s - drag_ * s;
  const double dpsi = 2.0 * rho_ * std::abs(s) - drag_;
  const Vec3 F = drag_ * a * vr + a * psi * n;  // = ρ_w a |v_n| v_n n_f + d_w a v_t

  Eigen::Map<Eigen::Matrix<double, 9, 1>> f(out.force);
  for (int j = 0; j < 3; ++j) f.segment<3>(3 * j) = F / 3.0;

  if (out.dfdq) {
    const Mat3 P = Mat3::Identity() - n * n.transpose();
    const Mat3 dF_dN =
        0.5 * (drag_ * vr + psi * n) * n.transpose() + 0.5 * dpsi * n * (vr.transpose() * P) + 0.5 * psi * P;
    const Mat3 E1 = cross_matrix(e1), E2 = cross_matrix(e2);
    const Mat3 dN[3] = {E2 - E1, -E2, E1};
    Eigen::Map<Eigen::Matrix<double, 9, 9>> K(out.dfdq);
    for (int i = 0; i < 3; ++i) {
      const Mat3 block = dF_dN * dN[i] / 3.0;
      for (int j = 0; j < 3; ++j) K.block<3, 3>(3 * j, 3 * i) = block;
    }
  }
  if (out.dfdv) {
    const Mat3 block = -a * (drag_ * Mat3::Identity() + dpsi * n * n.transpose()) / 9.0;
    Eigen::Map<Eigen::Matrix<double, 9, 9>> D(out.dfdv);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) D.block<3, 3>(3 * j, 3 * i) = block;
  }
}

}  // namespace wl
