// The tile law's curvature part on the triangles (docs/models.md §6.9.1): the
// curvature per triangle against the shape operator of the surface the mesh is
// placed on, the term's force, Jacobian and coefficient derivatives against
// finite differences inside the sampled box and beyond its faces (each piece on
// its own, with a non-zero derivative demanded there), its energy against the
// hand-computed law, and the scene key [fem] tile_law with its located errors.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <Eigen/Geometry>

#include "driver/calibrate.h"
#include "driver/fidelity.h"
#include "models/fem/fem_material.h"
#include "models/fem/fem_model.h"
#include "models/fem/terms/tile_bending.h"
#include "tests/fem/tile_law_test_data.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

const std::string& kHeader = test::kTileLawHeader;  // tests/fem/tile_law_test_data.h
const std::string kMembrane = "stretch_warp^2,0.6\nstretch_weft^2,0.4\nshear^2,0.3\n";
const std::string kBending =
    "curvature_warp^2,0.1\ncurvature_weft^2,0.08\ntwist^2,0.03\nstretch_warp*curvature_warp^2,-0.03\n"
    "shear*curvature_warp*twist,0.02\ncurvature_warp^4,0.02\ncurvature_weft^3,0.01\n";

struct Folder {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("wl_tile_bending_" + std::to_string(::getpid()));
  Folder() { std::filesystem::create_directories(dir); }
  ~Folder() { std::filesystem::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
};

// A 5 × 5 crossing cloth (L = 1 mm) whose continuum runs the law `law` ([fem] tile_law).
const std::string kCloth =
    "[cloth]\nwarps = 5\nwefts = 5\nspacing_m = 0.001\n[gravity]\nacceleration_m_per_s2 = [0, 0, 0]\n";

Scene scene_with_law(const Folder& f, const std::string& law_text, const std::string& fem_extra = "") {
  f.write("law.csv", law_text);
  return parse_scene(kCloth + "[fem]\ntile_law = \"law.csv\"\n" + fem_extra, f.write("s.toml", ""));
}

const Term& term_named(const FemModel& m, const std::string& name) {
  for (const auto& t : m.terms())
    if (t->name() == name) return *t;
  throw std::logic_error("no term " + name);
}

// Vertex positions on the tile's map (docs/calibration.md §9.1) about the cloth's centre,
//   x = Q(A X + ½ (XᵀBX) e_z) + (0, 0, 2 mm) + noise,
// with A of the strains (ε_u, ε_v, γ), B = [κ_u κ_uv; κ_uv κ_v], Q a turn about an oblique axis.
Vec placed(const FemModel& m, const std::array<double, 6>& theta, double noise = 0.0, unsigned seed = 1) {
  Eigen::Matrix<double, 3, 2> a;
  a.col(0) = (1 + theta[0]) * Vec3(std::cos(theta[2] / 2), std::sin(theta[2] / 2), 0);
  a.col(1) = (1 + theta[1]) * Vec3(std::sin(theta[2] / 2), std::cos(theta[2] / 2), 0);
  Eigen::Matrix2d b;
  b << theta[3], theta[5], theta[5], theta[4];
  const Mat3 turn = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-noise, noise);
  Vec q(3 * m.mesh().num_vertices());
  for (int i = 0; i < m.mesh().num_vertices(); ++i) {
    const Vec2 x = m.mesh().uv[i] - Vec2(0.002, 0.002);
    const Vec3 p = a * x + Vec3(0, 0, 0.5 * x.dot(b * x) + 0.002);
    q.segment<3>(3 * i) = turn * p + Vec3(u(rng), u(rng), u(rng));
  }
  return q;
}

test::LocalState local(const FemModel& m, const Term& t, int e, const Vec& q) {
  std::vector<double> lq(18), lv(18, 0.0);
  const Vec v = Vec::Zero(q.size());
  m.gather_local(t, e, q, v, lq.data(), lv.data());
  return {lq, lv};
}

// The triangles with a neighbour across each edge (the stencil holds six distinct vertices).
std::vector<int> interior(const Term& t) {
  std::vector<int> out;
  for (int e = 0; e < t.num_elements(); ++e) {
    std::vector<int> s(t.stencil(e).begin(), t.stencil(e).end());
    std::sort(s.begin(), s.end());
    if (std::unique(s.begin(), s.end()) == s.end()) out.push_back(e);
  }
  return out;
}

// The interior triangle nearest the cloth's centre (where the map's slopes are smallest).
int central(const FemModel& m, const Term& t) {
  int best = -1;
  double d = 1e300;
  for (int e : interior(t)) {
    Vec2 c = Vec2::Zero();
    for (int k = 0; k < 3; ++k) c += m.mesh().uv[t.stencil(e)[3 * k] / 3] / 3.0;
    if ((c - Vec2(0.002, 0.002)).norm() < d) d = (c - Vec2(0.002, 0.002)).norm(), best = e;
  }
  return best;
}

TEST(TileBending, CurvatureOfTheGridMeshIsTheShapeOperator) {
  Folder f;
  const FemModel m(scene_with_law(f, kHeader + kMembrane + kBending));
  const auto& t = dynamic_cast<const TileBendingTerm&>(term_named(m, "fem-tile-bending"));
  const std::vector<int> inner = interior(t);
  ASSERT_EQ(inner.size(), 18u);  // 32 triangles, 14 with a border edge
  // Cylinders about v and about u, a saddle, twist, and all at once: κ > 0 curves towards w_u × w_v.
  for (const std::array<double, 3>& b : {std::array<double, 3>{10, 0, 0}, {0, -10, 0}, {0, 0, 10}, {6, -4, 3}}) {
    const Vec q = placed(m, {0, 0, 0, b[0], b[1], b[2]});
    for (int e : inner) {
      const std::array<double, 3> k = t.curvature(e, local(m, t, e, q).q.data());
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(k[c], b[c], 1e-3 * 10) << "element " << e << " component " << c;
    }
  }
}

// Each piece of the law on its own: inside the box, beyond κ_u, beyond the twist, beyond the stretch,
// and beyond the shear's lower face (each ≥ 1/m or 0.1 scale from a face).
std::vector<std::array<double, 6>> pieces() {
  return {{0.004, 0.002, 0.2, 5, -3, 2},
          {0.003, 0.001, 0.1, 15, 2, 1},
          {0.002, 0.004, -0.1, 2, 1, -14},
          {0.03, 0.001, 0.2, 5, -3, 2},
          {0.005, -0.002, -0.7, -4, 6, 3}};
}

TEST(TileBending, ForceAndJacobianMatchFiniteDifferencesOnEachPiece) {
  Folder f;
  const FemModel m(scene_with_law(f, kHeader + kMembrane + kBending));
  const Term& t = term_named(m, "fem-tile-bending");
  const int e = interior(t).front();
  test::FdOptions opt;
  opt.jitter = 1e-5;  // stays on its piece
  for (const auto& theta : pieces()) {
    const auto r = test::check_element(t, e, {local(m, t, e, placed(m, theta, 1e-9))}, opt);
    EXPECT_TRUE(r.ok) << "strains " << theta[0] << " " << theta[2] << " " << theta[3] << " " << theta[5] << ": "
                      << r.detail;
  }
  // A border triangle: its missing edge adds nothing, and the rest is still exact.
  const std::vector<int> inner = interior(t);
  int border = 0;
  while (std::find(inner.begin(), inner.end(), border) != inner.end()) ++border;
  const auto r = test::check_element(t, border, {local(m, t, border, placed(m, pieces()[0], 1e-9))}, opt);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(TileBending, CoefficientDerivativesMatchFiniteDifferencesOnEachPiece) {
  Folder f;
  const std::vector<std::pair<std::string, double>> rows{
      {"curvature_warp^2", 0.1}, {"stretch_warp*curvature_warp^2", -0.03}, {"shear*curvature_warp*twist", 0.02}};
  const FemModel base(scene_with_law(f, kHeader + kMembrane + kBending));
  const Term& t0 = term_named(base, "fem-tile-bending");
  const std::vector<std::string> keys = t0.parameter_keys();
  ASSERT_EQ(keys.size(), 7u);  // the curvature monomials; the membrane's stay with the membrane term
  const int e = interior(t0).front();
  for (const auto& [row, value] : rows) {
    const int k = static_cast<int>(std::find(keys.begin(), keys.end(), "fem.tile_law." + row) - keys.begin());
    ASSERT_LT(k, 7) << row;
    auto make = [&, row = row, value = value](double p) {
      std::ostringstream old, now;
      old << row << "," << value;
      now.precision(17);
      now << row << "," << p;
      std::string terms = kBending;
      terms.replace(terms.find(old.str()), old.str().size(), now.str());
      const FemModel m(scene_with_law(f, kHeader + kMembrane + terms));
      return term_named(m, "fem-tile-bending").clone();
    };
    for (const auto& theta : pieces()) {
      const auto r = test::check_parameter_derivative(make, value, k, e, {local(base, t0, e, placed(base, theta))});
      EXPECT_TRUE(r.ok) << row << " at κ_u " << theta[3] << ", γ " << theta[2] << ": " << r.detail;
    }
  }
}

TEST(TileBending, EnergyInsideAndBeyondTheBox) {
  // A cylinder about v on the warp-only law W_b = W₀(0.1 t² + 0.02 t⁴), t = κ_u/10, per interior triangle
  // of rest area ½ mm²; the map's stretch ½κ²x² (≤ 10⁻⁴) only enters through the couplings, absent here.
  Folder f;
  const FemModel m(scene_with_law(f, kHeader + kMembrane +
                                         "curvature_warp^2,0.1\ncurvature_weft^2,0.08\n"
                                         "curvature_warp^4,0.02\n"));
  const Term& t = term_named(m, "fem-tile-bending");
  const int e = central(m, t);
  auto energy = [&](double kappa) { return t.energy(e, local(m, t, e, placed(m, {0, 0, 0, kappa, 0, 0})).q.data()); };
  const double area = 0.5e-6;
  // Inside, t = 0.5: 0.1/4 + 0.02/16.
  EXPECT_NEAR(energy(5), area * 1.5 * (0.025 + 0.00125), 1e-3 * area * 1.5 * 0.02625);
  // Beyond hi, t = 1.5, p = 1, d = 0.5: P(1) + P'(1) d + ½ (2·0.1) d² = 0.12 + 0.28·0.5 + 0.025.
  EXPECT_NEAR(energy(15), area * 1.5 * 0.285, 1e-3 * area * 1.5 * 0.285);
  EXPECT_NEAR(energy(-15), energy(15), 1e-3 * energy(15));  // the law is even in κ_u
}

std::string scene_error(const std::string& text, const Folder& f) {
  try {
    (void)FemModel(parse_scene(text, f.write("s.toml", "")));
  } catch (const SceneError& e) {
    return e.what();
  } catch (const FemParameterError& e) {
    return e.what();
  }
  return "no error";
}

TEST(TileBending, SceneKeyNamesTheLawRelativeToTheSceneFile) {
  Folder f;
  std::filesystem::create_directories(f.dir / "laws");
  f.write("laws/law.csv", kHeader + kMembrane + kBending);
  f.write("params.toml", "areal_density_kg_per_m2 = 0.7\nwarp_bending_N_m = 3e-6\n");
  const Scene s = parse_scene(kCloth + "[fem]\ntile_law = \"laws/law.csv\"\nparameter_file = \"params.toml\"\n",
                              f.write("s.toml", ""));
  EXPECT_EQ(s.fem.tile_law, (f.dir / "laws/law.csv").string());
  const FemModel m(s);
  const std::string terms = m.describe().at("terms");
  EXPECT_NE(terms.find("fem-tile-membrane"), std::string::npos) << terms;
  EXPECT_NE(terms.find("fem-tile-bending (32)"), std::string::npos) << terms;
  EXPECT_EQ(terms.find("fem-bending"), std::string::npos) << terms;
  EXPECT_EQ(terms.find("fem-stretch"), std::string::npos) << terms;
  EXPECT_DOUBLE_EQ(m.material().areal_density_kg_per_m2, 0.7);  // the parameter file after the law
  // The law stays when the material is written into the scene (fidelity's and calibrate's continua).
  const FemModel kept(with_material(s, m.material(), false));
  EXPECT_NE(kept.describe().at("terms").find("fem-tile-bending"), std::string::npos);
  // A law given to fidelity as --fem-params runs in its continuum variants.
  FidelityConfig c;
  c.scene = parse_scene(kCloth, f.write("plain.toml", ""));
  c.fem_params = f.dir / "laws/law.csv";
  c.variants = {"fem_s1"};
  const FidelityPlan plan = plan_fidelity(c);
  ASSERT_EQ(plan.variants.size(), 1u);
  EXPECT_NE(FemModel(plan.variants[0].variant.scene).describe().at("terms").find("fem-tile-membrane"),
            std::string::npos);

  // A missing file: at the scene's key; a malformed law: at its own line.
  const std::string missing = scene_error(kCloth + "[fem]\ntile_law = \"none.csv\"\n", f);
  EXPECT_NE(missing.find("s.toml:8"), std::string::npos) << missing;
  EXPECT_NE(missing.find("tile_law"), std::string::npos) << missing;
  EXPECT_NE(missing.find("none.csv"), std::string::npos) << missing;
  f.write("bad.csv", kHeader + "shear^2,x\n");
  const std::string bad = scene_error(kCloth + "[fem]\ntile_law = \"bad.csv\"\n", f);
  EXPECT_NE(bad.find("bad.csv:21: value 'x'"), std::string::npos) << bad;
  f.write("negative.csv", kHeader + kMembrane + "curvature_warp^2,0.1\ncurvature_weft^2,0.1\ntwist^2,-0.1\n");
  const std::string twist = scene_error(kCloth + "[fem]\ntile_law = \"negative.csv\"\n", f);
  EXPECT_NE(twist.find("negative.csv:26: the bending stiffness at rest along twist"), std::string::npos) << twist;
  const std::string empty = scene_error(kCloth + "[fem]\ntile_law = \"\"\n", f);
  EXPECT_NE(empty.find("tile_law"), std::string::npos) << empty;
}

}  // namespace
}  // namespace wl
