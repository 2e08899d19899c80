// The sparsity pattern shared by the assembled matrices (docs/design.md §3.3):
// entry (a, b) wherever DoFs a and b are in one element's stencil, the full
// diagonal and a model's extra entries. Built column by column from the
// elements that touch each DoF, so that what is held while it is built is one
// entry per stencil DoF (the incidence) and the pattern itself, not the n²
// pairs of every n-DoF element at once.
#pragma once
#include <utility>
#include <vector>

#include "models/core/term.h"

namespace wl {

// Compressed, row indices ascending in each column, every value zero.
// Throws std::logic_error on a stencil whose size is not its term's, or a DoF
// or extra entry outside [0, num_dofs).
SparseMatrix build_sparsity_pattern(int num_dofs, const std::vector<Term*>& terms,
                                    const std::vector<std::pair<int, int>>& extra);

}  // namespace wl
