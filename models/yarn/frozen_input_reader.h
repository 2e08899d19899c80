// A capability of the yarn model's terms that read frozen inputs (docs/models.md
// §5.4, §3.6.1): the contact normal force F_n of one crossing (friction, Gong's
// shear) and F_u, the stage-0 force on the element's first stencil DoF
// (friction, stage 1). Such a term derives from this interface besides Term;
// the yarn model's ContactChain asks for it with frozen_input_reader(term) and
// chains the derivatives below with ∂F_n/∂q and ∂F_u/∂q. Every other term keeps
// its inputs out of the core Term interface.
#pragma once

#include "models/core/term.h"

namespace wl {

class FrozenInputReader {
 public:
  virtual ~FrozenInputReader() = default;
  // The node whose contact normal force F_n element e reads (−1: none).
  virtual int normal_force_node(int e) const = 0;
  // The element force's derivatives with respect to that F_n and to F_u (stage-1
  // terms only) at local (q, v): n values each, added into dfdFn and dfdFu.
  virtual void frozen_input_derivatives(int e, const double* q, const double* v, double* dfdFn,
                                        double* dfdFu) const = 0;
};

// The term's FrozenInputReader capability; null for a term that reads no frozen input.
inline const FrozenInputReader* frozen_input_reader(const Term& term) {
  return dynamic_cast<const FrozenInputReader*>(&term);
}

}  // namespace wl
