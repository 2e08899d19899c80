// Virtual material tests on a knit patch (docs/calibration.md §8). The knit's
// material directions take the woven tests' names: the course (x, along each
// yarn) is the warp-like direction u, the wale (y, up the loops) the weft-like
// v. A test moves the patch's stitch contacts: both nodes of each contact
// follow the test's map from their place in the relaxed rest shape (their depth
// through the cloth along the surface normal), with the sliding coordinates of
// the held contacts held. The rings are those of the strip test's grips
// (docs/models.md §11.8): contact rows 0 and `courses` and the contacts of the
// first and last wale; the bending tests hold the next row and wale too. The
// continuum patch is the knit's continuum (models/fem/knit_contact_mesh.h), the
// triangle mesh through the contact grid, with the same rings held.
#pragma once
#include "calibration/virtual_tests.h"
#include "models/fem/knit_contact_mesh.h"

namespace wl {

class KnitModel;

// A knit patch of `patch` courses × `patch` wales (material_test_scene builds its scene): returns
// `patch`, or throws std::invalid_argument for a patch too small or one the pattern's tile does
// not cover whole.
int check_knit_patch(const Scene& scene, int patch);
// Smallest knit patch: the pattern's tile inside the two clamped rings, at least 6.
int minimum_knit_patch(const Scene& scene);
// The largest patch up to `largest` that check_knit_patch accepts (a multiple of the tile), or the
// smallest it accepts when none is that small.
int default_knit_patch(const Scene& scene, int largest);

// The points of a knit patch: both nodes of every stitch contact, the contact
// grid's centre, span (2·wales − 1)W/2 along u and area span·courses·C, R(0) reported.
TestPoints knit_contact_points(const KnitModel& model);
// The continuum patch's points on the contact grid (vertex κ + 2·wales·ρ of knit_contact_mesh).
TestPoints knit_continuum_points(const Scene& test_scene);

// Default ladders on a knit patch: strains up to 10 % (a knit's loops open far beyond the
// woven's 2 %), shear angles up to 0.4 rad, curvatures up to one radian of turning over the
// patch's span along the bend.
std::vector<double> default_knit_ladder(TestKind kind, const Scene& test_scene);

// The knit model's static tolerance: where Newton fails, energy descent to
// kKnitRestTolerance·k_s of the stiffest yarn (docs/models.md §11.8).
EquilibriumOptions knit_equilibrium_options(const Scene& test_scene);

}  // namespace wl
