#include "models/core/term.h"

namespace wl {

double Term::kinetic_energy(int e, const double* q, const double* v) const {
  const int n = stencil_size();
  thread_local std::vector<double> buf;  // force, mass (kept: no allocation per element)
  buf.assign(static_cast<size_t>(n + n * n), 0.0);
  double* m = buf.data() + n;
  evaluate(e, q, v, ElementOutput{buf.data(), nullptr, nullptr, m});
  double t = 0.0;
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a) t += v[a] * m[a + n * b] * v[b];
  return 0.5 * t;
}

}  // namespace wl
