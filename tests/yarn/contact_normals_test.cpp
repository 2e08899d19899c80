// ContactNormals (docs/models.md §3.6, §5.3): best-fit normals and the crimped
// normal force F_n on flat, pulled, mirrored and curved plain-weave sheets.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include <Eigen/Geometry>

#include "models/yarn/contact_normals.h"

namespace wl {
namespace {

constexpr double kL = 1e-3, kR = 0.5e-3;       // docs/models.md §8.4: L = 1 mm, R = 0.5 mm
constexpr double kKsU = 0.39, kKbU = 1.1e-10;  // warp k_s (N), k_b (N·m²)
constexpr double kKsV = 0.13, kKbV = 0.9e-10;  // weft

Scene plain_scene(int nu, int nv, bool sliding = true) {
  Scene s;
  s.wefts = nu;  // nodes along a warp
  s.warps = nv;
  s.spacing_m = kL;
  s.radius_m = kR;
  s.sliding = sliding;
  s.pattern.kind = Pattern::Kind::plain;
  return s;
}

ContactNormals make(const WovenGrid& g) {
  return ContactNormals(g, std::vector<double>(g.nv(), kKsU), std::vector<double>(g.nv(), kKbU),
                        std::vector<double>(g.nu(), kKsV), std::vector<double>(g.nu(), kKbV), kR);
}

// State with node (i, j) at pos(i, j) and every sliding coordinate at rest (u = iL, v = jL).
Vec state(const WovenGrid& g, const std::function<Vec3(int, int)>& pos) {
  Vec q = Vec::Zero(g.num_dofs());
  for (int j = 0; j < g.nv(); ++j)
    for (int i = 0; i < g.nu(); ++i) {
      const NodeDofs& d = g.dofs(g.node(i, j));
      q.segment<3>(d.x) = pos(i, j);
      if (is_dof(d.u)) q[d.u] = i * kL;
      if (is_dof(d.v)) q[d.v] = j * kL;
    }
  return q;
}

// Closed form of ½ nᵀ(F^u − F^v) contributed by ONE yarn of a flat plain weave
// whose neighbouring nodes are a horizontal distance h apart, with material
// spacing Δu = L. The crimped copy zig-zags: the centre sits R below (warp) or
// above (weft) the sheet, its in-yarn neighbours R on the other side, so every
// segment rises 2R over h:
//   l = √(h² + 4R²),  sin α = 2R/l,  cos α = h/l,  bending angle θ = 2α at every node.
// Stretch (docs/models.md §3.2): both segments pull the centre toward the sheet with tension
//   T = k_s(l/L − 1), normal component 2 T sin α.
// Bending (docs/models.md §3.3, Cirio et al. 2016 eq. (21)), U = 2L: on the stencil centred at the node
//   F_x1 = 2k_bθ/(l U) (sin α, −cos α) and F_x2 = 2k_bθ/(l U)(−sin α, −cos α),
//   so F_x0 = −(F_x1 + F_x2) has normal component 2·C cos α, C = k_bθ/(L l);
// each stencil centred at an in-yarn neighbour (mirror image) pushes the node
// with normal component C cos α. With m such neighbour stencils (m = 2 deep in
// the sheet, 1 next to the ring, where the ring node carries no stencil):
//   A = 2 k_s (l/L − 1)(2R/l) + (2 + m) k_b θ h /(L l²).
double yarn_push(double ks, double kb, double h, int m) {
  const double l = std::hypot(h, 2 * kR);
  const double theta = 2.0 * std::atan(2 * kR / h);
  return 2.0 * ks * (l / kL - 1.0) * (2 * kR / l) + (2 + m) * kb * theta * h / (kL * l * l);
}

TEST(ContactNormals, FlatSheetNormalsFollowTheOverUnderSign) {
  const WovenGrid g(plain_scene(6, 5));
  ContactNormals cn = make(g);
  cn.compute(state(g, [](int i, int j) { return Vec3(i * kL, j * kL, 0.02); }));
  for (int j = 0; j < g.nv(); ++j)
    for (int i = 0; i < g.nu(); ++i) {
      const Vec3 expected(0, 0, g.sign(i, j));  // +u × +v = +z, times s_ij
      EXPECT_LT((cn.normal()[g.node(i, j)] - expected).norm(), 1e-12) << i << "," << j;
    }
}

TEST(ContactNormals, FlatPlainWeaveAtRestMatchesClosedForm) {
  const WovenGrid g(plain_scene(8, 7));
  ContactNormals cn = make(g);
  cn.compute(state(g, [](int i, int j) { return Vec3(i * kL, j * kL, 0.0); }));
  for (int j = 0; j < g.nv(); ++j)
    for (int i = 0; i < g.nu(); ++i) {
      const double fn = cn.normal_force()[g.node(i, j)];
      if (!g.interior(i, j)) {
        EXPECT_EQ(fn, 0.0) << "ring node " << i << "," << j;
        continue;
      }
      const int mu = (i - 1 >= 1) + (i + 1 <= g.nu() - 2);  // warp stencils centred at neighbours
      const int mv = (j - 1 >= 1) + (j + 1 <= g.nv() - 2);
      const double expected = 0.5 * (yarn_push(kKsU, kKbU, kL, mu) + yarn_push(kKsV, kKbV, kL, mv));
      EXPECT_GT(fn, 0.0) << i << "," << j;
      EXPECT_NEAR(fn, expected, 1e-12 * expected) << i << "," << j;
    }
  // The same at a deep node in plain numbers: with R = L/2 the crimp rises 2R = L
  // over L, so l = √2 L, θ = 2·atan(1) = π/2, 2R/l = 1/√2 and
  //   F_n = ½[(k_s^u + k_s^v)(2 − √2) + (k_b^u + k_b^v) π / L²].
  const double deep = 0.5 * ((kKsU + kKsV) * (2.0 - std::sqrt(2.0)) + (kKbU + kKbV) * M_PI / (kL * kL));
  EXPECT_NEAR(cn.normal_force()[g.node(3, 3)], deep, 1e-12 * deep);
}

TEST(ContactNormals, PulledWarpsIncreaseNormalForce) {
  const WovenGrid g(plain_scene(8, 7));
  ContactNormals rest = make(g), pulled = make(g);
  const double stretch = 1.05;  // warps stretched by 5 % along u, wefts unchanged
  rest.compute(state(g, [](int i, int j) { return Vec3(i * kL, j * kL, 0.0); }));
  pulled.compute(state(g, [&](int i, int j) { return Vec3(i * kL * stretch, j * kL, 0.0); }));
  for (int j = 1; j < g.nv() - 1; ++j)
    for (int i = 1; i < g.nu() - 1; ++i) {
      const int id = g.node(i, j);
      EXPECT_GT(pulled.normal_force()[id], rest.normal_force()[id] + 1e-3) << i << "," << j;
      const int mu = (i - 1 >= 1) + (i + 1 <= g.nu() - 2), mv = (j - 1 >= 1) + (j + 1 <= g.nv() - 2);
      const double expected = 0.5 * (yarn_push(kKsU, kKbU, kL * stretch, mu) + yarn_push(kKsV, kKbV, kL, mv));
      EXPECT_NEAR(pulled.normal_force()[id], expected, 1e-12 * expected) << i << "," << j;
    }
}

TEST(ContactNormals, PullingOneWarpRaisesItsCrossings) {
  // Slide the material coordinates of warp j0 toward its middle (Δu < L on the
  // interior segments): that warp is stretched, its crossings press harder.
  const WovenGrid g(plain_scene(8, 7));
  ContactNormals rest = make(g), pulled = make(g);
  const auto flat = [](int i, int j) { return Vec3(i * kL, j * kL, 0.0); };
  Vec q = state(g, flat);
  rest.compute(q);
  const int j0 = 3;
  for (int i = 1; i < g.nu() - 1; ++i) q[g.dofs(g.node(i, j0)).u] = 3.5 * kL + (i - 3.5) * kL * 0.95;
  pulled.compute(q);
  for (int i = 2; i < g.nu() - 2; ++i) {
    const int id = g.node(i, j0);
    EXPECT_GT(pulled.normal_force()[id], rest.normal_force()[id]) << i;
  }
  // A crossing off that warp is not affected.
  EXPECT_NEAR(pulled.normal_force()[g.node(3, 1)], rest.normal_force()[g.node(3, 1)], 1e-15);
}

// A mixed cloth's F_n at its region's nodes only (set_active): at those nodes the same value as
// computed over the whole grid, on a sheet that is curved, stretched and slid unevenly; 0 elsewhere.
TEST(ContactNormals, ActiveNodesAloneGiveTheSameNormalForce) {
  const WovenGrid g(plain_scene(11, 10));
  ContactNormals all = make(g), some = make(g);
  std::vector<char> active(g.num_nodes(), 0);
  for (int j = 3; j <= 6; ++j)
    for (int i = 4; i <= 8; ++i) active[g.node(i, j)] = 1;
  some.set_active(active);
  Vec q = state(g, [](int i, int j) {
    return Vec3(i * kL * (1.02 + 0.003 * j), j * kL, 0.4 * kL * std::sin(0.7 * i + 0.3 * j * j));
  });
  for (int j = 1; j < g.nv() - 1; ++j)
    for (int i = 1; i < g.nu() - 1; ++i)
      if (is_dof(g.dofs(g.node(i, j)).u)) q[g.dofs(g.node(i, j)).u] += 0.02 * kL * std::cos(1.3 * i + j);
  all.compute(q);
  some.compute(q);
  int pressed = 0;
  for (int id = 0; id < g.num_nodes(); ++id) {
    if (!active[id]) {
      EXPECT_EQ(some.normal_force()[id], 0.0) << id;
      continue;
    }
    EXPECT_EQ(some.normal_force()[id], all.normal_force()[id]) << id;
    pressed += all.normal_force()[id] > 0.0;
  }
  EXPECT_GT(pressed, 10);
  EXPECT_THROW(some.compute_gradient(q), std::invalid_argument);
  EXPECT_THROW(some.set_active(std::vector<char>(3, 1)), std::invalid_argument);
}

TEST(ContactNormals, FlippingAllSignsLeavesNormalForceUnchanged) {
  // n = s_ij · n_plane, and n_plane follows the sheet's in-plane orientation
  // (+u × +v). Mirroring a flat sheet (x → −x) reverses n_plane, which negates
  // n at every node exactly as negating every s_ij would; the crimped copies
  // swap sides. F_n must not change. Checked on a sheared and stretched state.
  const WovenGrid g(plain_scene(7, 6));
  ContactNormals a = make(g), b = make(g);
  const auto deformed = [](int i, int j) {
    return Vec3(i * kL * 1.03 + 0.2 * j * kL + 1e-5 * std::sin(i + 2.0 * j), j * kL * 0.98, 0.0);
  };
  a.compute(state(g, deformed));
  b.compute(state(g, [&](int i, int j) {
    Vec3 x = deformed(i, j);
    x.x() = -x.x();
    return x;
  }));
  for (int id = 0; id < g.num_nodes(); ++id) {
    EXPECT_NEAR(a.normal()[id].z(), -b.normal()[id].z(), 1e-12) << id;  // every normal flipped
    EXPECT_NEAR(a.normal_force()[id], b.normal_force()[id], 1e-12 * (1.0 + a.normal_force()[id])) << id;
  }
  for (int j = 1; j < g.nv() - 1; ++j)
    for (int i = 1; i < g.nu() - 1; ++i) EXPECT_GT(a.normal_force()[g.node(i, j)], 0.0);
}

TEST(ContactNormals, RigidMotionInvariance) {
  const WovenGrid g(plain_scene(6, 6));
  ContactNormals a = make(g), b = make(g);
  const auto wavy = [](int i, int j) {
    return Vec3(i * kL, j * kL * 1.02, 0.3 * kL * std::sin(0.9 * i) * std::cos(0.7 * j));
  };
  const Mat3 Q = Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  const Vec3 t(0.1, -2.0, 0.4);
  a.compute(state(g, wavy));
  b.compute(state(g, [&](int i, int j) { return Vec3(Q * wavy(i, j) + t); }));
  for (int id = 0; id < g.num_nodes(); ++id) {
    EXPECT_LT((Q * a.normal()[id] - b.normal()[id]).norm(), 1e-9) << id;
    EXPECT_NEAR(a.normal_force()[id], b.normal_force()[id], 1e-9 * (1e-6 + a.normal_force()[id])) << id;
  }
}

TEST(ContactNormals, CurvedSheetNormalsAreRadial) {
  // Sheet wrapped on a cylinder of radius ρ about the y axis: the 5 points of an
  // interior node are symmetric about the radial line, so the best-fit normal is
  // radial; +u × +v points outward.
  const WovenGrid g(plain_scene(7, 5));
  ContactNormals cn = make(g);
  const double rho = 4e-3;
  cn.compute(state(g, [&](int i, int j) {
    const double a = i * kL / rho;
    return Vec3(rho * std::sin(a), j * kL, rho * std::cos(a));
  }));
  for (int j = 1; j < g.nv() - 1; ++j)
    for (int i = 1; i < g.nu() - 1; ++i) {
      const double a = i * kL / rho;
      const Vec3 radial(std::sin(a), 0.0, std::cos(a));
      EXPECT_LT((cn.normal()[g.node(i, j)] - g.sign(i, j) * radial).norm(), 1e-9) << i << "," << j;
    }
}

TEST(ContactNormals, NonSlidingGridUsesConstantCoordinates) {
  // With sliding off, u and v are constants of the grid; the rest result must match.
  const WovenGrid gs(plain_scene(7, 7, true)), gf(plain_scene(7, 7, false));
  ContactNormals a = make(gs), b = make(gf);
  const auto flat = [](int i, int j) { return Vec3(i * kL, j * kL, 0.0); };
  a.compute(state(gs, flat));
  b.compute(state(gf, flat));
  for (int id = 0; id < gs.num_nodes(); ++id) EXPECT_NEAR(a.normal_force()[id], b.normal_force()[id], 1e-15);
}

TEST(ContactNormals, RejectsBadInput) {
  const WovenGrid g(plain_scene(5, 4));
  const std::vector<double> wu(g.nv(), 1.0), wv(g.nu(), 1.0);
  EXPECT_THROW(ContactNormals(g, wv, wu, wv, wv, kR), std::invalid_argument);  // warp_ks sized by wefts
  EXPECT_THROW(ContactNormals(g, wu, wu, wv, wv, 0.0), std::invalid_argument);
  EXPECT_THROW(ContactNormals(g, {1, 1, -1, 1}, wu, wv, wv, kR), std::invalid_argument);
  ContactNormals cn(g, wu, wu, wv, wv, kR);
  EXPECT_THROW(cn.compute(Vec::Zero(3)), std::invalid_argument);
}

}  // namespace
}  // namespace wl
