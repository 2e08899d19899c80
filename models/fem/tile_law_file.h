// The tile law of a woven fabric as the continuum reads it (docs/models.md §6.9):
// the file `tile_law.csv` that `weavelab tiles` writes (docs/calibration.md §9.3),
// one "name,value" row per quantity after the header "name,value":
//   energy_scale_J_per_m2    W₀ > 0
//   scale:<strain>           s_k > 0, the normalization t_k = θ_k / s_k
//   lo:<strain>, hi:<strain> the sampled range of θ_k, lo ≤ 0 ≤ hi, lo < hi (lo: first)
//   <monomial>               its coefficient c_i, e.g. "stretch_warp^2*shear"
// for the six strains of kMacroStrainNames (calibration/woven_tile.h):
// stretch_warp, stretch_weft, shear, curvature_warp, curvature_weft, twist.
// The law is W(θ) = W₀ Σ_i c_i Π_k t_k^{e_ik}. Every name, number and monomial
// is checked: a bad row is a FemParameterError "<file>:<line>: ..." (exit 2).
//
// The continuum splits W as it discretizes (docs/models.md §6.9):
//   membrane  W_m(ε_u, ε_v, γ) = W(ε_u, ε_v, γ, 0, 0, 0), per triangle
//             (terms/tile_membrane.h), extended beyond the sampled box;
//   bending   the monomials with a curvature, per triangle with its curvature
//             from the dihedral angles of its edges (tile_bending_law.h,
//             terms/tile_bending.h, docs/models.md §6.9.1); their quadratic part at
//             zero membrane strain, k_warp = ∂²W/∂κ_u²(0) = 2W₀c[κ_u²]/s_κu² and
//             k_weft likewise, are the bending stiffnesses a parameter file would give.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "models/fem/tile_law_continuation.h"
#include "models/scene/scene.h"

namespace wl {

// The largest exponent of a monomial of a tile law.
inline constexpr int kTileLawMaxPower = 12;

// ∂ⁿ/∂tⁿ of t^e: e(e−1)…(e−n+1) t^{e−n}, from the powers t^0 … t^kTileLawMaxPower.
inline double power_derivative(const double* powers, int e, int n) {
  if (n > e) return 0.0;
  double f = 1.0;
  for (int i = 0; i < n; ++i) f *= e - i;
  return f * powers[e - n];
}

inline constexpr std::array<const char*, 6> kTileLawStrainNames{"stretch_warp",   "stretch_weft",   "shear",
                                                                "curvature_warp", "curvature_weft", "twist"};

struct TileLawMonomial {
  std::array<int, 6> exponent{};
  double coefficient = 0.0;
  int line = 0;  // its row in the file
};

struct TileLawFile {
  std::string source;
  double energy_scale = 0.0;         // W₀ [J/m²]
  std::array<double, 6> scale{};     // s_k
  std::array<double, 6> lo{}, hi{};  // the sampled box of θ
  std::vector<TileLawMonomial> terms;
  // ∂²W/∂κ²(0) along warp (κ_u) and weft (κ_v) [N·m].
  double warp_bending_N_m() const;
  double weft_bending_N_m() const;
};

// The yarn level's total yarn mass over the crossing grid's area [kg/m²], the
// mass `weavelab calibrate` gives the continuum (driver/calibrate.h); a tile law
// carries no mass, so its continuum takes this one (docs/models.md §6.9).
double yarn_matched_areal_density(const Scene& scene);
// True when `path` names a tile law: its first line is "name,value" (a FEM
// parameter file is TOML, which cannot start so). False for "" or an unreadable file.
bool is_tile_law_file(const std::string& path);
// The tile law the continuum runs: [fem] tile_law, else a parameter file that is a tile
// law (docs/models.md §6.9); "" for none.
std::string tile_law_path(const FemSettings& fem);
// Reads and checks `path`; FemParameterError (models/fem/fem_material.h) on any bad row,
// and unless the rows curvature_warp^2 and curvature_weft^2 give positive bending at rest.
TileLawFile read_tile_law_file(const std::string& path);
TileLawFile parse_tile_law(const std::string& text, const std::string& source);

// The membrane restriction W_m(m), m = (ε_u, ε_v, γ), with its gradient and
// Hessian in m (docs/models.md §6.9). Inside the sampled box it is the
// polynomial; outside, with p the nearest point of the box and d = m − p,
//   W_m = P(p) + ∇P(p)·d + ½ Σ_k h_k d_k²,   h_k = ∂²P/∂m_k²(0) > 0,
// C¹ across the box's faces (the Hessian jumps there).
class TileMembraneLaw {
 public:
  TileMembraneLaw() = default;
  // Throws FemParameterError unless every h_k > 0 (the law is stiff at rest).
  explicit TileMembraneLaw(const TileLawFile& law);
  void evaluate(const std::array<double, 3>& m, double* w, std::array<double, 3>* g, std::array<double, 9>* h) const;
  // The same for the law with the coefficient of membrane monomial i set to 1 and
  // every other to 0: ∂W_m/∂c_i, exact also outside the box (h_k = 2c[m_k²] is linear in c).
  void evaluate_unit(int i, const std::array<double, 3>& m, double* w, std::array<double, 3>* g) const;
  int size() const { return static_cast<int>(exponent_.size()); }
  // The law of the monomials whose strains all lie in `strains` (indexed as kTileLawStrainNames),
  // every other coefficient 0. W_m is linear in the coefficients, its continuation too, so the
  // laws of disjoint sets of monomials sum to the law.
  TileMembraneLaw restricted(const std::array<bool, 6>& strains) const;
  // "stretch_warp^2*shear" for membrane monomial i.
  std::string name(int i) const;

 private:
  // Derivatives of Σ c_i t^{e_i} (normalized t) at t: value, gradient, Hessian, third derivatives.
  void polynomial(const double* c, const std::array<double, 3>& t, double* p, double* g, double* h,
                  double* third) const;
  // The law of coefficients c continued beyond the box with face curvatures h_k (tile_law_continuation.h).
  void extend(const double* c, const std::array<double, 3>& curvature, const std::array<double, 3>& m, double* w,
              std::array<double, 3>* g, std::array<double, 9>* h) const;
  TileLawBox<3> box_;
  std::array<double, 3> rest_curvature_{};  // h_k in t
  std::vector<std::array<int, 3>> exponent_;
  std::vector<double> coefficient_;
};

}  // namespace wl
