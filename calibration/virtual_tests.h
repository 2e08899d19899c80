// Virtual material tests (docs/calibration.md §2): a square patch of the
// scene's fabric is deformed by a ladder of prescribed boundary motions and
// brought to quasi-static equilibrium at each rung; the response is the work
// conjugate of the load parameter λ per unit rest area,
//   R(λ) = (1/A) dW/dλ = −(1/A) Σ_b f_b · ∂x_b/∂λ,
// summed over the prescribed DoFs b (f the internal force there, so −f the
// reaction), A = ((N−1)L)² the area the patch's crossings span. For a uniaxial
// strain this is the reaction force per unit width [N/m], for a shear angle the
// shear force per unit width [N/m], for a curvature the moment per unit width
// [N·m/m = N].
//
// Boundary: the outer ring of crossings follows the affine map (stretch, shear)
// or, with the next ring so that the edges are clamped in rotation, the
// cylinder (bending) of λ; the interior is free. A clamped ring has no
// free edges that curl or neck, and the continuum patch of the same crossings
// gets the very same boundary, so edge effects enter both sides of the fit
// alike (docs/calibration.md §2 discusses the choice).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "calibration/equilibrium.h"
#include "models/core/model.h"
#include "models/scene/scene.h"

namespace wl {

// The six of the default battery, then the wider battery (docs/calibration.md §2.1):
// bending along the mesh's diagonal and along the other diagonal, and the
// combined loads stretch with shear and stretch with bending.
enum class TestKind {
  uniaxial_warp,
  uniaxial_weft,
  biaxial,
  shear,
  bending_warp,
  bending_weft,
  bending_diagonal,
  bending_antidiagonal,
  stretch_shear,
  stretch_bending
};

struct TestSpec {
  TestKind kind = TestKind::uniaxial_warp;
  std::vector<double> ladder;  // load parameters λ, increasing, > 0
  // The same load on the patch turned by the rigid rotation test_rotation()
  // about its centre: an objective model answers exactly as unrotated.
  bool rotated = false;
};

// The rigid rotation of rotated tests: 2 rad about the axis (1, 2, 3)/√14.
Mat3 test_rotation();

// Names as on the command line: uniaxial-warp, uniaxial-weft, biaxial, shear,
// bending-warp, bending-weft, bending-diagonal, bending-antidiagonal,
// stretch-shear, stretch-bending; each also as rotated-NAME.
const std::vector<std::string>& test_names();
// The six of the default battery (calibrate without --tests).
const std::vector<std::string>& default_test_names();
std::string test_name(TestKind kind);
std::string test_name(const TestSpec& test);  // with the "rotated-" prefix
// Throws std::invalid_argument naming the known tests.
TestKind test_kind(const std::string& name);
// The kind and the rotation of a name, which may carry the "rotated-" prefix.
TestSpec test_spec(const std::string& name);
std::string load_unit(TestKind kind);      // "1" (strain), "rad", "1/m"
std::string response_unit(TestKind kind);  // "N/m" or "N"
// Tests whose edges are clamped in rotation too (two held rings): bending and stretch with bending.
bool clamps_rotation(TestKind kind);
// Default ladder for a patch of N crossings per side at spacing L.
std::vector<double> default_ladder(TestKind kind, int patch, double spacing_m);

// The scene a material test runs on (a knit scene: `patch` courses × `patch` wales of its
// pattern, docs/calibration.md §8): `patch` × `patch` crossings of the
// scene's fabric (pattern, yarn types and their order, R, L, contact
// parameters), flat, with only the material terms (stretch, bending, shear,
// parallel contact when sliding), no pins or handles. Sliding is frozen
// unless `sliding` (docs/calibration.md §2: without friction nothing holds a
// sliding coordinate, with friction the static answer depends on the history).
// Throws std::invalid_argument when the patch is smaller than the pattern's
// repeat plus a free interior.
Scene material_test_scene(const Scene& scene, int patch, bool sliding = false);
// Smallest patch for a scene: one pattern repeat inside the two held rings of the bending tests, at least 6.
int minimum_patch(const Scene& scene);

// Position of a material point at rest offset r = (U, V, Z) from the patch
// centre under load λ, and its derivative ∂x/∂λ, about the centre (rotated
// when `rotated`): the maps of docs/calibration.md §2; Z, the depth through a
// knit, is carried along the surface normal (§8). `span_m` is the patch's rest
// extent along U (stretch-bending's curvature per strain is 50/span_m).
void test_map(TestKind kind, const Vec3& r, double span_m, double lambda, bool rotated, Vec3* x, Vec3* dx);

// Position of crossing (i, j) of the patch under load λ, and its derivative ∂x/∂λ.
struct PatchMap {
  TestKind kind;
  int patch;
  double spacing_m, height_m;
  bool rotated = false;
  Vec3 position(int i, int j, double lambda) const;
  Vec3 derivative(int i, int j, double lambda) const;
};

struct ResponsePoint {
  double load = 0.0;
  double response = 0.0;
  int newton_iterations = 0;
};

struct ResponseCurve {
  TestKind kind;
  std::vector<ResponsePoint> points;  // the rungs that converged, in order
  bool complete = true;               // false: a rung did not converge (message)
  std::string message;
  // d response / d p for each requested parameter key, per point (continuum).
  std::vector<std::vector<double>> sensitivities;  // [point][parameter]
  bool stopped = false;                            // EquilibriumOptions::stop_requested ended it (not complete)
};

// The points a test moves: the x DoF of each, its rest offset from the patch
// centre and its ring depth (0 the outermost, 1 the next, …). A test holds the
// points of depth < 1, or < 2 where it clamps rotation, with the DoFs listed in
// held_with (a knit node's sliding coordinates); the others are free.
struct TestPoints {
  std::vector<int> x_of;
  std::vector<Vec3> rest;
  std::vector<int> depth;
  std::vector<std::vector<int>> held_with;  // empty, or one list per point
  Vec3 centre = Vec3::Zero();
  double span_m = 0.0;   // rest extent along U (test_map)
  double area_m2 = 0.0;  // A of R = (1/A) dW/dλ
  // Solve at λ = 0 first and report R(0) (run_material_test's at_rest): a knit's rest shape.
  bool settle_at_rest = false;
  // The in-plane tests (stretch, shear, stretch-shear) also hold every point's z at rest: a knit's
  // self-stressed interior, sliding, finds no rest otherwise (docs/calibration.md §8). Not rotated.
  bool hold_depth_in_plane = false;
};

// The crossings (i, j) of a woven patch, point i + patch·j: rest offset (iL − c, jL − c, 0),
// c = (patch − 1)L/2, depth min(i, j, patch − 1 − i, patch − 1 − j), A = ((patch − 1)L)².
TestPoints crossing_points(const std::function<int(int, int)>& x_dof, int patch, double spacing_m);
// Tests that keep the patch in its plane: uniaxial, biaxial, shear, stretch-shear.
bool in_plane(TestKind kind);
// The DoFs a test holds; throws std::invalid_argument for a rotated in-plane test that holds z.
std::vector<int> held_dofs(const TestPoints& points, const TestSpec& test);

// Runs one test on a model of a material test scene (yarn, knit or FEM).
// When `parameter_keys` is not empty, also the exact dR/dp by the implicit
// function theorem: dq_f/dp = (−K_ff)⁻¹ ∂f_f/∂p with the converged
// factorization (docs/calibration.md §3). `eq` is a solver made for
// held_dofs(points, test) on `model` (new, or restart()ed: the curve is then bitwise the same).
// With TestPoints::settle_at_rest, `at_rest` (if given) receives the equilibrium with the ring at
// rest, λ = 0: a knit's self-stressed rest shape pulls on its ring, R(0) ≠ 0 (docs/calibration.md §8).
ResponseCurve run_material_test(Model& model, EquilibriumSolver& eq, const TestPoints& points, const TestSpec& test,
                                const std::vector<std::string>& parameter_keys = {},
                                const EquilibriumOptions& options = {}, ResponsePoint* at_rest = nullptr);
// The same with a new solver, for the crossings of a woven patch.
ResponseCurve run_material_test(Model& model, const std::function<int(int, int)>& x_dof, const TestSpec& test,
                                int patch, double spacing_m, const std::vector<std::string>& parameter_keys = {},
                                const EquilibriumOptions& options = {});

// The same for the yarn and continuum models of a material test scene (woven or knit: the knit
// model on its stitch contacts, the continuum on the contact grid, docs/calibration.md §8).
ResponseCurve run_yarn_test(const Scene& test_scene, const TestSpec& test, const EquilibriumOptions& options = {},
                            ResponsePoint* at_rest = nullptr);
// The yarn level's curves of several tests, `threads` at a time (≤ 1: in order).
// Each test runs on its own model, so the curves are bitwise those of one test
// after another; `done(k, curve)` is called as test k ends, one call at a time;
// `at_rest`, if given, receives each test's R(0) as run_yarn_test's; `options` are each test's
// (with a stop hook, every test ends at its Newton iteration).
std::vector<ResponseCurve> run_yarn_tests(const Scene& test_scene, const std::vector<TestSpec>& tests, int threads,
                                          const std::function<void(int, const ResponseCurve&)>& done = {},
                                          std::vector<ResponsePoint>* at_rest = nullptr,
                                          const EquilibriumOptions& options = {});
struct FemMaterial;
struct FemMesh;
class FemModel;
// The continuum patch of a material test scene: the grid mesh through the crossings (woven) or
// the contact grid (knit), and its points.
FemMesh material_test_mesh(const Scene& test_scene);
TestPoints continuum_test_points(const Scene& test_scene, const FemModel& model);
ResponseCurve run_fem_test(const Scene& test_scene, const FemMaterial& material, const TestSpec& test,
                           const std::vector<std::string>& parameter_keys = {}, const EquilibriumOptions& options = {});

}  // namespace wl
