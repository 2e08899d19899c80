#include "models/yarn/terms/parallel_contact.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wl {

void ParallelContactTerm::add(const std::array<int, 2>& stencil, double kc_L, double d) {
  if (!(kc_L >= 0.0) || !std::isfinite(kc_L))
    throw std::invalid_argument("ParallelContactTerm::add: kc_L = " + std::to_string(kc_L) +
                                " N; expected a finite value >= 0");
  if (!(d > 0.0) || !std::isfinite(d))
    throw std::invalid_argument("ParallelContactTerm::add: contact distance d = " + std::to_string(d) +
                                " m; expected a finite value > 0");
  stencils_.push_back(stencil);
  kc_L_.push_back(kc_L);
  d_.push_back(d);
}

// V = ½ k_c L ReLU(d − Δu)², docs/models.md §3.5
double ParallelContactTerm::energy(int e, const double* q) const {
  const double gap = d_[e] - (q[1] - q[0]);
  return gap > 0.0 ? 0.5 * sign_ * kc_L_[e] * gap * gap : 0.0;
}

// F_u0 = −F_u1 = k_c L (Δu − d) when active; ∂F_u0/∂u0 = ∂F_u1/∂u1 = −k_c L,
// ∂F_u0/∂u1 = ∂F_u1/∂u0 = k_c L (docs/models.md §3.5).
void ParallelContactTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const double gap = d_[e] - (q[1] - q[0]);
  if (gap <= 0.0) return;  // inactive: outputs stay zero
  const double k = sign_ * kc_L_[e];
  out.force[0] = -k * gap;
  out.force[1] = k * gap;
  if (out.dfdq) {
    MatMap m(out.dfdq);
    m << -k, k, k, -k;
  }
}

double parallel_contact_distance(int sign_a, int sign_b, double R) {
  if ((sign_a != 1 && sign_a != -1) || (sign_b != 1 && sign_b != -1))
    throw std::invalid_argument("parallel_contact_distance: signs (" + std::to_string(sign_a) + ", " +
                                std::to_string(sign_b) + "); expected +1 or -1 each");
  if (!(R > 0.0) || !std::isfinite(R))
    throw std::invalid_argument("parallel_contact_distance: yarn radius R = " + std::to_string(R) +
                                " m; expected a finite value > 0");
  return sign_a != sign_b ? 4.0 * R : 2.0 * R;
}

}  // namespace wl
