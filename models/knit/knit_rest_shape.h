// The rest shape of a knit (docs/models.md §11.3): the pattern's smallest
// repeating tile, periodic in both directions, relaxed without gravity to
// static equilibrium (Newton's method on the assembled stiffness with a
// Levenberg–Marquardt shift and energy descent), then tiled over the cloth.
// The period is the generated one; relax_knit_period() relaxes it too (its
// two lattice lengths) until the net force conjugate to each vanishes (§11.3.1).
// Cached in memory per pattern and parameters.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "models/core/types.h"
#include "models/scene/scene.h"

namespace wl {

struct KnitRestShape {
  int courses = 0, wales = 0;           // the tile
  std::vector<Vec3> dx;                 // per tile node: relaxed − generated position [m]
  std::vector<std::vector<double>> du;  // per tile node and slot: relaxed − generated coordinate [m]
  double residual_N = 0.0;              // ‖f‖∞ over the tile's free DoFs at the relaxed state
  int iterations = 0;                   // Newton steps (all of them, over every period tried)
  double energy_generated_J = 0.0, energy_relaxed_J = 0.0;
  // The period relative to the generated one (wales·W, courses·C), and the
  // net force conjugate to each period length, P_i = ∂E/∂ℓ_i at the relaxed state.
  std::array<double, 2> period_scale{1.0, 1.0};
  std::array<double, 2> period_force_N{0.0, 0.0};
  int period_iterations = 0;
  // Whether the period is relaxed (|P_i| within kKnitPeriodTolerance·k_s), and
  // where it is not, why the generated one is kept.
  bool period_relaxed = false;
  std::string period_note;
};

// Converged when ‖f‖∞ ≤ kKnitRestTolerance·k_s of the stiffest yarn; a relaxed
// period when also |P_i| ≤ kKnitPeriodTolerance·k_s.
inline constexpr double kKnitRestTolerance = 1e-9;
inline constexpr double kKnitPeriodTolerance = 1e-7;
// k_s = Y·πR² of the scene's stiffest yarn type [N]: the force scale of the knit's static tolerances.
double stiffest_yarn_N(const Scene& scene);

// Relaxes the tile of a knit scene (scene.knit set) at its generated period;
// throws std::runtime_error when the solve does not converge.
KnitRestShape relax_knit_tile(const Scene& scene);
// The same at a given period scale, held fixed.
KnitRestShape relax_knit_tile(const Scene& scene, const std::array<double, 2>& period_scale);
// P_i = ∂E/∂ℓ_i of the tile at state q and period scale s: the central
// difference of its energy in ℓ_i at fixed q (docs/models.md §11.3.1).
std::array<double, 2> knit_period_force(const Scene& scene, const std::array<double, 2>& period_scale, const Vec& q);
// The tile relaxed with its period (§11.3.1): at most max_steps outer steps.
// Not converged is an outcome (message), not an exception.
struct KnitPeriodRelaxation {
  KnitRestShape rest;  // the last state reached
  bool converged = false;
  std::string message;
  double fixed_period_energy_J = 0.0;  // relaxed at the generated period
};
KnitPeriodRelaxation relax_knit_period(const Scene& scene, int max_steps = 40);
// The tile state of a rest shape (node positions and coordinates).
Vec knit_tile_state(const Scene& scene, const KnitRestShape& rest);
// The rest shape of a knit scene's cloth (docs/models.md §11.3.1): the tile
// relaxed with its period; at the generated period when the scene has no
// contact compression (then no rest period exists) or when the period does not
// relax (period_note says why). Computed once per pattern and parameters
// (thread-safe); a tile that does not relax throws a SceneError located at the
// scene's [cloth.pattern] (knit_scene_error.h).
const KnitRestShape& relaxed_tile(const Scene& scene);

}  // namespace wl
