#include "calibration/virtual_tests.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "models/fem/fem_model.h"
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
};

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

const std::vector<std::string>& test_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const TestInfo& t : kTests) n.push_back(t.name);
    return n;
  }();
  return names;
}

std::string test_name(TestKind kind) { return info(kind).name; }
std::string load_unit(TestKind kind) { return info(kind).load_unit; }
std::string response_unit(TestKind kind) { return info(kind).response_unit; }

TestKind test_kind(const std::string& name) {
  for (const TestInfo& t : kTests)
    if (name == t.name) return t.kind;
  std::string known;
  for (const TestInfo& t : kTests) known += std::string(known.empty() ? "" : ", ") + t.name;
  throw std::invalid_argument("unknown test '" + name + "', expected one of " + known);
}

std::vector<double> default_ladder(TestKind kind, int patch, double L) {
  std::vector<double> l;
  switch (kind) {
    case TestKind::uniaxial_warp:
    case TestKind::uniaxial_weft:
    case TestKind::biaxial:
      for (int k = 1; k <= 8; ++k) l.push_back(0.0025 * k);  // strains up to 2 %
      break;
    case TestKind::shear:
      for (int k = 1; k <= 16; ++k) l.push_back(0.05 * k);  // shear angles up to 0.8 rad (46°)
      break;
    case TestKind::bending_warp:
    case TestKind::bending_weft:
      // curvatures up to one radian of turning over the patch
      for (int k = 1; k <= 8; ++k) l.push_back(k / (8.0 * (patch - 1) * L));
      break;
  }
  return l;
}

int minimum_patch(const Scene& scene) { return std::max(6, pattern_repeat(scene.pattern) + 4); }

Scene material_test_scene(const Scene& scene, int patch, bool sliding) {
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
  Scene t = scene;
  t.warps = t.wefts = patch;
  t.sliding = sliding;
  t.pose = Scene::Pose::flat;
  t.height_m = 0.0;
  t.pins.clear();
  t.handles.clear();
  t.gravity_m_per_s2 = {0.0, 0.0, 0.0};
  t.wind_velocity_m_per_s = {0.0, 0.0, 0.0};
  t.air_density_kg_per_m3 = t.wind_drag_Ns_per_m3 = 0.0;
  TermSwitches& on = t.terms;
  on.gravity = on.wind = on.handles = on.friction = on.inertia = false;
  t.fem = FemSettings{};
  return t;
}

Vec3 PatchMap::position(int i, int j, double lambda) const {
  const double c = 0.5 * (patch - 1) * spacing_m;
  const double u = i * spacing_m - c, v = j * spacing_m - c;
  double a, r, da, dr;
  Vec3 x = Vec3::Zero();
  switch (kind) {
    case TestKind::uniaxial_warp: x = Vec3((1 + lambda) * u, v, 0); break;
    case TestKind::uniaxial_weft: x = Vec3(u, (1 + lambda) * v, 0); break;
    case TestKind::biaxial: x = Vec3((1 + lambda) * u, (1 + lambda) * v, 0); break;
    case TestKind::shear: {
      // picture frame: warp and weft each turn by λ/2 towards each other, lengths kept
      const double cs = std::cos(lambda / 2), sn = std::sin(lambda / 2);
      x = Vec3(u * cs + v * sn, u * sn + v * cs, 0);
      break;
    }
    case TestKind::bending_warp:
      arc(u, lambda, &a, &r, &da, &dr);
      x = Vec3(a, v, r);
      break;
    case TestKind::bending_weft:
      arc(v, lambda, &a, &r, &da, &dr);
      x = Vec3(u, a, r);
      break;
  }
  return x + Vec3(c, c, height_m);
}

Vec3 PatchMap::derivative(int i, int j, double lambda) const {
  const double c = 0.5 * (patch - 1) * spacing_m;
  const double u = i * spacing_m - c, v = j * spacing_m - c;
  double a, r, da, dr;
  switch (kind) {
    case TestKind::uniaxial_warp: return Vec3(u, 0, 0);
    case TestKind::uniaxial_weft: return Vec3(0, v, 0);
    case TestKind::biaxial: return Vec3(u, v, 0);
    case TestKind::shear: {
      const double cs = std::cos(lambda / 2), sn = std::sin(lambda / 2);
      return 0.5 * Vec3(-u * sn + v * cs, u * cs - v * sn, 0);
    }
    case TestKind::bending_warp: arc(u, lambda, &a, &r, &da, &dr); return Vec3(da, 0, dr);
    case TestKind::bending_weft: arc(v, lambda, &a, &r, &da, &dr); return Vec3(0, da, dr);
  }
  return Vec3::Zero();
}

ResponseCurve run_material_test(Model& model, const std::function<int(int, int)>& x_dof, const TestSpec& test,
                                int patch, double L, const std::vector<std::string>& keys,
                                const EquilibriumOptions& options) {
  const PatchMap map{test.kind, patch, L, 0.0};
  // Held crossings: the outer ring; for bending the next ring too, so that the
  // edges are clamped in rotation as well (a ring held in position only lets the
  // rows relax like pinned beams, away from the cylinder).
  const bool bending = test.kind == TestKind::bending_warp || test.kind == TestKind::bending_weft;
  const int depth = bending ? 2 : 1;
  std::vector<int> ring, prescribed;
  for (int j = 0; j < patch; ++j)
    for (int i = 0; i < patch; ++i)
      if (std::min({i, j, patch - 1 - i, patch - 1 - j}) < depth) {
        ring.push_back(i + patch * j);
        for (int c = 0; c < 3; ++c) prescribed.push_back(x_dof(i, j) + c);
      }
  EquilibriumSolver eq(model, prescribed);
  const double area = std::pow((patch - 1) * L, 2);

  ResponseCurve curve{test.kind, {}, true, "", {}};
  Vec q = model.initial_q();
  const Vec zero_v = Vec::Zero(model.num_dofs());
  Vec dfdp, s;
  double previous = 0.0;
  for (double lambda : test.ladder) {
    // Every crossing moves with the map (the ring exactly, the interior as a first guess).
    for (int j = 0; j < patch; ++j)
      for (int i = 0; i < patch; ++i)
        q.segment<3>(x_dof(i, j)) += map.position(i, j, lambda) - map.position(i, j, previous);
    previous = lambda;
    const EquilibriumResult r = eq.solve(q, options);
    if (!r.converged) {
      std::ostringstream m;
      m << test_name(test.kind) << " at " << lambda << " " << load_unit(test.kind) << ": " << r.message;
      curve.complete = false;
      curve.message = m.str();
      break;
    }
    // R = −(1/A) Σ_b f_b·∂x_b/∂λ over the ring.
    auto response_of = [&](const Vec& f) {
      double w = 0.0;
      for (int n : ring) {
        const int i = n % patch, j = n / patch;
        w -= f.segment<3>(x_dof(i, j)).dot(map.derivative(i, j, lambda));
      }
      return w / area;
    };
    const Evaluation& ev = eq.evaluation();
    curve.points.push_back({lambda, response_of(ev.force), r.iterations});
    std::vector<double> sens;
    for (const std::string& key : keys) {
      // df/dp = K·dq/dp + ∂f/∂p, with dq_f/dp = (−K_ff)⁻¹ ∂f_f/∂p (dq = 0 on the ring).
      model.force_parameter_derivative(key, 0.0, q, zero_v, dfdp);
      eq.solve_free(dfdp, s);
      sens.push_back(response_of(ev.dfdq * s + dfdp));
    }
    curve.sensitivities.push_back(std::move(sens));
  }
  return curve;
}

ResponseCurve run_yarn_test(const Scene& test_scene, const TestSpec& test, const EquilibriumOptions& options) {
  YarnModel model(test_scene);
  const WovenGrid& g = model.grid();
  return run_material_test(
      model, [&](int i, int j) { return g.dofs(g.node(i, j)).x; }, test, test_scene.warps, test_scene.spacing_m, {},
      options);
}

ResponseCurve run_fem_test(const Scene& test_scene, const FemMaterial& material, const TestSpec& test,
                           const std::vector<std::string>& keys, const EquilibriumOptions& options) {
  FemModel model(test_scene, make_fem_mesh(test_scene), material);
  return run_material_test(
      model,
      [&](int i, int j) {
        return 3 * model.vertex_of_node({i, j});
      },
      test, test_scene.warps, test_scene.spacing_m, keys, options);
}

}  // namespace wl
