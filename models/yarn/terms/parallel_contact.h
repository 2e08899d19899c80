// Contact between the two parallel yarns that cross a segment at its ends, as a
// penalty in Eulerian space (docs/models.md §3.5, Cirio et al. 2016 eqs. (72)–(74),
// Gong et al. 2022 eqs. (55)–(58)). Local stencil (u0, u1):
//   V = ½ k_c L ReLU(d − Δu)²,  Δu = u1 − u0.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "models/core/term.h"

namespace wl {

class ParallelContactTerm : public StencilTerm<2> {
 public:
  // sign +1: the penalty above; −1: its negative, V = −½ k_c L ReLU(d − Δu)², whose force pulls the
  // two crossings together as the published code's does (docs/published_code.md row 12).
  explicit ParallelContactTerm(double sign = 1.0) : sign_(sign) {}
  // One segment; kc_L = k_c·L in N (≥ 0), d the contact distance in m (> 0).
  void add(const std::array<int, 2>& stencil, double kc_L, double d);

  std::string name() const override { return "parallel-contact"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<ParallelContactTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  double sign_;
  std::vector<double> kc_L_, d_;
};

// Contact distance of the two yarns crossing a segment at its ends, from the
// over/under signs (±1) of the two crossings: 4R when the segment's yarn
// passes between them (signs differ), else 2R (docs/models.md §4.14).
double parallel_contact_distance(int sign_a, int sign_b, double R);

}  // namespace wl
