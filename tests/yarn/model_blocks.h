// Block-by-block comparison of assembled matrices of the yarn model: rows and
// columns grouped by DoF kind (x positions, u along the warp, v along the weft),
// each block with its own relative error, so that a small block (inertia,
// sliding couplings) is not hidden by a large one.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "models/yarn/yarn_model.h"

namespace wl::test {

inline constexpr std::array<const char*, 3> kDofKind = {"x", "u", "v"};

// Kind of every DoF: 0 = position, 1 = u (along the warp), 2 = v (along the weft).
inline std::vector<int> dof_kinds(const YarnModel& m) {
  std::vector<int> kind(m.num_dofs(), 0);
  for (int k = 0; k < m.grid().num_nodes(); ++k) {
    const NodeDofs& d = m.grid().dofs(k);
    if (is_dof(d.u)) kind[d.u] = 1;
    if (is_dof(d.v)) kind[d.v] = 2;
  }
  return kind;
}

// Squared Frobenius norms per (row kind, column kind) block of a reference
// matrix and of its difference from another, column by column.
struct Blocks {
  std::array<std::array<double, 3>, 3> ref{}, diff{};
  void add(const std::vector<int>& kind, int col, const Vec& reference, const Vec& other) {
    for (int r = 0; r < reference.size(); ++r) {
      ref[kind[r]][kind[col]] += reference[r] * reference[r];
      diff[kind[r]][kind[col]] += (reference[r] - other[r]) * (reference[r] - other[r]);
    }
  }
  double relative(int r, int c) const { return std::sqrt(diff[r][c] / ref[r][c]); }
};

// The model's force with every auxiliary quantity (F_n, F_u, anchors) as the
// last model.evaluate left it: the terms evaluated element by element, without
// the model's update of F_n or the terms' prepare().
inline Vec frozen_force(const YarnModel& m, const Vec& q, const Vec& v, bool inertia_only = false) {
  Vec f = Vec::Zero(m.num_dofs());
  std::vector<double> ql, vl, fl;
  for (const auto& term : m.terms()) {
    if (inertia_only && !term->provides_mass()) continue;
    const int n = term->stencil_size();
    ql.resize(n);
    vl.resize(n);
    fl.resize(n);
    for (int e = 0; e < term->num_elements(); ++e) {
      const auto s = term->stencil(e);
      for (int a = 0; a < n; ++a) {
        ql[a] = is_dof(s[a]) ? q[s[a]] : m.constants()[constant_slot(s[a])];
        vl[a] = is_dof(s[a]) ? v[s[a]] : 0.0;
      }
      std::fill(fl.begin(), fl.end(), 0.0);
      term->evaluate(e, ql.data(), vl.data(), ElementOutput{fl.data()});
      for (int a = 0; a < n; ++a)
        if (is_dof(s[a])) f[s[a]] += fl[a];
    }
  }
  return f;
}

}  // namespace wl::test
