#include "driver/energy_split.h"

#include <array>

#include "models/core/term_model.h"
#include "models/fem/fem_model.h"
#include "models/fem/terms/tile_bending.h"
#include "models/fem/terms/tile_membrane.h"
#include "models/yarn/yarn_model.h"

namespace wl {
namespace {

// Energy of element e of `term` at q (constant stencil entries from `constants`).
double element_energy(const Term& term, int e, const Vec& q, const Vec& constants, std::vector<double>& local) {
  const std::span<const int> s = term.stencil(e);
  local.resize(s.size());
  for (size_t k = 0; k < s.size(); ++k) local[k] = is_dof(s[k]) ? q[s[k]] : constants[constant_slot(s[k])];
  return term.energy(e, local.data());
}

// Sum of the energies of the elements of `term` at q.
double energy_of_term(const Term& term, const Vec& q, const Vec& constants) {
  std::vector<double> local;
  double sum = 0;
  for (int e = 0; e < term.num_elements(); ++e) sum += element_energy(term, e, q, constants, local);
  return sum;
}

// Sum of the energies of the terms named `name` at q.
double term_energy(const TermModel& model, const std::string& name, const Vec& q) {
  double sum = 0;
  for (const auto& term : model.terms())
    if (term->name() == name) sum += energy_of_term(*term, q, model.constants());
  return sum;
}

// The strains of a tile law along each direction (kTileLawStrainNames): ε_u, κ_u; ε_v, κ_v.
constexpr std::array<bool, 6> kWarpStrains{true, false, false, true, false, false};
constexpr std::array<bool, 6> kWeftStrains{false, true, false, false, true, false};

// Yarn level: warp and weft parts by the yarn of each element; its first two
// nodes (stencil entries 0 and 3, the x of two neighbours on one yarn) share
// j on a warp and i on a weft (docs/models.md §2.1, §2.4).
std::vector<EnergyPart> yarn_parts(const YarnModel& yarn, const Vec& q) {
  std::vector<int> row_of_x(yarn.num_dofs(), -1);
  for (int n = 0; n < yarn.grid().num_nodes(); ++n) row_of_x[yarn.grid().dofs(n).x] = n / yarn.grid().nu();
  std::vector<EnergyPart> out;
  std::vector<double> local;
  for (const char* name : {"stretch", "bending"}) {
    std::array<double, 2> part{0, 0};  // warp, weft
    bool present = false;
    for (const auto& term : yarn.terms()) {
      if (term->name() != name) continue;
      present = true;
      for (int e = 0; e < term->num_elements(); ++e) {
        const std::span<const int> s = term->stencil(e);
        const bool warp = row_of_x[s[0]] == row_of_x[s[3]];
        part[warp ? 0 : 1] += element_energy(*term, e, q, yarn.constants(), local);
      }
    }
    if (!present) continue;
    out.push_back({name, true, part[0]});
    out.push_back({name, false, part[1]});
  }
  return out;
}

}  // namespace

EnergySplit::EnergySplit(const Model& model, const Scene& scene) {
  if (const auto* fem = dynamic_cast<const FemModel*>(&model)) {
    FemMaterial warp = fem->material(), weft = fem->material();
    warp.weft_stretch_N_per_m = warp.weft_bending_N_m = 0.0;
    weft.warp_stretch_N_per_m = weft.warp_bending_N_m = 0.0;
    warp_only_ = std::make_unique<FemModel>(scene, fem->mesh(), warp);
    weft_only_ = std::make_unique<FemModel>(scene, fem->mesh(), weft);
    for (const auto& term : fem->terms()) {
      if (const auto* m = dynamic_cast<const TileMembraneTerm*>(term.get()))
        tile_parts_.push_back(
            {m->with_law(std::make_shared<const TileMembraneLaw>(m->law().restricted(kWarpStrains))),
             m->with_law(std::make_shared<const TileMembraneLaw>(m->law().restricted(kWeftStrains)))});
      if (const auto* b = dynamic_cast<const TileBendingTerm*>(term.get()))
        tile_parts_.push_back({b->with_law(std::make_shared<const TileBendingLaw>(b->law().restricted(kWarpStrains))),
                               b->with_law(std::make_shared<const TileBendingLaw>(b->law().restricted(kWeftStrains)))});
    }
  }
}

EnergySplit::~EnergySplit() = default;

std::vector<EnergyPart> EnergySplit::parts(const Model& model, const Vec& q) const {
  if (const auto* yarn = dynamic_cast<const YarnModel*>(&model)) return yarn_parts(*yarn, q);
  std::vector<EnergyPart> out;
  if (!warp_only_) return out;
  const auto& warp = dynamic_cast<const TermModel&>(*warp_only_);
  const auto& weft = dynamic_cast<const TermModel&>(*weft_only_);
  for (const char* name : {"fem-stretch", "fem-bending"}) {
    bool present = false;
    for (const auto& term : warp.terms()) present = present || term->name() == name;
    if (!present) continue;
    out.push_back({name, true, term_energy(warp, name, q)});
    out.push_back({name, false, term_energy(weft, name, q)});
  }
  const Vec& constants = dynamic_cast<const TermModel&>(model).constants();
  for (const TileTermParts& t : tile_parts_) {
    out.push_back({t.warp->name(), true, energy_of_term(*t.warp, q, constants)});
    out.push_back({t.weft->name(), false, energy_of_term(*t.weft, q, constants)});
  }
  return out;
}

}  // namespace wl
