// The periodic tile of a woven fabric under a prescribed macroscopic
// deformation (docs/calibration.md §9): the smallest block of crossings that
// repeats the pattern and the yarn types, its nodes' images across the tile's
// border placed by the macroscopic map φ, with the yarn level's material terms
// (stretch, bending, shear) on the yarns through it. Sliding is frozen, as in
// the virtual tests (docs/calibration.md §1).
//
// The macroscopic map about the tile centre, of the six strains
// θ = (ε_u, ε_v, γ, κ_u, κ_v, κ_uv) (docs/calibration.md §9.1):
//   φ(X) = A X + ½ s n − (1/6) A G⁻¹ (B X) s,   s = XᵀB X,  G = AᵀA,
//   A = [(1+ε_u)(cos γ/2, sin γ/2, 0), (1+ε_v)(sin γ/2, cos γ/2, 0)],  n = e_z,
//   B = [[κ_u, κ_uv], [κ_uv, κ_v]]  (the material second fundamental form),
// turned by a rotation Q. The cubic term keeps the first fundamental form
// exact to O(|X|³) wherever det B = 0 (a cylinder); a Gaussian curvature
// leaves a metric error (1/3)((BX)(BX)ᵀ − B s), of order κ²|X|² at the tile's nodes.
//
// An image of node k shifted by the lattice vector D is the node's position
// plus the constant φ(X_k + D) − φ(X_k): its fluctuation is periodic. Node 0
// is held at its rest place (the rigid translation); the map fixes rotation.
// F_n of Gong's shear is frozen at its value on the flat fabric at rest, so the
// tile's energy is an exact potential (docs/calibration.md §9.2).
#pragma once
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "models/core/term_model.h"
#include "models/scene/scene.h"

namespace wl {

// θ = (ε_u, ε_v, γ, κ_u, κ_v, κ_uv): strains [-], shear angle [rad], curvatures [1/m].
using MacroStrain = std::array<double, 6>;
inline constexpr std::array<const char*, 6> kMacroStrainNames{"stretch_warp",   "stretch_weft",   "shear",
                                                              "curvature_warp", "curvature_weft", "twist"};
using StrainJacobian = Eigen::Matrix<double, 3, 6>;

// φ(X) (unrotated) and, when `dphi` is given, ∂φ/∂θ (exact, forward-mode AD).
Vec3 macro_map(const MacroStrain& theta, const Vec2& X, StrainJacobian* dphi = nullptr);

// The tile: crossings (i, j), i along the warp (0 … nu − 1), j along the weft.
struct WovenTileSize {
  int nu = 0, nv = 0;
};
// The smallest tile that repeats the pattern's over/under signs and both yarn
// type cycles; std::invalid_argument for a knit scene.
WovenTileSize woven_tile_size(const Scene& scene);

class WovenTileModel : public TermModel {
 public:
  WovenTileModel(const Scene& scene, const MacroStrain& theta, const Mat3& rotation = Mat3::Identity());
  std::unique_ptr<Model> clone() const override { return std::make_unique<WovenTileModel>(*this); }
  std::string name() const override { return "woven-tile"; }
  bool mass_depends_on_q() const override { return false; }
  Frame frame(double t, const Vec& q, const Vec& v) const override;
  std::map<std::string, std::string> describe() const override;

  const WovenTileSize& size() const { return size_; }
  // The tile's rest area nu·nv·L² [m²].
  double rest_area() const;
  // ∂E/∂θ at fixed q [J per unit of θ]: the images' forces on their shifts,
  //   ∂E/∂θ_k = −Σ_e Σ_a f_{e,a} ∂s_{e,a}/∂θ_k.
  Eigen::Matrix<double, 1, 6> strain_partial(const Vec& q) const;

 private:
  struct Image {  // a crossing of the lattice: its tile node and lattice offset
    int node, m, n;
    Vec2 X;  // its material place about the tile centre [m]
  };
  // One element's stencil entries, their shifts and ∂shift/∂θ (6 per entry).
  struct Entries {
    std::vector<int> dofs;
    std::vector<double> shift, dshift;
    void position(const WovenTileModel& tile, const Image& image);
    void coordinate(const WovenTileModel& tile, const Image& image, bool warp);
  };
  Image image(int i, int j) const;
  void set_state();
  // Wraps `term` in an ImageTerm with the elements' shifts and keeps their ∂shift/∂θ.
  void add_term(std::unique_ptr<Term> term, const std::vector<Entries>& elements);
  void add_stretch();
  void add_bending();
  void add_shear();
  std::vector<double> rest_normal_force() const;

  Scene scene_;
  WovenTileSize size_;
  MacroStrain theta_;
  Mat3 rotation_;
  std::vector<std::vector<double>> dshift_;  // per term: per element entry, 6 values
};

}  // namespace wl
