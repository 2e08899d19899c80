#include "models/knit/image_term.h"

#include <array>
#include <stdexcept>

namespace wl {

ImageTerm::ImageTerm(std::unique_ptr<Term> inner, std::vector<double> shift)
    : inner_(std::move(inner)), shift_(std::move(shift)) {
  const int n = inner_->stencil_size();
  if (n > kMaxStencil || static_cast<int>(shift_.size()) != n * inner_->num_elements())
    throw std::invalid_argument("ImageTerm: one shift per stencil entry of every element expected");
}

ImageTerm::ImageTerm(const ImageTerm& other) : inner_(other.inner_->clone()), shift_(other.shift_) {}

void ImageTerm::shifted(int e, const double* q, double* out) const {
  const int n = inner_->stencil_size();
  for (int a = 0; a < n; ++a) out[a] = q[a] + shift_[static_cast<size_t>(e) * n + a];
}

double ImageTerm::energy(int e, const double* q) const {
  std::array<double, kMaxStencil> s{};
  shifted(e, q, s.data());
  return inner_->energy(e, s.data());
}

void ImageTerm::evaluate(int e, const double* q, const double* v, const ElementOutput& out) const {
  std::array<double, kMaxStencil> s{};
  shifted(e, q, s.data());
  inner_->evaluate(e, s.data(), v, out);
}

double ImageTerm::kinetic_energy(int e, const double* q, const double* v) const {
  std::array<double, kMaxStencil> s{};
  shifted(e, q, s.data());
  return inner_->kinetic_energy(e, s.data(), v);
}

}  // namespace wl
