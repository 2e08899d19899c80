// The contact normal force F_n that friction and Gong's shear hold frozen for
// their elements (docs/models.md §3.6, §5.4): copied in prepare() from the
// model's per-node table in the EvalContext, so a term keeps no reference into
// its model (docs/design.md §3.4).
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "models/core/term.h"

namespace wl {

// Fn[e] = ctx.normal_force[node[e]], or 0 when the model computes no F_n.
inline void freeze_normal_force(const EvalContext& ctx, const std::vector<int>& node, std::vector<double>& Fn,
                                const char* who) {
  Fn.resize(node.size());
  for (size_t e = 0; e < node.size(); ++e) {
    if (ctx.normal_force.empty()) {
      Fn[e] = 0.0;
      continue;
    }
    if (node[e] < 0 || static_cast<size_t>(node[e]) >= ctx.normal_force.size())
      throw std::out_of_range(std::string(who) + ": node " + std::to_string(node[e]) +
                              " outside the normal-force table of size " + std::to_string(ctx.normal_force.size()));
    Fn[e] = ctx.normal_force[node[e]];
  }
}

}  // namespace wl
