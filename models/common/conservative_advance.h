// Conservative advancement along a straight move (docs/models.md §3.11.7,
// §3.11.10): d(α) is the distance of a pair at the fraction α of the move and
// is Lipschitz in α with constant `lip`, so from α the pair stays farther than
// `target` for a further (d(α) − target)/lip:
//   α₀ = 0,  α_{k+1} = α_k + (d(α_k) − target)/lip.
// Returns 1 when the move stays farther than target, else the α reached (short
// of the first approach: conservative), stopping when the advance falls below
// 10⁻⁹ or after 100 advances.
#pragma once

namespace wl {

template <class DistanceAt>
double conservative_advance(double d0, double target, double lip, const DistanceAt& distance_at) {
  double alpha = 0.0, d = d0;
  for (int it = 0; it < 100; ++it) {
    if (!(lip > 0.0)) return 1.0;
    const double step = (d - target) / lip;
    if (alpha + step >= 1.0) return 1.0;
    if (step <= 1e-9) return alpha;
    alpha += step;
    d = distance_at(alpha);
  }
  return alpha;
}

}  // namespace wl
