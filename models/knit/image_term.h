// A term over periodic images (docs/models.md §11.3): wraps any term and adds a
// constant shift per element and local entry to the gathered state before the
// wrapped term sees it. The tile of a knit pattern uses it for elements that
// reach across the tile's border (a node's image is the node shifted by the
// tile's period, a yarn's coordinate there by its arc length per period).
// A constant shift changes neither the force nor its derivatives in q and v.
#pragma once
#include <memory>
#include <vector>

#include "models/core/term.h"

namespace wl {

class ImageTerm : public Term {
 public:
  // `shift`: stencil_size() values per element of `inner`, in element order.
  ImageTerm(std::unique_ptr<Term> inner, std::vector<double> shift);
  ImageTerm(const ImageTerm& other);

  std::unique_ptr<Term> clone() const override { return std::make_unique<ImageTerm>(*this); }
  std::string name() const override { return inner_->name(); }
  int stencil_size() const override { return inner_->stencil_size(); }
  int num_elements() const override { return inner_->num_elements(); }
  std::span<const int> stencil(int e) const override { return inner_->stencil(e); }
  bool conservative() const override { return inner_->conservative(); }
  bool has_velocity_jacobian() const override { return inner_->has_velocity_jacobian(); }
  bool provides_mass() const override { return inner_->provides_mass(); }
  bool imex_explicit() const override { return inner_->imex_explicit(); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  double kinetic_energy(int e, const double* q, const double* v) const override;

 private:
  static constexpr int kMaxStencil = 32;
  void shifted(int e, const double* q, double* out) const;
  std::unique_ptr<Term> inner_;
  std::vector<double> shift_;
};

}  // namespace wl
