// The stretch and bending energies of a yarn-level or continuum model split
// into the part carried along the warp and the part along the weft
// (docs/design.md §7.6), for `weavelab diagnose`:
//   yarn level  each stretch segment and bending triple lies on one yarn: a
//               warp (its nodes share j) or a weft (they share i);
//   continuum   the triangle stretch energy and the hinge bending energy are
//               linear in (k_warp, k_weft) (docs/models.md §6.3, §6.5), so the
//               warp part is the energy of the same model with the weft
//               stiffness set to 0, and the other way round;
//   tile law    the membrane and the curvature part per triangle are linear in
//               the law's coefficients (docs/models.md §6.9), so the warp part
//               is the energy of the law's monomials in ε_u and κ_u alone, the
//               weft part that of its monomials in ε_v and κ_v alone.
// The two parts sum to the term's energy, except for the tile law, whose
// monomials with a shear, a twist, or strains of both directions are in
// neither. The continuum's border bars (fem-border-stretch) are not split.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "models/core/model.h"
#include "models/core/term.h"
#include "models/scene/scene.h"

namespace wl {

struct EnergyPart {
  std::string term;  // "stretch", "bending", "fem-stretch", "fem-bending", "fem-tile-membrane", "fem-tile-bending"
  bool warp = true;  // the warp part (else the weft part)
  double energy_J = 0.0;
};

class EnergySplit {
 public:
  // For a YarnModel or a FemModel (built from `scene`); another model has nothing to split.
  EnergySplit(const Model& model, const Scene& scene);
  ~EnergySplit();
  // Warp then weft part of every split term of `model` (the model given to
  // the constructor, or one built the same way) at q, stretch before bending.
  std::vector<EnergyPart> parts(const Model& model, const Vec& q) const;

 private:
  std::unique_ptr<Model> warp_only_, weft_only_;  // continuum: the other direction's stiffness 0
  struct TileTermParts {
    std::unique_ptr<Term> warp, weft;  // a tile-law term under its warp and its weft monomials
  };
  std::vector<TileTermParts> tile_parts_;
};

}  // namespace wl
