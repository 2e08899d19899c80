// Stitch-length penalty on the sliding coordinates of one yarn across a stitch
// segment (docs/models.md §11.5, the Eulerian reading of the source's
// stitch-length term): when one end of the stitch slides, the other follows.
//   V = ½ k_l L (Δu/L − 1)²,  Δu = u1 − u0 (the yarn's coordinates at the
//   segment's ends in its direction of travel), L its rest value, k_l in N.
// Local stencil (2): u0, u1.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class StitchLengthTerm : public ProportionalParameterTerm<2> {
 public:
  // kl ≥ 0 [N], rest > 0 [m].
  void add(const std::array<int, 2>& stencil, double kl, double rest);

  std::string name() const override { return "stitch_length"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<StitchLengthTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  std::vector<double> kl_, rest_;
};

}  // namespace wl
