#include "models/core/sparsity_pattern.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace wl {
namespace {

// Compressed lists by DoF (CSR): entries of `item` between start[d] and start[d + 1].
template <typename Item>
struct ByDof {
  std::vector<int64_t> start;
  std::vector<Item> item;
};

struct ElementRef {
  int term;
  int element;
};

// Counting pass then filling pass over `visit(add)`, where add(dof, item)
// files an item under a DoF: no list grows by reallocation.
template <typename Item, typename Visit>
ByDof<Item> group_by_dof(int num_dofs, const Visit& visit) {
  ByDof<Item> out;
  out.start.assign(static_cast<size_t>(num_dofs) + 1, 0);
  visit([&](int dof, const Item&) { ++out.start[dof + 1]; });
  for (int d = 0; d < num_dofs; ++d) out.start[d + 1] += out.start[d];
  out.item.resize(static_cast<size_t>(out.start[num_dofs]));
  std::vector<int64_t> fill(out.start.begin(), out.start.end() - 1);
  visit([&](int dof, const Item& item) { out.item[fill[dof]++] = item; });
  return out;
}

void check_stencils(int num_dofs, const std::vector<Term*>& terms, const std::vector<std::pair<int, int>>& extra) {
  for (const auto& [r, c] : extra)
    if (r < 0 || c < 0 || r >= num_dofs || c >= num_dofs)
      throw std::logic_error("assembly: extra pattern entry out of range");
  for (const Term* t : terms)
    for (int e = 0; e < t->num_elements(); ++e) {
      const auto s = t->stencil(e);
      if (static_cast<int>(s.size()) != t->stencil_size())
        throw std::logic_error("assembly: stencil size mismatch in term '" + t->name() + "'");
      for (int a : s)
        if (is_dof(a) && a >= num_dofs)
          throw std::logic_error("assembly: DoF index out of range in term '" + t->name() + "'");
    }
}

// The distinct rows of column b, unordered, appended to `rows`; `mark[a] == b`
// for a row already taken (so `mark` starts below every column index).
void column_rows(int b, const std::vector<Term*>& terms, const ByDof<ElementRef>& elements,
                 const ByDof<int>& extra_rows, std::vector<int>& mark, std::vector<int>& rows) {
  auto take = [&](int a) {
    if (mark[a] == b) return;
    mark[a] = b;
    rows.push_back(a);
  };
  take(b);
  for (int64_t k = extra_rows.start[b]; k < extra_rows.start[b + 1]; ++k) take(extra_rows.item[k]);
  for (int64_t k = elements.start[b]; k < elements.start[b + 1]; ++k) {
    const ElementRef ref = elements.item[k];
    for (int a : terms[ref.term]->stencil(ref.element))
      if (is_dof(a)) take(a);
  }
}

}  // namespace

SparseMatrix build_sparsity_pattern(int num_dofs, const std::vector<Term*>& terms,
                                    const std::vector<std::pair<int, int>>& extra) {
  check_stencils(num_dofs, terms, extra);
  // Each element filed once under every DoF of its stencil (a DoF repeated in
  // one stencil files it again: harmless, its rows are taken once).
  const auto elements = group_by_dof<ElementRef>(num_dofs, [&](const auto& add) {
    for (int k = 0; k < static_cast<int>(terms.size()); ++k)
      for (int e = 0; e < terms[k]->num_elements(); ++e)
        for (int b : terms[k]->stencil(e))
          if (is_dof(b)) add(b, ElementRef{k, e});
  });
  const auto extra_rows = group_by_dof<int>(num_dofs, [&](const auto& add) {
    for (const auto& [r, c] : extra) add(c, r);
  });

  std::vector<int> mark(num_dofs, -1), rows;
  SparseMatrix pattern(num_dofs, num_dofs);
  int64_t nnz = 0;
  for (int b = 0; b < num_dofs; ++b) {  // counting pass: the column sizes
    rows.clear();
    column_rows(b, terms, elements, extra_rows, mark, rows);
    nnz += static_cast<int64_t>(rows.size());
    pattern.outerIndexPtr()[b + 1] = static_cast<int>(std::min<int64_t>(nnz, std::numeric_limits<int>::max()));
  }
  if (nnz > std::numeric_limits<int>::max())
    throw std::logic_error("assembly: the pattern's " + std::to_string(nnz) + " entries overflow its 32-bit indices");
  pattern.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  std::fill(mark.begin(), mark.end(), -1);
  int* inner = pattern.innerIndexPtr();
  for (int b = 0; b < num_dofs; ++b) {  // filling pass: each column's rows, ascending
    rows.clear();
    column_rows(b, terms, elements, extra_rows, mark, rows);
    std::sort(rows.begin(), rows.end());
    std::copy(rows.begin(), rows.end(), inner + pattern.outerIndexPtr()[b]);
  }
  std::fill(pattern.valuePtr(), pattern.valuePtr() + nnz, 0.0);
  return pattern;
}

}  // namespace wl
