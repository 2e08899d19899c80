#include "calibration/virtual_tests.h"

#include "calibration/parallel_starts.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "calibration/knit_test_patch.h"
#include "models/fem/fem_model.h"
#include "models/knit/knit_model.h"
#include "models/yarn/yarn_model.h"

namespace wl {
namespace {

struct TestInfo {
  TestKind kind;
  const char* name;
  const char* load_unit;
  const char* response_unit;
};

const TestInfo kTests[] = {
    {TestKind::uniaxial_warp, "uniaxial-warp", "1", "N/m"},
    {TestKind::uniaxial_weft, "uniaxial-weft", "1", "N/m"},
    {TestKind::biaxial, "biaxial", "1", "N/m"},
    {TestKind::shear, "shear", "rad", "N/m"},
    {TestKind::bending_warp, "bending-warp", "1/m", "N"},
    {TestKind::bending_weft, "bending-weft", "1/m", "N"},
    {TestKind::bending_diagonal, "bending-diagonal", "1/m", "N"},
    {TestKind::bending_antidiagonal, "bending-antidiagonal", "1/m", "N"},
    {TestKind::stretch_shear, "stretch-shear", "1", "N/m"},
    {TestKind::stretch_bending, "stretch-bending", "1", "N/m"},
};
constexpr int kDefaultTests = 6;  // the first six: the default battery

// Combined loads: the shear angle per unit strain of stretch-shear (2 % with 0.2 rad,
// below the lock), and the turning over the patch per unit strain of stretch-bending
// (2 % with one radian, the top of the bending ladder).
constexpr double kShearPerStrain = 10.0;
constexpr double kTurningPerStrain = 50.0;
constexpr const char* kRotatedPrefix = "rotated-";

const TestInfo& info(TestKind k) {
  for (const TestInfo& t : kTests)
    if (t.kind == k) return t;
  throw std::logic_error("unknown test kind");
}

// Length of the repeat of a weave pattern along either direction.
int pattern_repeat(const Pattern& p) {
  switch (p.kind) {
    case Pattern::Kind::plain: return 2;
    case Pattern::Kind::twill: return p.twill_over + p.twill_under;
    case Pattern::Kind::satin: return p.satin_harness;
  }
  return 2;
}

// sin(a)/κ and (1 − cos a)/κ with a = κs, and their κ-derivatives, stable at small a.
void arc(double s, double kappa, double* along, double* rise, double* d_along, double* d_rise) {
  const double a = kappa * s;
  if (std::abs(a) < 1e-3) {
    const double a2 = a * a;
    *along = s * (1 - a2 / 6 + a2 * a2 / 120);
    *rise = s * a * (0.5 - a2 / 24);
    *d_along = s * s * (-a / 3 + a2 * a / 30);
    *d_rise = s * s * (0.5 - a2 / 8);
    return;
  }
  *along = std::sin(a) / kappa;
  *rise = (1 - std::cos(a)) / kappa;
  *d_along = (s * std::cos(a) - *along) / kappa;
  *d_rise = (s * std::sin(a) - *rise) / kappa;
}

}  // namespace

Mat3 test_rotation() { return Eigen::AngleAxisd(2.0, Vec3(1, 2, 3).normalized()).toRotationMatrix(); }

const std::vector<std::string>& test_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const TestInfo& t : kTests) n.push_back(t.name);
    return n;
  }();
  return names;
}

const std::vector<std::string>& default_test_names() {
  static const std::vector<std::string> names(test_names().begin(), test_names().begin() + kDefaultTests);
  return names;
}

std::string test_name(TestKind kind) { return info(kind).name; }
std::string test_name(const TestSpec& test) { return (test.rotated ? kRotatedPrefix : "") + test_name(test.kind); }

bool clamps_rotation(TestKind kind) {
  return kind == TestKind::bending_warp || kind == TestKind::bending_weft || kind == TestKind::bending_diagonal ||
         kind == TestKind::bending_antidiagonal || kind == TestKind::stretch_bending;
}
std::string load_unit(TestKind kind) { return info(kind).load_unit; }
std::string response_unit(TestKind kind) { return info(kind).response_unit; }

TestKind test_kind(const std::string& name) {
  for (const TestInfo& t : kTests)
    if (name == t.name) return t.kind;
  std::string known;
  for (const TestInfo& t : kTests) known += std::string(known.empty() ? "" : ", ") + t.name;
  throw std::invalid_argument("unknown test '" + name + "', expected one of " + known + " (each also as " +
                              kRotatedPrefix + "NAME)");
}

TestSpec test_spec(const std::string& name) {
  const std::string prefix = kRotatedPrefix;
  const bool rotated = name.rfind(prefix, 0) == 0;
  return {test_kind(rotated ? name.substr(prefix.size()) : name), {}, rotated};
}

std::vector<double> default_ladder(TestKind kind, int patch, double L) {
  std::vector<double> l;
  switch (kind) {
    case TestKind::uniaxial_warp:
    case TestKind::uniaxial_weft:
    case TestKind::biaxial:
    case TestKind::stretch_shear:
    case TestKind::stretch_bending:
      for (int k = 1; k <= 8; ++k) l.push_back(0.0025 * k);  // strains up to 2 %
      break;
    case TestKind::shear:
      for (int k = 1; k <= 16; ++k) l.push_back(0.05 * k);  // shear angles up to 0.8 rad (46°)
      break;
    case TestKind::bending_warp:
    case TestKind::bending_weft:
    case TestKind::bending_diagonal:
    case TestKind::bending_antidiagonal:
      // curvatures up to one radian of turning over the patch
      for (int k = 1; k <= 8; ++k) l.push_back(k / (8.0 * (patch - 1) * L));
      break;
  }
  return l;
}

int minimum_patch(const Scene& scene) {
  return scene.knit ? minimum_knit_patch(scene) : std::max(6, pattern_repeat(scene.pattern) + 4);
}

Scene material_test_scene(const Scene& scene, int patch, bool sliding) {
  Scene t = scene;
  if (scene.knit) {
    t.knit->courses = t.knit->wales = check_knit_patch(scene, patch);
  } else {
    const int min_patch = minimum_patch(scene);
    if (patch < min_patch) {
      std::ostringstream s;
      s << "patch of " << patch << " crossings is too small for the "
        << (scene.pattern.kind == Pattern::Kind::plain   ? "plain"
            : scene.pattern.kind == Pattern::Kind::twill ? "twill"
                                                         : "satin")
        << " pattern: need at least " << min_patch
        << " (one pattern repeat inside the two clamped rings of the bending tests)";
      throw std::invalid_argument(s.str());
    }
    t.warps = t.wefts = patch;
  }
  t.sliding = sliding;
  t.pose = Scene::Pose::flat;
  t.height_m = 0.0;
  t.pins.clear();
  t.handles.clear();
  t.obstacles.clear();             // the fabric alone: a scene's ledge or floor is not part of the material
  t.self_contact.enabled = false;  // nor does it fold onto itself
  t.gravity_m_per_s2 = {0.0, 0.0, 0.0};
  t.wind_velocity_m_per_s = {0.0, 0.0, 0.0};
  t.air_density_kg_per_m3 = t.wind_drag_Ns_per_m3 = 0.0;
  TermSwitches& on = t.terms;
  on.gravity = on.wind = on.handles = on.friction = on.inertia = false;
  t.fem = FemSettings{};
  return t;
}

namespace {

// The bending direction b of a diagonal cylinder and the axis direction a in the plane.
void diagonal_axes(TestKind kind, Vec2* b, Vec2* a) {
  const double h = std::sqrt(0.5);
  *b = kind == TestKind::bending_diagonal ? Vec2(h, h) : Vec2(h, -h);
  *a = Vec2(-b->y(), b->x());
}

// The map of the point at rest offset (u, v, z) under load λ, about the patch centre and
// unrotated: its position x and its derivative dx = ∂x/∂λ.
void local_map(TestKind kind, double u, double v, double z, double span, double lambda, Vec3* x, Vec3* dx) {
  double a, r, da, dr;
  // The bending maps carry a depth z along the cylinder's normal n(θ) = (−sin θ·b, cos θ),
  // θ the turning at the point, b the bending direction in the plane: x += z·n, dx += z·n'(θ)·dθ/dλ.
  auto along_normal = [&](double theta, double dtheta, const Vec2& b) {
    if (z == 0.0) return;
    const double sn = std::sin(theta), cs = std::cos(theta);
    *x += z * Vec3(-sn * b.x(), -sn * b.y(), cs);
    *dx += z * dtheta * Vec3(-cs * b.x(), -cs * b.y(), -sn);
  };
  switch (kind) {
    case TestKind::uniaxial_warp:
      *x = Vec3((1 + lambda) * u, v, 0);
      *dx = Vec3(u, 0, 0);
      break;
    case TestKind::uniaxial_weft:
      *x = Vec3(u, (1 + lambda) * v, 0);
      *dx = Vec3(0, v, 0);
      break;
    case TestKind::biaxial:
      *x = Vec3((1 + lambda) * u, (1 + lambda) * v, 0);
      *dx = Vec3(u, v, 0);
      break;
    case TestKind::shear: {
      // picture frame: warp and weft each turn by λ/2 towards each other, lengths kept
      const double cs = std::cos(lambda / 2), sn = std::sin(lambda / 2);
      *x = Vec3(u * cs + v * sn, u * sn + v * cs, 0);
      *dx = 0.5 * Vec3(-u * sn + v * cs, u * cs - v * sn, 0);
      break;
    }
    case TestKind::bending_warp:
      arc(u, lambda, &a, &r, &da, &dr);
      *x = Vec3(a, v, r);
      *dx = Vec3(da, 0, dr);
      along_normal(lambda * u, u, Vec2(1, 0));
      return;
    case TestKind::bending_weft:
      arc(v, lambda, &a, &r, &da, &dr);
      *x = Vec3(u, a, r);
      *dx = Vec3(0, da, dr);
      along_normal(lambda * v, v, Vec2(0, 1));
      return;
    case TestKind::bending_diagonal:
    case TestKind::bending_antidiagonal: {
      // the cylinder of curvature λ bending along b, its axis along a
      Vec2 b, ax;
      diagonal_axes(kind, &b, &ax);
      const double s = b.dot(Vec2(u, v));
      arc(s, lambda, &a, &r, &da, &dr);
      const Vec2 p = a * b + ax.dot(Vec2(u, v)) * ax;
      *x = Vec3(p.x(), p.y(), r);
      *dx = Vec3(da * b.x(), da * b.y(), dr);
      along_normal(lambda * s, s, b);
      return;
    }
    case TestKind::stretch_shear: {
      // warp strain λ, then the picture frame at γ = kShearPerStrain·λ
      const double g = kShearPerStrain * lambda, cs = std::cos(g / 2), sn = std::sin(g / 2);
      const double s = (1 + lambda) * u, dg = 0.5 * kShearPerStrain;
      *x = Vec3(s * cs + v * sn, s * sn + v * cs, 0);
      *dx = Vec3(u * cs + dg * (-s * sn + v * cs), u * sn + dg * (s * cs - v * sn), 0);
      break;
    }
    case TestKind::stretch_bending: {
      // warp strain λ along the arc of the cylinder of curvature κ = cλ, c = kTurningPerStrain/span:
      // x = arc(s, κ) with s = (1+λ)u, dx/dλ = ∂x/∂s·u + ∂x/∂κ·c, ∂(along, rise)/∂s = (cos κs, sin κs)
      const double k_per = kTurningPerStrain / span, kappa = k_per * lambda;
      const double s = (1 + lambda) * u;
      arc(s, kappa, &a, &r, &da, &dr);
      *x = Vec3(a, v, r);
      *dx = Vec3(std::cos(kappa * s) * u + da * k_per, 0, std::sin(kappa * s) * u + dr * k_per);
      along_normal(kappa * s, k_per * s + kappa * u, Vec2(1, 0));
      return;
    }
  }
  if (z != 0.0) x->z() += z;  // the in-plane maps keep a point's depth
}

}  // namespace

void test_map(TestKind kind, const Vec3& r, double span_m, double lambda, bool rotated, Vec3* x, Vec3* dx) {
  local_map(kind, r.x(), r.y(), r.z(), span_m, lambda, x, dx);
  if (rotated) *x = test_rotation() * *x, *dx = test_rotation() * *dx;
}

Vec3 PatchMap::position(int i, int j, double lambda) const {
  const double c = 0.5 * (patch - 1) * spacing_m;
  Vec3 x, dx;
  test_map(kind, Vec3(i * spacing_m - c, j * spacing_m - c, 0), (patch - 1) * spacing_m, lambda, rotated, &x, &dx);
  return x + Vec3(c, c, height_m);
}

Vec3 PatchMap::derivative(int i, int j, double lambda) const {
  const double c = 0.5 * (patch - 1) * spacing_m;
  Vec3 x, dx;
  test_map(kind, Vec3(i * spacing_m - c, j * spacing_m - c, 0), (patch - 1) * spacing_m, lambda, rotated, &x, &dx);
  return dx;
}

TestPoints crossing_points(const std::function<int(int, int)>& x_dof, int patch, double L) {
  TestPoints p;
  const double c = 0.5 * (patch - 1) * L;
  for (int j = 0; j < patch; ++j)
    for (int i = 0; i < patch; ++i) {
      p.x_of.push_back(x_dof(i, j));
      p.rest.emplace_back(i * L - c, j * L - c, 0.0);
      p.depth.push_back(std::min({i, j, patch - 1 - i, patch - 1 - j}));
    }
  p.centre = Vec3(c, c, 0.0);
  p.span_m = (patch - 1) * L;
  p.area_m2 = std::pow((patch - 1) * L, 2);
  return p;
}

namespace {

// Held points: the outer ring; for bending the next ring too, so that the
// edges are clamped in rotation as well (a ring held in position only lets the
// rows relax like pinned beams, away from the cylinder).
std::vector<int> held_points(const TestPoints& points, const TestSpec& test) {
  const int depth = clamps_rotation(test.kind) ? 2 : 1;
  std::vector<int> ring;
  for (size_t n = 0; n < points.x_of.size(); ++n)
    if (points.depth[n] < depth) ring.push_back(static_cast<int>(n));
  return ring;
}

}  // namespace

bool in_plane(TestKind kind) {
  return kind == TestKind::uniaxial_warp || kind == TestKind::uniaxial_weft || kind == TestKind::biaxial ||
         kind == TestKind::shear || kind == TestKind::stretch_shear;
}

std::vector<int> held_dofs(const TestPoints& points, const TestSpec& test) {
  std::vector<int> prescribed;
  for (int n : held_points(points, test)) {
    for (int c = 0; c < 3; ++c) prescribed.push_back(points.x_of[n] + c);
    if (!points.held_with.empty())
      prescribed.insert(prescribed.end(), points.held_with[n].begin(), points.held_with[n].end());
  }
  if (points.hold_depth_in_plane && in_plane(test.kind)) {
    if (test.rotated)
      throw std::invalid_argument(test_name(test) +
                                  ": an in-plane test that holds every point's z "
                                  "(a knit patch) is not offered rotated");
    for (size_t n = 0; n < points.x_of.size(); ++n)
      if (points.depth[n] >= (clamps_rotation(test.kind) ? 2 : 1)) prescribed.push_back(points.x_of[n] + 2);
  }
  return prescribed;
}

ResponseCurve run_material_test(Model& model, const std::function<int(int, int)>& x_dof, const TestSpec& test,
                                int patch, double L, const std::vector<std::string>& keys,
                                const EquilibriumOptions& options) {
  const TestPoints points = crossing_points(x_dof, patch, L);
  EquilibriumSolver eq(model, held_dofs(points, test));
  return run_material_test(model, eq, points, test, keys, options);
}

ResponseCurve run_material_test(Model& model, EquilibriumSolver& eq, const TestPoints& points, const TestSpec& test,
                                const std::vector<std::string>& keys, const EquilibriumOptions& options,
                                ResponsePoint* at_rest) {
  const std::vector<int> ring = held_points(points, test);
  const std::vector<int>& x_of = points.x_of;
  const size_t count = x_of.size();
  auto position = [&](size_t n, double lambda) {
    Vec3 x, dx;
    test_map(test.kind, points.rest[n], points.span_m, lambda, test.rotated, &x, &dx);
    return Vec3(x + points.centre);
  };
  auto derivative = [&](size_t n, double lambda) {
    Vec3 x, dx;
    test_map(test.kind, points.rest[n], points.span_m, lambda, test.rotated, &x, &dx);
    return dx;
  };

  ResponseCurve curve{test.kind, {}, true, "", {}};
  Vec q = model.initial_q();
  const Vec zero_v = Vec::Zero(model.num_dofs());
  Vec dfdp, s;
  if (test.rotated) {
    // Turn the rest patch about its centre first; the ladder's increments are turned alike.
    const Mat3 Q = test_rotation();
    for (size_t n = 0; n < count; ++n) {
      auto x = q.segment<3>(x_of[n]);
      x = points.centre + Q * (Vec3(x) - points.centre);
    }
  }
  // R = −(1/A) Σ_b f_b·∂x_b/∂λ over the ring.
  auto response_of = [&](const Vec& f, double lambda) {
    double w = 0.0;
    for (int n : ring) w -= f.segment<3>(x_of[n]).dot(derivative(n, lambda));
    return w / points.area_m2;
  };
  if (points.settle_at_rest) {
    const EquilibriumResult r = eq.solve(q, options);
    if (!r.converged) {
      curve.complete = false;
      curve.stopped = r.stopped;
      curve.message = test_name(test) + " at rest (λ = 0): " + r.message;
      return curve;
    }
    if (at_rest) *at_rest = {0.0, response_of(eq.evaluation().force, 0.0), r.iterations + r.descent_steps};
  }
  double previous = 0.0;
  for (double lambda : test.ladder) {
    // Every point moves with the map (the ring exactly, the interior as a first guess).
    for (size_t n = 0; n < count; ++n) q.segment<3>(x_of[n]) += position(n, lambda) - position(n, previous);
    previous = lambda;
    const EquilibriumResult r = eq.solve(q, options);
    if (!r.converged) {
      std::ostringstream m;
      m << test_name(test) << " at " << lambda << " " << load_unit(test.kind) << ": " << r.message;
      curve.complete = false;
      curve.stopped = r.stopped;
      curve.message = m.str();
      break;
    }
    const Evaluation& ev = eq.evaluation();
    curve.points.push_back({lambda, response_of(ev.force, lambda), r.iterations + r.descent_steps});
    std::vector<double> sens;
    for (const std::string& key : keys) {
      // df/dp = K·dq/dp + ∂f/∂p, with dq_f/dp = (−K_ff)⁻¹ ∂f_f/∂p (dq = 0 on the ring).
      model.force_parameter_derivative(key, 0.0, q, zero_v, dfdp);
      eq.solve_free(dfdp, s);
      sens.push_back(response_of(ev.dfdq * s + dfdp, lambda));
    }
    curve.sensitivities.push_back(std::move(sens));
  }
  return curve;
}

ResponseCurve run_yarn_test(const Scene& test_scene, const TestSpec& test, const EquilibriumOptions& options,
                            ResponsePoint* at_rest) {
  if (test_scene.knit) {
    KnitModel model(test_scene);
    const TestPoints points = knit_contact_points(model);
    EquilibriumSolver eq(model, held_dofs(points, test));
    EquilibriumOptions o = options;
    if (!(o.descent_tolerance > 0)) o.descent_tolerance = knit_equilibrium_options(test_scene).descent_tolerance;
    return run_material_test(model, eq, points, test, {}, o, at_rest);
  }
  YarnModel model(test_scene);
  const WovenGrid& g = model.grid();
  return run_material_test(
      model, [&](int i, int j) { return g.dofs(g.node(i, j)).x; }, test, test_scene.warps, test_scene.spacing_m, {},
      options);
}

std::vector<ResponseCurve> run_yarn_tests(const Scene& test_scene, const std::vector<TestSpec>& tests, int threads,
                                          const std::function<void(int, const ResponseCurve&)>& done,
                                          std::vector<ResponsePoint>* at_rest, const EquilibriumOptions& options) {
  std::vector<ResponseCurve> curves(tests.size());
  if (at_rest) at_rest->assign(tests.size(), ResponsePoint{});
  std::mutex report;
  run_starts(static_cast<int>(tests.size()), threads, [&](int k) {
    curves[k] = run_yarn_test(test_scene, tests[k], options, at_rest ? &(*at_rest)[k] : nullptr);
    if (!done) return;
    std::lock_guard<std::mutex> lock(report);
    done(k, curves[k]);
  });
  return curves;
}

FemMesh material_test_mesh(const Scene& test_scene) {
  return test_scene.knit ? knit_contact_mesh(test_scene) : make_fem_mesh(test_scene);
}

TestPoints continuum_test_points(const Scene& test_scene, const FemModel& model) {
  if (test_scene.knit) return knit_continuum_points(test_scene);
  return crossing_points(
      [&](int i, int j) {
        return 3 * model.vertex_of_node({i, j});
      },
      test_scene.warps, test_scene.spacing_m);
}

ResponseCurve run_fem_test(const Scene& test_scene, const FemMaterial& material, const TestSpec& test,
                           const std::vector<std::string>& keys, const EquilibriumOptions& options) {
  FemModel model(test_scene, material_test_mesh(test_scene), material);
  const TestPoints points = continuum_test_points(test_scene, model);
  EquilibriumSolver eq(model, held_dofs(points, test));
  return run_material_test(model, eq, points, test, keys, options);
}

}  // namespace wl
