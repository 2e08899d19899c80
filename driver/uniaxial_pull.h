// `weavelab pull`: a quasi-static uniaxial strip test of a flat scene's cloth,
// woven or knitted, at yarn level (docs/models.md §11.8). The first and last
// rows of nodes across the pull direction are clamped grips (positions and
// sliding coordinates held); the far grip moves by λ·H along the pull, H the
// grips' rest distance; everything else is free (the sides neck and curl).
// Only the material terms act (stretch, bending, shear, parallel contact and
// the knit terms; no gravity, wind, handles, friction or inertia); hold_z
// also holds every node's z (an in-plane test). At each rung of the strain
// ladder the patch is brought to static equilibrium (calibration/equilibrium.h,
// energy descent where its line search fails; warm-started from the previous rung) and the
// pull per unit width F/W = Σ (−f·e) over the far grip's positions is read,
// W the grip's rest width. Grips: woven, the crossing rows j = 0 and
// j = warps − 1 (pull along y) or columns i = 0, i = wefts − 1 (along x);
// knit, the contact rows 0 and `courses` (along y, wale-wise) or the contacts
// of the first and last wale (along x, course-wise).
// The yarn density is the total yarn length of the patch per rest area H·W.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "models/scene/scene.h"

namespace wl {

struct PullConfig {
  std::vector<double> strains{0.01, 0.02, 0.05, 0.1};  // λ, increasing, > 0
  char direction = 'y';                                // 'x' or 'y'
  bool hold_z = false;                                 // every node's z held at rest (an in-plane test)
  std::filesystem::path out_dir;                       // pull.csv, pull.json
};

struct PullPoint {
  double strain = 0.0, force_per_width_N_per_m = 0.0, residual_N = 0.0;
  int newton_iterations = 0;
};

struct PullResult {
  double grip_distance_m = 0.0, grip_width_m = 0.0;  // H, W at rest
  double yarn_length_m = 0.0;                        // total yarn length of the patch
  double yarn_length_per_area_per_m = 0.0;           // yarn_length / (H·W)
  std::vector<PullPoint> points;                     // the rungs that converged, from λ = 0
  bool complete = true;
  std::string message;         // why a rung did not converge
  std::string interrupted_in;  // the rung a SIGINT or SIGTERM ended at its iteration ("" otherwise)
};

// Throws std::invalid_argument for a scene that is not flat or a bad ladder.
PullResult run_pull(const Scene& scene, const PullConfig& config);
// Runs and writes out_dir/pull.csv (strain, force_per_width_N_per_m,
// newton_iterations, residual_N) and out_dir/pull.json; after a signal, the
// rungs reached and outcome interrupted (driver/interrupted_record.h), then
// throws Interrupted.
PullResult pull_command(const Scene& scene, const PullConfig& config);

}  // namespace wl
