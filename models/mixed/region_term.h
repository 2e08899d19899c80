// Some elements of another model's term, each scaled by its share of the cloth
// and with its stencil moved to the mixed cloth's DoFs (docs/models.md §12.3):
// how the mixed model takes the continuum's terms without copying their code.
// Energy, force, Jacobians, mass and parameter derivatives are the wrapped
// element's times its share. The wrapped term may read the evaluation's time
// from prepare() (handles), not the state: its own stencils are the other
// model's.
#pragma once
#include <memory>
#include <vector>

#include "models/core/term.h"

namespace wl {

class RegionTerm : public Term {
 public:
  struct Element {
    int element;               // in the wrapped term
    double share;              // in (0, 1]
    std::vector<int> stencil;  // the wrapped element's stencil in the mixed cloth's DoFs
  };
  // Throws std::logic_error for a term that constrains steps or an element whose stencil size differs.
  RegionTerm(std::unique_ptr<Term> term, std::vector<Element> elements);
  RegionTerm(const RegionTerm& other);

  std::unique_ptr<Term> clone() const override { return std::make_unique<RegionTerm>(*this); }
  std::string name() const override { return term_->name(); }
  int stencil_size() const override { return term_->stencil_size(); }
  int num_elements() const override { return static_cast<int>(elements_.size()); }
  std::span<const int> stencil(int e) const override { return elements_[e].stencil; }
  bool conservative() const override { return term_->conservative(); }
  bool has_velocity_jacobian() const override { return term_->has_velocity_jacobian(); }
  bool provides_mass() const override { return term_->provides_mass(); }
  int stage() const override { return term_->stage(); }
  bool symmetric_jacobian() const override { return term_->symmetric_jacobian(); }
  bool projects_step_stiffness() const override { return term_->projects_step_stiffness(); }
  bool imex_explicit() const override { return term_->imex_explicit(); }
  void prepare(const EvalContext& ctx) override { term_->prepare(ctx); }
  void accept_step(const EvalContext& ctx, double h) override { term_->accept_step(ctx, h); }

  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  double kinetic_energy(int e, const double* q, const double* v) const override;
  std::vector<std::string> parameter_keys() const override { return term_->parameter_keys(); }
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;
  void mass_parameter_derivative(int e, int k, const double* q, double* dmdp) const override;

 private:
  std::unique_ptr<Term> term_;
  std::vector<Element> elements_;
};

}  // namespace wl
