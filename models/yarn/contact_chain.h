// The exact derivatives of the frozen inputs F_n and F_u chained into a yarn
// model's Jacobians and parameter derivatives (docs/models.md §3.6.1, §9.1):
//   ∂f_e/∂q += ∂f_e/∂F_n · ∂F_n/∂q                       (Gong's shear, friction)
//   ∂F/∂q   += ∂F/∂F_u · ∂F_u/∂q,  ∂F/∂v += ∂F/∂F_u · ∂F_u/∂v   (friction; ∂F_u/∂q,
//              ∂F_u/∂v: the DoF's row of the stage-0 Jacobians)
//   ∂f_e/∂p += ∂f_e/∂F_n · ∂F_n/∂p (+ ∂F/∂F_u · ∂F_u/∂p, the stage-0 ∂f/∂p on the DoF).
// The couplings reach beyond the terms' stencils (∂F_n/∂q spans about thirty
// nodes), so the model's pattern holds pattern_entries() as well.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "models/core/term_model.h"
#include "models/yarn/contact_normals.h"

namespace wl {

class ContactChain {
 public:
  // `normals`: after compute_gradient() at any state (the rows' structure does
  // not depend on it). Stage-0 readers of F_n must put no force on a DoF whose
  // F_u a stage-1 term reads (throws std::logic_error otherwise).
  ContactChain(const std::vector<std::unique_ptr<Term>>& terms, const ContactNormals& normals);

  std::vector<std::pair<int, int>> pattern_entries() const;
  // Maps the entries to value slots of the model's pattern.
  void bind(const SparseMatrix& pattern);

  // After stage 0: keeps the F_u DoFs' rows of the stage-0 Jacobians.
  void keep_stage0_rows(const AssemblyRequest& req, const Evaluation& out);
  // After stage 1: adds the chained derivatives into out.dfdq and out.dfdv.
  void add_jacobians(const TermModel& model, const Vec& q, const Vec& v, const ContactNormals& normals,
                     const AssemblyRequest& req, Evaluation& out) const;
  // dfdp holds the terms' own ∂f/∂p for `key`; adds the chain with ∂F_n/∂p per
  // node (dfn_dp). Returns whether it added anything non-zero.
  bool add_parameter_derivative(const TermModel& model, const std::string& key, const Vec& q, const Vec& v,
                                const std::vector<double>& dfn_dp, Vec& dfdp) const;
  // ∂F_u/∂q·sq + ∂F_u/∂v·sv for the F_u that element e of term t reads, from
  // the stage-0 rows of the last evaluation with Jacobians (0 when it reads none).
  double tangential_directional(int t, int e, const Vec& sq, const Vec& sv) const;
  // ∂F_u/∂p: the stage-0 part of dfdp (the terms' own ∂f/∂p for `key`) on the
  // DoF whose F_u element e of term t reads.
  double tangential_parameter_derivative(const TermModel& model, int t, int e, const std::string& key, const Vec& q,
                                         const Vec& v, const Vec& dfdp) const;

 private:
  struct Reader {
    int term, element, node;
    std::vector<int> row;  // per local entry: index into the node's rows, −1 for constants
  };
  struct NodeBlock {
    std::vector<int> rows, cols;  // global DoFs; cols = the node's ∂F_n/∂q entries
    std::vector<int> slots;       // rows.size() × cols.size(), row-major
  };
  struct TangentialReader {
    int term, element, dof;
    std::vector<int> cols, slots;  // the DoF's row in the pattern
    size_t offset = 0;             // into stage0_*_
  };
  std::vector<Reader> readers_;
  std::vector<NodeBlock> nodes_;             // per node id
  int tangential_index(int t, int e) const;  // into tangential_, −1: element e of term t reads no F_u
  std::vector<TangentialReader> tangential_;
  std::vector<std::vector<int>> tangential_of_;  // per term, per element: index into tangential_ or −1
  std::vector<double> stage0_dfdq_, stage0_dfdv_;
  bool have_stage0_ = false;
};

}  // namespace wl
