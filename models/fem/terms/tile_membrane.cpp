#include "models/fem/terms/tile_membrane.h"

#include "models/fem/terms/membrane_strains.h"

namespace wl {
TileMembraneTerm::TileMembraneTerm(std::shared_ptr<const TileMembraneLaw> law) : law_(std::move(law)) {}

void TileMembraneTerm::add(const std::array<int, 9>& stencil, const TriangleRest& rest) {
  stencils_.push_back(stencil);
  rest_.push_back(rest);
}

double TileMembraneTerm::energy(int e, const double* q) const {
  const TriangleRest& r = rest_[e];
  const MembraneStrains st = membrane_strains(warp_vector(r, q), weft_vector(r, q), false);
  if (!st.valid) return 0.0;
  double w;
  law_->evaluate(st.m, &w, nullptr, nullptr);
  return r.area * w;
}

void TileMembraneTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const TriangleRest& r = rest_[e];
  const MembraneStrains st = membrane_strains(warp_vector(r, q), weft_vector(r, q), out.dfdq != nullptr);
  if (!st.valid) return;  // collapsed or folded: the strains are undefined, no force
  double w;
  std::array<double, 3> g;
  std::array<double, 9> h;
  law_->evaluate(st.m, &w, &g, out.dfdq ? &h : nullptr);
  Vec3 fu = Vec3::Zero(), fv = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    fu += g[k] * st.gu[k];
    fv += g[k] * st.gv[k];
  }
  add_column_gradient(r, fu, fv, -r.area, out.force);
  if (!out.dfdq) return;
  Mat3 huu = Mat3::Zero(), huv = Mat3::Zero(), hvv = Mat3::Zero();
  for (int k = 0; k < 3; ++k) {
    huu += g[k] * st.huu[k];
    huv += g[k] * st.huv[k];
    hvv += g[k] * st.hvv[k];
    for (int l = 0; l < 3; ++l) {
      const double hkl = h[3 * k + l];
      huu += hkl * st.gu[k] * st.gu[l].transpose();
      huv += hkl * st.gu[k] * st.gv[l].transpose();
      hvv += hkl * st.gv[k] * st.gv[l].transpose();
    }
  }
  add_column_hessian(r, huu, huv, hvv, -r.area, out.dfdq);
}

std::unique_ptr<TileMembraneTerm> TileMembraneTerm::with_law(std::shared_ptr<const TileMembraneLaw> law) const {
  auto t = std::make_unique<TileMembraneTerm>(*this);
  t->law_ = std::move(law);
  return t;
}

std::vector<std::string> TileMembraneTerm::parameter_keys() const {
  std::vector<std::string> keys;
  for (int i = 0; i < law_->size(); ++i) keys.push_back("fem.tile_law." + law_->name(i));
  return keys;
}

void TileMembraneTerm::parameter_derivative(int e, int k, const double* q, const double*, double* dfdp) const {
  const TriangleRest& r = rest_[e];
  const MembraneStrains st = membrane_strains(warp_vector(r, q), weft_vector(r, q), false);
  if (!st.valid) return;
  double w;
  std::array<double, 3> g;
  law_->evaluate_unit(k, st.m, &w, &g);
  Vec3 fu = Vec3::Zero(), fv = Vec3::Zero();
  for (int j = 0; j < 3; ++j) {
    fu += g[j] * st.gu[j];
    fv += g[j] * st.gv[j];
  }
  add_column_gradient(r, fu, fv, -r.area, dfdp);
}

}  // namespace wl
