// A Model that is a list of Terms assembled by the shared Assembly. The yarn
// and FEM models derive from it and only build their terms and frames.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "models/core/assembly.h"
#include "models/core/model.h"

namespace wl {

class TermModel : public Model {
 public:
  int num_dofs() const override { return num_dofs_; }
  Vec initial_q() const override { return q0_; }
  Vec initial_v() const override { return v0_; }
  std::span<const int> fixed_dofs() const override { return fixed_; }
  const SparseMatrix& pattern() const override { return assembly_->pattern(); }
  void evaluate(double t, const Vec& q, const Vec& v, unsigned flags, Evaluation& out) override;
  void evaluate_step(double t, const Vec& q, const Vec& v, const StepWeights& w, Evaluation& scratch, SparseMatrix& a,
                     Vec& r) override;
  double potential_energy(const Vec& q) const override;
  // Σ_e ½ v_eᵀ M_e v_e over the mass terms' elements (no matrix formed).
  double kinetic_energy(double t, const Vec& q, const Vec& v, Evaluation& scratch) override;
  void accept_step(double t, const Vec& q, const Vec& v, double h) override;
  bool projects_step_stiffness() const override;
  bool constrains_steps() const override;
  double admissible_fraction(double t0, const Vec& q0, double t1, const Vec& q1) const override;
  std::vector<std::string> parameter_keys() const override;
  std::vector<std::string> asymmetric_terms() const override;
  bool force_parameter_derivative(const std::string& key, double t, const Vec& q, const Vec& v,
                                  Vec& dfdp) const override;
  bool mass_parameter_product(const std::string& key, const Vec& q, const Vec& w, Vec& out) const override;
  void mass_directional_product(const Vec& q, const Vec& dq, const Vec& w, Vec& out) const override;

  const std::vector<std::unique_ptr<Term>>& terms() const { return terms_; }
  // "name (elements), ..." over the terms, for describe().
  std::string term_counts() const;
  // Per term name (terms of one name summed, in the order of terms()): the
  // potential energy and the power of the force at (t, q, v) [J, W]. The terms'
  // frozen inputs (contact normal forces) are taken at (t, q, v), or kept from
  // the last evaluation when `prepare` is false.
  struct TermReading {
    std::string name;
    double energy_J = 0.0, power_W = 0.0;
    bool conservative = true;  // energy_J is the term's potential
    bool mass = false;         // provides the mass: its energy is the kinetic one
  };
  std::vector<TermReading> term_readings(double t, const Vec& q, const Vec& v, bool prepare = true);
  const Vec& constants() const { return constants_; }
  // Local q and v of element e of a term (constants filled in, their velocity 0).
  void gather_local(const Term& term, int e, const Vec& q, const Vec& v, double* lq, double* lv) const;

 protected:
  TermModel() = default;
  // Copies the data and clones every term (history included), then builds the
  // assembly over the clones: what a derived model's clone() starts from.
  TermModel(const TermModel& other);
  TermModel& operator=(const TermModel&) = delete;

  // Global auxiliary quantities (contact normal forces) at (t, q, v), computed
  // at the start of every evaluation and handed to the terms' prepare() in ctx.
  virtual void prepare_auxiliary(double /*t*/, const Vec& /*q*/, const Vec& /*v*/, EvalContext& /*ctx*/) {}
  // Called after stage 0 and after stage 1 of an evaluation that is not
  // mass-only, with what has been assembled so far: where a model adds the
  // derivatives of its auxiliary quantities (docs/models.md §3.6.1).
  virtual void after_stage(int /*stage*/, const Vec& /*q*/, const Vec& /*v*/, const AssemblyRequest& /*req*/,
                           Evaluation& /*out*/) {}

  // Whether evaluate_step may form the step matrix in one pass: false for a
  // model whose after_stage adds to ∂f/∂q or ∂f/∂v (it needs them apart).
  virtual bool single_pass_step() const { return true; }

  // Derived constructors fill num_dofs_, q0_, v0_, fixed_, constants_ and
  // terms_, then call finalize().
  void finalize();
  // Replaces terms_ by terms of the same kinds and stencils (new parameters)
  // and keeps the assembly (pattern, colouring, slots). Throws
  // std::logic_error when a term's name or stencils differ.
  void replace_terms(std::vector<std::unique_ptr<Term>> terms);

  int num_dofs_ = 0;
  Vec q0_, v0_, constants_;
  std::vector<int> fixed_;
  std::vector<std::unique_ptr<Term>> terms_;
  std::vector<std::pair<int, int>> extra_pattern_;  // entries the pattern holds besides the terms' blocks

 private:
  // Auxiliaries, stage 0, stage 1 (docs/design.md §3.4) into out.force and the given matrices.
  void assemble_stages(double t, const Vec& q, const Vec& v, const AssemblyRequest& req, Evaluation& out,
                       SparseMatrix* dfdq, SparseMatrix* dfdv, SparseMatrix* mass);

  std::unique_ptr<Assembly> assembly_;
  Vec stage0_force_;
};

}  // namespace wl
