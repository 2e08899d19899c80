// One shared assembly for every model (docs/design.md §3.3): gathers
// each element's local state, calls its term and scatters the result into a
// global force vector and matrices that share one sparsity pattern (computed
// once). Elements of a term are coloured so that no two elements of a colour
// touch the same DoF; a colour is evaluated in parallel without locks and the
// summation order is fixed, so results are bitwise reproducible.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "models/core/model.h"
#include "models/core/term.h"

namespace wl {

// Which terms contribute (IMEX split, Term::imex_explicit(); mass_only: the
// terms that provide mass, for M(q) alone).
enum class TermFilter { all, explicit_only, implicit_only, mass_only };

struct AssemblyRequest {
  bool dfdq = false;
  bool dfdv = false;
  bool mass = false;
  TermFilter filter = TermFilter::all;
  // One pass for the implicit step (Model::evaluate_step): each element adds
  // step->mass·M_e + step->dfdv·D_e + step->dfdq·K_e into the `dfdq` matrix
  // argument (A; `dfdv` and `mass` are not written) and, with step->rhs_dfdq
  // ≠ 0, K_e·w_e into *dfdq_w. The flags above are then ignored.
  const StepWeights* step = nullptr;
  Vec* dfdq_w = nullptr;
  // ∂f/∂q for a step matrix formed apart (kStepStiffness): the terms that
  // project their step stiffness do, as they do with `step`.
  bool step_stiffness = false;
};

class Assembly {
 public:
  // `extra`: (row, column) entries the pattern holds besides the terms' blocks
  // (a model's couplings through its auxiliary quantities, docs/models.md §3.6.1).
  Assembly(int num_dofs, std::vector<Term*> terms, const std::vector<std::pair<int, int>>& extra = {});

  int num_dofs() const { return num_dofs_; }
  // Evaluates `terms` from now on in place of the constructor's: they must be
  // as many, with the same names and stencils (new parameters only), so the
  // pattern, colouring and slots stay. Throws std::logic_error otherwise.
  void rebind(const std::vector<Term*>& terms);
  // Pattern shared by mass, ∂f/∂q and ∂f/∂v: the union of all stencil blocks
  // plus the full diagonal. Values are zero.
  const SparseMatrix& pattern() const { return pattern_; }

  // Adds the contributions of every term of the given stage to f and, where
  // requested, to the matrices (which must have pattern()'s structure).
  void add_stage(int stage, const Vec& q, const Vec& v, const Vec& constants, const AssemblyRequest& req, Vec& f,
                 SparseMatrix* dfdq, SparseMatrix* dfdv, SparseMatrix* mass) const;

  // Potential energy of all conservative terms.
  double energy(const Vec& q, const Vec& constants) const;
  // Kinetic energy ½ vᵀ M(q) v summed over the mass terms' elements (v is
  // zero on constants).
  double kinetic_energy(const Vec& q, const Vec& v, const Vec& constants) const;
  // Per term, in the order given to the constructor: its energy (conservative
  // terms; 0 otherwise) and the power of its force, Σ_e f_e · v_e [J, W]. The
  // terms must have been prepared at (q, v) (Model::evaluate does it).
  void term_energies_and_powers(const Vec& q, const Vec& v, const Vec& constants, std::vector<double>& energy,
                                std::vector<double>& power) const;

  // Adds ∂f/∂p for the parameter `key` (Term::parameter_keys()) of every term
  // that depends on it into `dfdp`; returns whether any term does.
  bool add_parameter_derivative(const std::string& key, const Vec& q, const Vec& v, const Vec& constants,
                                Vec& dfdp) const;
  // Adds (∂M/∂p)·w for the parameter `key` into `out`; returns whether any
  // mass-providing term depends on it.
  bool add_mass_parameter_product(const std::string& key, const Vec& q, const Vec& w, const Vec& constants,
                                  Vec& out) const;
  // Adds ((∂M/∂q)·dq)·w into `out` (constants do not move: dq is zero there).
  void add_mass_directional_product(const Vec& q, const Vec& dq, const Vec& w, const Vec& constants, Vec& out) const;

 private:
  struct TermPlan {
    Term* term;
    int n;
    std::vector<int> colour_start;  // elements sorted by colour: order[colour_start[c] .. colour_start[c+1])
    std::vector<int> order;
    // Where each element's n×n block goes in pattern_'s values: per stencil
    // column b the start of column s[b] (−1 for a constant), per entry (a, b)
    // the row's place in that column (0xFFFF for a constant), b-major.
    std::vector<int> column_start;
    std::vector<std::uint16_t> row_place;
    bool has_constants = false;  // some stencil holds a constant
  };
  void add_term(const TermPlan& plan, const Vec& q, const Vec& v, const Vec& constants, const AssemblyRequest& req,
                Vec& f, SparseMatrix* dfdq, SparseMatrix* dfdv, SparseMatrix* mass) const;

  int num_dofs_;
  SparseMatrix pattern_;
  std::vector<TermPlan> plans_;
};

}  // namespace wl
