// A zero-rest-length penalty spring holding a point at an anchor (scene
// handles, docs/models.md §3.10). Model agnostic:
// local stencil x[3] of any point (yarn node or mesh vertex).
//   V = ½ k ‖x − anchor‖²
#pragma once
#include <array>
#include <string>
#include <vector>

#include "models/core/term.h"

namespace wl {

class HandleSpringTerm : public StencilTerm<3> {
 public:
  // One handle; anchor in m, stiffness k in N/m (≥ 0).
  void add(const std::array<int, 3>& stencil, const Vec3& anchor, double k);

  std::string name() const override { return "handles"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<HandleSpringTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  std::vector<Vec3> anchor_;
  std::vector<double> k_;
};

}  // namespace wl
