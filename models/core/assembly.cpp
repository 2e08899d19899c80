#include "models/core/assembly.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "models/core/sparsity_pattern.h"
#include "models/core/step_stiffness.h"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace wl {
namespace {

constexpr int kParallelMinElements = 4096;  // below this a colour is evaluated serially

// An element's local q and v (v is zero on constants; also q and a direction dq).
void gather_state(std::span<const int> s, const Vec& q, const Vec& v, const Vec& constants, double* ql, double* vl) {
  for (size_t a = 0; a < s.size(); ++a) {
    ql[a] = is_dof(s[a]) ? q[s[a]] : constants[constant_slot(s[a])];
    vl[a] = is_dof(s[a]) ? v[s[a]] : 0.0;
  }
}

// Greedy colouring: an element gets the first colour not used by any element
// sharing a DoF with it. As many colours as that takes: a knit whose yarn
// radius is large against its loops needs more than 64.
std::vector<int> colour_elements(const Term& term, int num_dofs, int* num_colours) {
  const int ne = term.num_elements();
  std::vector<int> colour(ne, -1);
  std::vector<std::vector<int>> dof_colours(num_dofs);
  std::vector<char> used;  // per colour so far: taken by a neighbour of the element
  int max_colour = 0;
  for (int e = 0; e < ne; ++e) {
    used.assign(static_cast<size_t>(max_colour) + 1, 0);
    for (int i : term.stencil(e))
      if (is_dof(i))
        for (int c : dof_colours[i]) used[c] = 1;
    int c = 0;
    while (used[c]) ++c;  // used[max_colour] is 0: a new colour at the latest
    colour[e] = c;
    max_colour = std::max(max_colour, c + 1);
    for (int i : term.stencil(e))
      if (is_dof(i)) dof_colours[i].push_back(c);
  }
  *num_colours = max_colour;
  return colour;
}

// Where an element's n×n block goes in the pattern's values: entry (a, b)
// at start[b] + place[a + n b] (start −1: a constant's column; place
// kNoRow: a constant's row).
struct BlockPlace {
  const int* start;
  const std::uint16_t* place;
};
constexpr std::uint16_t kNoRow = 0xFFFF;

// global[entry (a, b)] += local[a + n b] over an element's n×n block, in the
// order of a + n b; constants' rows and columns skipped only where `checked`
// (a term with constants in its stencils).
void scatter_block(bool checked, int n, BlockPlace at, const double* local, double* global) {
  for (int b = 0; b < n; ++b) {
    const double* lb = local + n * b;
    const std::uint16_t* pb = at.place + n * b;
    if (checked) {
      if (at.start[b] < 0) continue;
      double* column = global + at.start[b];
      for (int a = 0; a < n; ++a)
        if (pb[a] != kNoRow) column[pb[a]] += lb[a];
      continue;
    }
    double* column = global + at.start[b];
#pragma GCC unroll 4
    for (int a = 0; a < n; ++a) column[pb[a]] += lb[a];
  }
}

// A[entry] += c_m m + c_v d + c_q k over an element's n×n block (d, m: null
// where the term provides none). The block is combined in k first (a loop
// the compiler vectorizes), then scattered: k is overwritten.
void add_step_block(const StepWeights& c, bool checked, int n, BlockPlace at, double* k, const double* d,
                    const double* m, double* a) {
  const int nn = n * n;
  const double cq = c.dfdq, cv = c.dfdv, cm = c.mass;
  if (d && m)
    for (int ab = 0; ab < nn; ++ab) k[ab] = cq * k[ab] + cv * d[ab] + cm * m[ab];
  else if (d)
    for (int ab = 0; ab < nn; ++ab) k[ab] = cq * k[ab] + cv * d[ab];
  else if (m)
    for (int ab = 0; ab < nn; ++ab) k[ab] = cq * k[ab] + cm * m[ab];
  else
    for (int ab = 0; ab < nn; ++ab) k[ab] *= cq;
  scatter_block(checked, n, at, k, a);
}

// out[s[a]] += Σ_b block(a, b) w_b over the DoF rows of a column-major n×n
// block; a symmetric block is read by columns (contiguous).
void add_block_product(bool symmetric, int n, const int* s, const double* block, const double* w, Vec& out) {
  for (int a = 0; a < n; ++a) {
    if (!is_dof(s[a])) continue;
    double x = 0.0;
    if (symmetric)
      for (int b = 0; b < n; ++b) x += block[b + n * a] * w[b];
    else
      for (int b = 0; b < n; ++b) x += block[a + n * b] * w[b];
    out[s[a]] += x;
  }
}

}  // namespace

Assembly::Assembly(int num_dofs, std::vector<Term*> terms, const std::vector<std::pair<int, int>>& extra)
    : num_dofs_(num_dofs), pattern_(build_sparsity_pattern(num_dofs, terms, extra)) {
  const int* outer = pattern_.outerIndexPtr();
  const int* inner = pattern_.innerIndexPtr();
  for (int col = 0; col < num_dofs; ++col)
    if (outer[col + 1] - outer[col] >= kNoRow)
      throw std::length_error("assembly: DoF " + std::to_string(col) + " is coupled to " +
                              std::to_string(outer[col + 1] - outer[col]) + " DoFs, more than the " +
                              std::to_string(kNoRow - 1) + " a scatter plan's 16-bit row places hold");
  auto place_of = [&](int row, int col) {
    const int* begin = inner + outer[col];
    return static_cast<std::uint16_t>(std::lower_bound(begin, inner + outer[col + 1], row) - begin);
  };

  for (Term* t : terms) {
    TermPlan plan;
    plan.term = t;
    plan.n = t->stencil_size();
    const int ne = t->num_elements();
    int nc = 0;
    std::vector<int> colour = colour_elements(*t, num_dofs, &nc);
    plan.colour_start.assign(nc + 1, 0);
    for (int c : colour) ++plan.colour_start[c + 1];
    for (int c = 0; c < nc; ++c) plan.colour_start[c + 1] += plan.colour_start[c];
    plan.order.resize(ne);
    std::vector<int> fill(plan.colour_start.begin(), plan.colour_start.end() - 1);
    for (int e = 0; e < ne; ++e) plan.order[fill[colour[e]]++] = e;
    const int n = plan.n;
    plan.column_start.assign(static_cast<size_t>(ne) * n, -1);
    plan.row_place.assign(static_cast<size_t>(ne) * n * n, kNoRow);
    for (int e = 0; e < ne; ++e) {
      auto s = t->stencil(e);
      for (int b = 0; b < n; ++b) {
        if (!is_dof(s[b])) {
          plan.has_constants = true;
          continue;
        }
        plan.column_start[static_cast<size_t>(e) * n + b] = outer[s[b]];
        for (int a = 0; a < n; ++a)
          if (is_dof(s[a])) plan.row_place[(static_cast<size_t>(e) * n + b) * n + a] = place_of(s[a], s[b]);
          else plan.has_constants = true;
      }
    }
    plans_.push_back(std::move(plan));
  }
}

void Assembly::rebind(const std::vector<Term*>& terms) {
  if (terms.size() != plans_.size())
    throw std::logic_error("assembly: rebind with " + std::to_string(terms.size()) + " terms, built with " +
                           std::to_string(plans_.size()));
  for (size_t k = 0; k < terms.size(); ++k) {
    const Term &was = *plans_[k].term, &now = *terms[k];
    bool same = was.name() == now.name() && was.stencil_size() == now.stencil_size() &&
                was.num_elements() == now.num_elements();
    for (int e = 0; same && e < now.num_elements(); ++e) {
      const auto a = was.stencil(e), b = now.stencil(e);
      same = std::equal(a.begin(), a.end(), b.begin());
    }
    if (!same) throw std::logic_error("assembly: rebind: term '" + now.name() + "' differs in its stencils");
  }
  for (size_t k = 0; k < terms.size(); ++k) plans_[k].term = terms[k];
}

void Assembly::add_stage(int stage, const Vec& q, const Vec& v, const Vec& constants, const AssemblyRequest& req,
                         Vec& f, SparseMatrix* dfdq, SparseMatrix* dfdv, SparseMatrix* mass) const {
  for (const TermPlan& plan : plans_) {
    if (plan.term->stage() != stage) continue;
    if (req.filter == TermFilter::explicit_only && !plan.term->imex_explicit()) continue;
    if (req.filter == TermFilter::implicit_only && plan.term->imex_explicit()) continue;
    if (req.filter == TermFilter::mass_only && !plan.term->provides_mass()) continue;
    add_term(plan, q, v, constants, req, f, dfdq, dfdv, mass);
  }
}

void Assembly::add_term(const TermPlan& plan, const Vec& q, const Vec& v, const Vec& constants,
                        const AssemblyRequest& req, Vec& f, SparseMatrix* dfdq, SparseMatrix* dfdv,
                        SparseMatrix* mass) const {
  const Term& term = *plan.term;
  const int n = plan.n;
  const StepWeights* step = dfdq ? req.step : nullptr;
  const bool want_k = step || (req.dfdq && dfdq);
  const bool want_d = term.has_velocity_jacobian() && (step ? step->dfdv != 0.0 : req.dfdv && dfdv);
  const bool want_m = term.provides_mass() && (step ? !step->constant_mass : req.mass && mass);
  double* kv = want_k && !step ? dfdq->valuePtr() : nullptr;
  double* dv = want_d && !step ? dfdv->valuePtr() : nullptr;
  double* mv = want_m && !step ? mass->valuePtr() : nullptr;
  double* av = step ? dfdq->valuePtr() : nullptr;
  const Vec* w = step && step->rhs_dfdq != 0.0 && req.dfdq_w ? step->w : nullptr;
  // The step matrix's K_e (and the right-hand side's K_e w_e) projected, docs/models.md §3.11.2.
  const bool project = want_k && (step || req.step_stiffness) && term.projects_step_stiffness();
  const bool k_symmetric = term.symmetric_jacobian() || project;  // K_e = −∇²E_e, or its projection

  auto run_range = [&](int begin, int end) {
    thread_local std::vector<double> buf;  // q, v, w, f; dfdq, dfdv, mass (kept: no allocation per evaluation)
    buf.resize(static_cast<size_t>(4 * n + 3 * n * n));
    double* ql = buf.data();
    double* vl = ql + n;
    double* wl = vl + n;
    double* fl = wl + n;
    double* kl = fl + n;
    double* dl = kl + n * n;
    double* ml = dl + n * n;
    ElementOutput out{fl, want_k ? kl : nullptr, want_d ? dl : nullptr, want_m ? ml : nullptr};
    for (int k = begin; k < end; ++k) {
      const int e = plan.order[k];
      auto s = term.stencil(e);
      gather_state(s, q, v, constants, ql, vl);
      // Zero only what the term will write (outputs arrive zero-filled).
      std::fill(fl, fl + n, 0.0);
      if (want_k) std::fill(kl, kl + n * n, 0.0);
      if (want_d) std::fill(dl, dl + n * n, 0.0);
      if (want_m) std::fill(ml, ml + n * n, 0.0);
      term.evaluate(e, ql, vl, out);
      if (project) {  // over the stencil's DoFs only: a constant's rows and columns are not A's
        for (int a = 0; a < n; ++a)
          if (!is_dof(s[a]))
            for (int b = 0; b < n; ++b) kl[a + n * b] = kl[b + n * a] = 0.0;
        project_step_stiffness(n, kl);
      }
      for (int a = 0; a < n; ++a)
        if (is_dof(s[a])) f[s[a]] += fl[a];
      const BlockPlace at{plan.column_start.data() + static_cast<size_t>(e) * n,
                          plan.row_place.data() + static_cast<size_t>(e) * n * n};
      if (av) {  // A += c_m M_e + c_v D_e + c_q K_e, docs/models.md §7.2
        if (w) {
          for (int a = 0; a < n; ++a) wl[a] = is_dof(s[a]) ? (*w)[s[a]] : 0.0;
          add_block_product(k_symmetric, n, s.data(), kl, wl, *req.dfdq_w);
        }
        add_step_block(*step, plan.has_constants, n, at, kl, want_d ? dl : nullptr, want_m ? ml : nullptr, av);
        continue;
      }
      if (kv) scatter_block(plan.has_constants, n, at, kl, kv);
      if (dv) scatter_block(plan.has_constants, n, at, dl, dv);
      if (mv) scatter_block(plan.has_constants, n, at, ml, mv);
    }
  };

  const int num_colours = static_cast<int>(plan.colour_start.size()) - 1;
  for (int c = 0; c < num_colours; ++c) {
    const int begin = plan.colour_start[c], end = plan.colour_start[c + 1];
    if (end - begin < kParallelMinElements) {
      run_range(begin, end);
      continue;
    }
#pragma omp parallel
    {
      int tid = 0, nt = 1;
#ifdef _OPENMP
      tid = omp_get_thread_num();
      nt = omp_get_num_threads();
#endif
      const int len = end - begin;
      const int lo = begin + static_cast<int>(static_cast<long long>(len) * tid / nt);
      const int hi = begin + static_cast<int>(static_cast<long long>(len) * (tid + 1) / nt);
      run_range(lo, hi);
    }
  }
}

double Assembly::energy(const Vec& q, const Vec& constants) const {
  double total = 0.0;
  std::vector<double> ql;
  for (const TermPlan& plan : plans_) {
    const Term& term = *plan.term;
    if (!term.conservative()) continue;
    ql.resize(plan.n);
    for (int e = 0; e < term.num_elements(); ++e) {
      auto s = term.stencil(e);
      for (int a = 0; a < plan.n; ++a) ql[a] = is_dof(s[a]) ? q[s[a]] : constants[constant_slot(s[a])];
      total += term.energy(e, ql.data());
    }
  }
  return total;
}

double Assembly::kinetic_energy(const Vec& q, const Vec& v, const Vec& constants) const {
  double total = 0.0;
  std::vector<double> ql, vl;
  for (const TermPlan& plan : plans_) {
    const Term& term = *plan.term;
    if (!term.provides_mass()) continue;
    ql.resize(plan.n);
    vl.resize(plan.n);
    for (int e = 0; e < term.num_elements(); ++e) {
      auto s = term.stencil(e);
      gather_state(s, q, v, constants, ql.data(), vl.data());
      total += term.kinetic_energy(e, ql.data(), vl.data());
    }
  }
  return total;
}

void Assembly::term_energies_and_powers(const Vec& q, const Vec& v, const Vec& constants, std::vector<double>& energy,
                                        std::vector<double>& power) const {
  energy.assign(plans_.size(), 0.0);
  power.assign(plans_.size(), 0.0);
  std::vector<double> ql, vl, fl;
  for (size_t k = 0; k < plans_.size(); ++k) {
    const Term& term = *plans_[k].term;
    const int n = plans_[k].n;
    ql.resize(n);
    vl.resize(n);
    fl.resize(n);
    for (int e = 0; e < term.num_elements(); ++e) {
      auto s = term.stencil(e);
      gather_state(s, q, v, constants, ql.data(), vl.data());
      if (term.conservative()) energy[k] += term.energy(e, ql.data());
      std::fill(fl.begin(), fl.end(), 0.0);
      term.evaluate(e, ql.data(), vl.data(), ElementOutput{fl.data()});
      for (int a = 0; a < n; ++a) power[k] += fl[a] * vl[a];
    }
  }
}

bool Assembly::add_parameter_derivative(const std::string& key, const Vec& q, const Vec& v, const Vec& constants,
                                        Vec& dfdp) const {
  bool any = false;
  std::vector<double> ql, vl, fl;
  for (const TermPlan& plan : plans_) {
    const Term& term = *plan.term;
    const std::vector<std::string> keys = term.parameter_keys();
    const auto it = std::find(keys.begin(), keys.end(), key);
    if (it == keys.end()) continue;
    any = true;
    const int k = static_cast<int>(it - keys.begin());
    ql.resize(plan.n);
    vl.resize(plan.n);
    fl.resize(plan.n);
    for (int e = 0; e < term.num_elements(); ++e) {
      auto s = term.stencil(e);
      gather_state(s, q, v, constants, ql.data(), vl.data());
      std::fill(fl.begin(), fl.end(), 0.0);
      term.parameter_derivative(e, k, ql.data(), vl.data(), fl.data());
      for (int a = 0; a < plan.n; ++a)
        if (is_dof(s[a])) dfdp[s[a]] += fl[a];
    }
  }
  return any;
}

void Assembly::add_mass_directional_product(const Vec& q, const Vec& dq, const Vec& w, const Vec& constants,
                                            Vec& out) const {
  std::vector<double> ql, dql, ml;
  for (const TermPlan& plan : plans_) {
    const Term& term = *plan.term;
    const PositionDependentMass* dependent = position_dependent_mass(term);
    if (!term.provides_mass() || !dependent) continue;
    const int n = plan.n;
    ql.resize(n);
    dql.resize(n);
    ml.resize(n * n);
    for (int e = 0; e < term.num_elements(); ++e) {
      auto s = term.stencil(e);
      gather_state(s, q, dq, constants, ql.data(), dql.data());
      std::fill(ml.begin(), ml.end(), 0.0);
      dependent->mass_directional_derivative(e, ql.data(), dql.data(), ml.data());
      for (int a = 0; a < n; ++a) {
        if (!is_dof(s[a])) continue;
        for (int b = 0; b < n; ++b)
          if (is_dof(s[b])) out[s[a]] += ml[a + n * b] * w[s[b]];
      }
    }
  }
}

bool Assembly::add_mass_parameter_product(const std::string& key, const Vec& q, const Vec& w, const Vec& constants,
                                          Vec& out) const {
  bool any = false;
  std::vector<double> ql, ml;
  for (const TermPlan& plan : plans_) {
    const Term& term = *plan.term;
    if (!term.provides_mass()) continue;
    const std::vector<std::string> keys = term.parameter_keys();
    const auto it = std::find(keys.begin(), keys.end(), key);
    if (it == keys.end()) continue;
    any = true;
    const int k = static_cast<int>(it - keys.begin()), n = plan.n;
    ql.resize(n);
    ml.resize(n * n);
    for (int e = 0; e < term.num_elements(); ++e) {
      auto s = term.stencil(e);
      for (int a = 0; a < n; ++a) ql[a] = is_dof(s[a]) ? q[s[a]] : constants[constant_slot(s[a])];
      std::fill(ml.begin(), ml.end(), 0.0);
      term.mass_parameter_derivative(e, k, ql.data(), ml.data());
      for (int a = 0; a < n; ++a) {
        if (!is_dof(s[a])) continue;
        for (int b = 0; b < n; ++b)
          if (is_dof(s[b])) out[s[a]] += ml[a + n * b] * w[s[b]];
      }
    }
  }
  return any;
}

}  // namespace wl
