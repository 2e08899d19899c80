// Contact compression at a stitch contact (docs/models.md §11.6): the two yarns
// through a stitch share its segment a→b, which carries them through the
// cloth, one behind the other; its extent through the cloth, h = n·(x_b − x_a),
// is the distance between their centrelines in the stack and must not fall
// below the contact distance D = 2R (the two yarns would pass through each
// other and the stitch would lose its front and back). With the course
// direction c = σ_s (½(x_a' + x_b') − ½(x_a + x_b)) towards the contact on the
// other side of the same loop (a', b'; σ_s = +1 from the left one, −1 from the
// right one), the wale direction w = ½(x_ua + x_ub) − ½(x_da + x_db) from the
// contact below (da, db) to the one above (ua, ub) in the same wale and side,
// and the cloth's normal n = (c × w)/‖c × w‖ (+z for the generated flat cloth):
//   V = ½ κ (D − σ h)² for σ h < D, else 0,  σ = +1 knit, −1 purl,
//   ∇h: e = x_b − x_a gives ±n; v = c × w gives g_v = (I − n nᵀ) e / ‖v‖, and
//   g_c = w × g_v, g_w = g_v × c, spread over the nodes that average into c, w.
// F = κ (D − σh) σ ∇h; the Jacobian is the exact derivative of F by
// forward-mode automatic differentiation (Eigen's AutoDiffScalar).
// A stacked stitch (n ≥ 3 yarns, stack_pairs.h) has one element per pair of its
// yarns, their centrelines the share φ = (j − i)/(n − 1) of the stack apart:
//   V = ½ κ (D − φσh)² for φσh < D,  F = κ (D − φσh) φσ ∇h   (φ = 1: the two-yarn stitch).
// Local stencil (24): x_a, x_b, x_a', x_b', x_da, x_db, x_ua, x_ub.
// Precondition: c and w not parallel.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class StitchCompressionTerm : public ProportionalParameterTerm<24> {
 public:
  // kappa ≥ 0 [N/m], contact distance D > 0 [m]; the contact is the left (+1)
  // or right (−1) one of its loop (side_sign) and a knit (+1) or purl (−1) stitch (stitch_sign);
  // the pair's share 0 < φ ≤ 1 of the stack height (stack_pairs.h; 1 for a two-yarn stitch).
  void add(const std::array<int, 24>& stencil, double kappa, double contact_distance, int side_sign, int stitch_sign,
           double stack_share = 1.0);

  std::string name() const override { return "stitch_compression"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<StitchCompressionTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // σ h of element e at a local state: the stack height of its yarns.
  double stack_height(int e, const double* q) const;

 private:
  std::vector<double> kappa_, contact_distance_, stack_share_;
  std::vector<int> side_, stitch_;
};

}  // namespace wl
