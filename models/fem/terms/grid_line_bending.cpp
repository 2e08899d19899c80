#include "models/fem/terms/grid_line_bending.h"

#include <algorithm>

#include "models/yarn/terms/bending.h"

namespace wl {
namespace {

// The yarn kernel's local state: (x0, x1, x2, u1 = l, u2 = −l).
std::array<double, 11> yarn_local(const double* q, double l) {
  std::array<double, 11> s;
  std::copy(q, q + 9, s.begin());
  s[9] = l;
  s[10] = -l;
  return s;
}

}  // namespace

void GridLineBendingTerm::add(const std::array<int, 9>& stencil, double k_line, double l) {
  stencils_.push_back(stencil);
  k_.push_back(k_line);
  l_.push_back(l);
}

double GridLineBendingTerm::energy(int e, const double* q) const {
  return BendingTerm::local_energy(yarn_local(q, l_[e]).data(), k_[e]);
}

void GridLineBendingTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const std::array<double, 11> s = yarn_local(q, l_[e]);
  Eigen::Matrix<double, 11, 1> f;
  Eigen::Matrix<double, 11, 11> K;
  BendingTerm::local_evaluate(s.data(), k_[e], f.data(), out.dfdq ? K.data() : nullptr);
  VecMap(out.force) = f.head<9>();
  if (out.dfdq) MatMap(out.dfdq) = K.topLeftCorner<9, 9>();
}

}  // namespace wl
