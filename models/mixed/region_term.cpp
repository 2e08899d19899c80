#include "models/mixed/region_term.h"

#include <stdexcept>

namespace wl {

RegionTerm::RegionTerm(std::unique_ptr<Term> term, std::vector<Element> elements)
    : term_(std::move(term)), elements_(std::move(elements)) {
  if (term_->constrains_steps())
    throw std::logic_error("RegionTerm: term '" + term_->name() + "' constrains steps (not carried over)");
  for (const Element& el : elements_)
    if (static_cast<int>(el.stencil.size()) != term_->stencil_size())
      throw std::logic_error("RegionTerm: a stencil of term '" + term_->name() + "' has the wrong size");
}

RegionTerm::RegionTerm(const RegionTerm& other)
    : Term(other), term_(other.term_->clone()), elements_(other.elements_) {}

double RegionTerm::energy(int e, const double* q) const {
  const Element& el = elements_[e];
  return el.share * term_->energy(el.element, q);
}

// The outputs arrive zero-filled (term.h, assembly.cpp) and hold this element's alone: scaled in place.
void RegionTerm::evaluate(int e, const double* q, const double* v, const ElementOutput& out) const {
  const Element& el = elements_[e];
  term_->evaluate(el.element, q, v, out);
  if (el.share == 1.0) return;
  const int n = stencil_size();
  auto scale = [&](double* x, int count) {
    if (x)
      for (int a = 0; a < count; ++a) x[a] *= el.share;
  };
  scale(out.force, n);
  scale(out.dfdq, n * n);
  scale(out.dfdv, n * n);
  scale(out.mass, n * n);
}

double RegionTerm::kinetic_energy(int e, const double* q, const double* v) const {
  const Element& el = elements_[e];
  return el.share * term_->kinetic_energy(el.element, q, v);
}

void RegionTerm::parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const {
  const Element& el = elements_[e];
  std::vector<double> d(stencil_size(), 0.0);
  term_->parameter_derivative(el.element, k, q, v, d.data());
  for (size_t a = 0; a < d.size(); ++a) dfdp[a] += el.share * d[a];
}

void RegionTerm::mass_parameter_derivative(int e, int k, const double* q, double* dmdp) const {
  const Element& el = elements_[e];
  std::vector<double> d(static_cast<size_t>(stencil_size()) * stencil_size(), 0.0);
  term_->mass_parameter_derivative(el.element, k, q, d.data());
  for (size_t a = 0; a < d.size(); ++a) dmdp[a] += el.share * d[a];
}

}  // namespace wl
