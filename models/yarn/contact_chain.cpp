#include "models/yarn/contact_chain.h"

#include <algorithm>
#include <stdexcept>

#include "models/yarn/frozen_input_reader.h"

namespace wl {
namespace {

// Each term's FrozenInputReader capability, null for a term that reads no frozen input.
std::vector<const FrozenInputReader*> frozen_input_readers(const std::vector<std::unique_ptr<Term>>& terms) {
  std::vector<const FrozenInputReader*> readers;
  for (const auto& term : terms) readers.push_back(frozen_input_reader(*term));
  return readers;
}

}  // namespace

ContactChain::ContactChain(const std::vector<std::unique_ptr<Term>>& terms, const ContactNormals& normals) {
  const auto& grad = normals.gradient();
  nodes_.resize(grad.size());
  std::vector<int> stage0_rows;
  const std::vector<const FrozenInputReader*> reader_of = frozen_input_readers(terms);
  for (int t = 0; t < static_cast<int>(terms.size()); ++t)
    for (int e = 0; reader_of[t] && e < terms[t]->num_elements(); ++e) {
      const int node = reader_of[t]->normal_force_node(e);
      if (node < 0 || grad[node].dof.empty()) continue;
      Reader r{t, e, node, {}};
      NodeBlock& b = nodes_[node];
      for (int d : terms[t]->stencil(e)) {
        if (!is_dof(d)) {
          r.row.push_back(-1);
          continue;
        }
        auto it = std::find(b.rows.begin(), b.rows.end(), d);
        if (it == b.rows.end()) it = b.rows.insert(b.rows.end(), d);
        r.row.push_back(static_cast<int>(it - b.rows.begin()));
        if (terms[t]->stage() == 0) stage0_rows.push_back(d);
      }
      readers_.push_back(std::move(r));
      const int dof = terms[t]->stencil(e)[0];
      if (terms[t]->stage() == 1 && is_dof(dof)) tangential_.push_back({t, e, dof, {}, {}, 0});
    }
  for (NodeBlock& b : nodes_)
    if (!b.rows.empty()) b.cols.assign(grad[&b - nodes_.data()].dof.begin(), grad[&b - nodes_.data()].dof.end());
  tangential_of_.resize(terms.size());
  for (size_t k = 0; k < tangential_.size(); ++k) {
    const TangentialReader& r = tangential_[k];
    if (std::find(stage0_rows.begin(), stage0_rows.end(), r.dof) != stage0_rows.end())
      throw std::logic_error("ContactChain: a stage-0 reader of F_n acts on a DoF whose F_u is read");
    tangential_of_[r.term].resize(terms[r.term]->num_elements(), -1);
    tangential_of_[r.term][r.element] = static_cast<int>(k);
  }
}

int ContactChain::tangential_index(int t, int e) const {
  if (t < 0 || t >= static_cast<int>(tangential_of_.size()) || e >= static_cast<int>(tangential_of_[t].size()))
    return -1;
  return tangential_of_[t][e];
}

double ContactChain::tangential_directional(int t, int e, const Vec& sq, const Vec& sv) const {
  const int k = tangential_index(t, e);
  if (k < 0 || !have_stage0_) return 0.0;
  const TangentialReader& r = tangential_[k];
  double sum = 0.0;
  for (size_t i = 0; i < r.cols.size(); ++i)
    sum += stage0_dfdq_[r.offset + i] * sq[r.cols[i]] + stage0_dfdv_[r.offset + i] * sv[r.cols[i]];
  return sum;
}

double ContactChain::tangential_parameter_derivative(const TermModel& model, int t, int e, const std::string& key,
                                                     const Vec& q, const Vec& v, const Vec& dfdp) const {
  const int k = tangential_index(t, e);
  if (k < 0) return 0.0;
  const TangentialReader& r = tangential_[k];
  const Term& term = *model.terms()[t];
  const auto keys = term.parameter_keys();
  const auto it = std::find(keys.begin(), keys.end(), key);
  if (it == keys.end()) return dfdp[r.dof];
  const int n = term.stencil_size();
  std::vector<double> lq(n), lv(n), own(n, 0.0);
  model.gather_local(term, e, q, v, lq.data(), lv.data());
  term.parameter_derivative(e, static_cast<int>(it - keys.begin()), lq.data(), lv.data(), own.data());
  return dfdp[r.dof] - own[0];
}

std::vector<std::pair<int, int>> ContactChain::pattern_entries() const {
  std::vector<std::pair<int, int>> out;
  for (const NodeBlock& b : nodes_)
    for (int r : b.rows)
      for (int c : b.cols) out.emplace_back(r, c);
  return out;
}

void ContactChain::bind(const SparseMatrix& pattern) {
  const int* outer = pattern.outerIndexPtr();
  const int* inner = pattern.innerIndexPtr();
  auto slot_of = [&](int row, int col) {
    const int* begin = inner + outer[col];
    const int* end = inner + outer[col + 1];
    const int* it = std::lower_bound(begin, end, row);
    if (it == end || *it != row) throw std::logic_error("ContactChain: pattern lacks a chained entry");
    return static_cast<int>(it - inner);
  };
  for (NodeBlock& b : nodes_) {
    b.slots.clear();
    for (int r : b.rows)
      for (int c : b.cols) b.slots.push_back(slot_of(r, c));
  }
  // Each F_u DoF's row: one pass over the columns.
  std::vector<int> which(pattern.rows(), -1);
  for (size_t k = 0; k < tangential_.size(); ++k) {
    which[tangential_[k].dof] = static_cast<int>(k);
    tangential_[k].cols.clear();
    tangential_[k].slots.clear();
  }
  for (int c = 0; c < pattern.cols(); ++c)
    for (int k = outer[c]; k < outer[c + 1]; ++k)
      if (which[inner[k]] >= 0) {
        tangential_[which[inner[k]]].cols.push_back(c);
        tangential_[which[inner[k]]].slots.push_back(k);
      }
  size_t offset = 0;
  for (TangentialReader& r : tangential_) r.offset = offset, offset += r.slots.size();
  stage0_dfdq_.assign(offset, 0.0);
  stage0_dfdv_.assign(offset, 0.0);
}

void ContactChain::keep_stage0_rows(const AssemblyRequest& req, const Evaluation& out) {
  if (!req.dfdq && !req.dfdv) return;  // keeps the rows of the last evaluation with Jacobians
  have_stage0_ = false;
  if (req.filter == TermFilter::explicit_only || req.filter == TermFilter::mass_only) return;
  for (const TangentialReader& r : tangential_)
    for (size_t k = 0; k < r.slots.size(); ++k) {
      stage0_dfdq_[r.offset + k] = req.dfdq ? out.dfdq.valuePtr()[r.slots[k]] : 0.0;
      stage0_dfdv_[r.offset + k] = req.dfdv ? out.dfdv.valuePtr()[r.slots[k]] : 0.0;
    }
  have_stage0_ = true;
}

void ContactChain::add_jacobians(const TermModel& model, const Vec& q, const Vec& v, const ContactNormals& normals,
                                 const AssemblyRequest& req, Evaluation& out) const {
  if (!req.dfdq && !req.dfdv) return;
  if (req.filter == TermFilter::explicit_only || req.filter == TermFilter::mass_only) return;
  const auto& terms = model.terms();
  const std::vector<const FrozenInputReader*> reader_of = frozen_input_readers(terms);
  const auto& grad = normals.gradient();
  std::vector<double> lq, lv, dfn, dfu;
  std::vector<std::vector<double>> row_weight(nodes_.size());
  std::vector<double> fu_weight(tangential_.size(), 0.0);
  size_t next_tangential = 0;
  for (const Reader& r : readers_) {
    const Term& term = *terms[r.term];
    const int n = term.stencil_size();
    lq.assign(n, 0.0), lv.assign(n, 0.0), dfn.assign(n, 0.0), dfu.assign(n, 0.0);
    model.gather_local(term, r.element, q, v, lq.data(), lv.data());
    reader_of[r.term]->frozen_input_derivatives(r.element, lq.data(), lv.data(), dfn.data(), dfu.data());
    std::vector<double>& w = row_weight[r.node];
    w.resize(nodes_[r.node].rows.size(), 0.0);
    for (int a = 0; a < n; ++a)
      if (r.row[a] >= 0) w[r.row[a]] += dfn[a];
    if (next_tangential < tangential_.size() && tangential_[next_tangential].term == r.term &&
        tangential_[next_tangential].element == r.element)
      fu_weight[next_tangential++] = dfu[0];
  }
  // ∂f/∂q += (∂f/∂F_n) (∂F_n/∂q) per node.
  if (req.dfdq) {
    double* val = out.dfdq.valuePtr();
    for (size_t node = 0; node < nodes_.size(); ++node) {
      const NodeBlock& b = nodes_[node];
      const std::vector<double>& w = row_weight[node];
      if (w.empty()) continue;
      const std::vector<double>& g = grad[node].value;
      const size_t nc = b.cols.size();
      for (size_t r = 0; r < b.rows.size(); ++r)
        if (w[r] != 0.0)
          for (size_t c = 0; c < nc; ++c) val[b.slots[r * nc + c]] += w[r] * g[c];
    }
  }
  // ∂F/∂q, ∂F/∂v += (∂F/∂F_u) × the DoF's row of the stage-0 Jacobians.
  if (!have_stage0_) return;
  for (size_t k = 0; k < tangential_.size(); ++k) {
    const TangentialReader& r = tangential_[k];
    if (fu_weight[k] == 0.0) continue;
    for (size_t i = 0; i < r.slots.size(); ++i) {
      if (req.dfdq) out.dfdq.valuePtr()[r.slots[i]] += fu_weight[k] * stage0_dfdq_[r.offset + i];
      if (req.dfdv) out.dfdv.valuePtr()[r.slots[i]] += fu_weight[k] * stage0_dfdv_[r.offset + i];
    }
  }
}

bool ContactChain::add_parameter_derivative(const TermModel& model, const std::string& key, const Vec& q, const Vec& v,
                                            const std::vector<double>& dfn_dp, Vec& dfdp) const {
  const auto& terms = model.terms();
  const std::vector<const FrozenInputReader*> reader_of = frozen_input_readers(terms);
  std::vector<double> lq, lv, dfn, dfu;
  // ∂F_u/∂p: the stage-0 part of ∂f/∂p on the DoF (the reader's own ∂F/∂p removed).
  std::vector<double> dfu_dp(tangential_.size(), 0.0);
  for (size_t k = 0; k < tangential_.size(); ++k)
    dfu_dp[k] = tangential_parameter_derivative(model, tangential_[k].term, tangential_[k].element, key, q, v, dfdp);
  bool any = false;
  size_t next_tangential = 0;
  for (const Reader& r : readers_) {
    const Term& term = *terms[r.term];
    const int n = term.stencil_size();
    const bool tangential = next_tangential < tangential_.size() && tangential_[next_tangential].term == r.term &&
                            tangential_[next_tangential].element == r.element;
    const double dfu_p = tangential ? dfu_dp[next_tangential++] : 0.0;
    if (dfn_dp[r.node] == 0.0 && dfu_p == 0.0) continue;
    lq.assign(n, 0.0), lv.assign(n, 0.0), dfn.assign(n, 0.0), dfu.assign(n, 0.0);
    model.gather_local(term, r.element, q, v, lq.data(), lv.data());
    reader_of[r.term]->frozen_input_derivatives(r.element, lq.data(), lv.data(), dfn.data(), dfu.data());
    const auto s = term.stencil(r.element);
    for (int a = 0; a < n; ++a)
      if (is_dof(s[a])) {
        const double add = dfn[a] * dfn_dp[r.node] + (a == 0 ? dfu[0] * dfu_p : 0.0);
        dfdp[s[a]] += add;
        any = any || add != 0.0;
      }
  }
  return any;
}

}  // namespace wl
