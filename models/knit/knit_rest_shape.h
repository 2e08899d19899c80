// The rest shape of a knit (docs/models.md §11.3): the pattern's smallest
// repeating tile, periodic in both directions, relaxed without gravity to
// static equilibrium (Newton's method on the assembled stiffness with a
// Levenberg–Marquardt shift and energy descent), then tiled over the cloth.
// Cached in memory per pattern and parameters.
#pragma once
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
  int iterations = 0;
  double energy_generated_J = 0.0, energy_relaxed_J = 0.0;
};

// Converged when ‖f‖∞ ≤ kKnitRestTolerance·k_s of the stiffest yarn.
inline constexpr double kKnitRestTolerance = 1e-9;

// Relaxes the tile of a knit scene (scene.knit set); throws std::runtime_error
// naming the pattern when the solve does not converge.
KnitRestShape relax_knit_tile(const Scene& scene);
// The same, computed once per pattern and parameters (thread-safe).
const KnitRestShape& relaxed_tile(const Scene& scene);

}  // namespace wl
