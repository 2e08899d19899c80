#include "calibration/stretch_law_guess.h"

#include <algorithm>
#include <cmath>

namespace wl {
namespace {

const FitCurve* find_curve(const std::vector<FitCurve>& curves, TestKind kind) {
  for (const FitCurve& c : curves)
    if (c.test.kind == kind && !c.test.rotated) return &c;
  return nullptr;
}

}  // namespace

double cubic_part(const FitCurve& c) {
  double a11 = 0, a12 = 0, a22 = 0, b1 = 0, b2 = 0;
  for (size_t i = 0; i < c.target.size(); ++i) {
    const double e = c.test.ladder[i], e3 = e * e * e;
    a11 += e * e, a12 += e * e3, a22 += e3 * e3, b1 += e * c.target[i], b2 += e3 * c.target[i];
  }
  const double det = a11 * a22 - a12 * a12;
  return det > 1e-12 * a11 * a22 ? (a11 * b2 - a12 * b1) / det : 0.0;
}

void stretch_law_first_guess(const std::vector<FitCurve>& curves, bool coupling, bool stiffening, FemMaterial& m) {
  const FitCurve *u = find_curve(curves, TestKind::uniaxial_warp), *v = find_curve(curves, TestKind::uniaxial_weft),
                 *b = find_curve(curves, TestKind::biaxial);
  if (coupling) {
    const double bound = std::sqrt(m.warp_stretch_N_per_m * m.weft_stretch_N_per_m);
    auto secant = [](const FitCurve* c, double fallback) { return c ? c->target[0] / c->test.ladder[0] : fallback; };
    const double k = 0.5 * (secant(b, 0) - secant(u, m.warp_stretch_N_per_m) - secant(v, m.weft_stretch_N_per_m));
    m.stretch_coupling_N_per_m = std::clamp(k, 0.02 * bound, 0.9 * bound);
  }
  if (stiffening) {
    auto quartic = [&](const FitCurve* c, double k) {
      if (!c && !b) return 0.0;
      const double q = c ? cubic_part(*c) : b ? 0.5 * cubic_part(*b) : 0.0, e = c ? c->test.ladder.back() : 0.1;
      return std::max(q, 0.01 * k / (e * e));
    };
    m.warp_stretch_quartic_N_per_m = quartic(u, m.warp_stretch_N_per_m);
    m.weft_stretch_quartic_N_per_m = quartic(v, m.weft_stretch_N_per_m);
    if (u && v && b) {
      const double e = b->test.ladder.back(), k = 0.5 * (m.warp_stretch_N_per_m + m.weft_stretch_N_per_m);
      m.areal_stretch_quartic_N_per_m =
          std::max((cubic_part(*b) - cubic_part(*u) - cubic_part(*v)) / 14.0, 0.01 * k / (e * e));
    }
  }
}

}  // namespace wl
