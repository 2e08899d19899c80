// Wind on a triangle (docs/models.md §3.9, §4.19): derivatives in x and
// ẋ against finite differences, independence of the triangle's orientation,
// no force when moving with the wind, pressure along the wind, drag opposing
// relative tangential motion, dissipation in still air, degenerate triangles.
#include <gtest/gtest.h>

#include "models/common/wind.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

using Vec9 = Eigen::Matrix<double, 9, 1>;
const std::array<int, 9> kStencil{0, 1, 2, 3, 4, 5, 6, 7, 8};

WindTerm make_term(const Vec3& w, double rho = 2.0, double d = 0.5) {
  WindTerm t(w, rho, d);
  t.add(kStencil);
  return t;
}

Vec9 force(const Term& t, const std::vector<double>& q, const std::vector<double>& v) {
  Vec9 f = Vec9::Zero();
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data()});
  return f;
}

// The same triangle with nodes 1 and 2 swapped (opposite normal).
test::LocalState flipped(const test::LocalState& s) {
  test::LocalState r = s;
  for (int k = 0; k < 3; ++k) {
    std::swap(r.q[3 + k], r.q[6 + k]);
    std::swap(r.v[3 + k], r.v[6 + k]);
  }
  return r;
}

std::vector<test::LocalState> states() {
  std::vector<test::LocalState> s{
      {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0}},
      {{0.1, -0.2, 0.3, 1.2, 0.1, -0.4, 0.2, 0.9, 0.5}, {0.3, -0.2, 1.0, 0.1, 0.4, -0.5, -0.6, 0.2, 0.3}},
      {{0, 0, 0, 0.01, 0.002, 0.0, 0.003, 0.012, 0.004}, {2.0, 6.0, -1.0, 1.0, 4.0, 0.5, 0.0, 7.0, 0.0}},
      {{-1, 2, 0.5, -0.3, 2.4, 1.1, -0.8, 3.1, 0.2}, {-3, -2, -1, 0.5, -6, 2, 1, 0, -7}},
  };
  const size_t n = s.size();
  for (size_t i = 0; i < n; ++i) s.push_back(flipped(s[i]));
  return s;
}

TEST(WindTerm, DerivativesMatchFiniteDifferences) {
  for (const Vec3& w : {Vec3(0, 5, 0), Vec3(0, -5, 0), Vec3(1.5, -2, 3), Vec3(0, 0, 0)}) {
    const WindTerm t = make_term(w);
    // The first state has the wind in the triangle's plane, on the kink of |w·n| in the
    // second derivative, where central differences err by O(h): a small step.
    test::FdOptions opt;
    opt.rel_step = 1e-7;
    auto r = test::check_element(t, 0, states(), opt);
    EXPECT_TRUE(r.ok) << "wind " << w.transpose() << "\n" << r.detail;
  }
}

TEST(WindTerm, ForceIndependentOfTriangleOrientation) {
  const WindTerm t = make_term(Vec3(0.5, 5, -1));
  for (const auto& s : states()) {
    const auto r = flipped(s);
    Vec9 f = force(t, s.q, s.v), g = force(t, r.q, r.v);
    Vec9 g_back = g;
    g_back.segment<3>(3) = g.segment<3>(6);
    g_back.segment<3>(6) = g.segment<3>(3);
    EXPECT_LT((f - g_back).norm(), 1e-12 * (1 + f.norm()));
  }
}

TEST(WindTerm, TriangleMovingWithTheWindFeelsNoForce) {
  const Vec3 w(1, 5, -2);
  const WindTerm t = make_term(w);
  std::vector<double> v{w[0], w[1], w[2], w[0], w[1], w[2], w[0], w[1], w[2]};
  for (const auto& s : states()) EXPECT_LT(force(t, s.q, v).norm(), 1e-12);
  // Only the mean velocity matters: nodes moving apart about a co-moving centre.
  std::vector<double> spread = v;
  for (int k = 0; k < 3; ++k) {
    spread[k] += 0.4;
    spread[3 + k] -= 0.4;
  }
  EXPECT_LT(force(t, states()[1].q, spread).norm(), 1e-12);
}

TEST(WindTerm, NormalWindPushesAlongTheWindWithDynamicPressure) {
  // Right triangle with legs 2 and 3 in the xz plane (a = 3), wind along +y or −y.
  const std::vector<double> q{0, 0, 0, 2, 0, 0, 0, 0, 3}, v(9, 0.0);
  const double rho = 2.0, a = 3.0;
  for (double wy : {5.0, -5.0}) {
    const WindTerm t = make_term(Vec3(0, wy, 0), rho, 0.5);
    const Vec9 f = force(t, q, v);
    const Vec3 total = f.segment<3>(0) + f.segment<3>(3) + f.segment<3>(6);
    EXPECT_NEAR(total.y(), rho * a * wy * std::abs(wy), 1e-12);
    EXPECT_NEAR(total.x(), 0.0, 1e-12);
    EXPECT_NEAR(total.z(), 0.0, 1e-12);
    for (int j = 0; j < 3; ++j) EXPECT_LT((f.segment<3>(3 * j) - total / 3).norm(), 1e-12);
  }
}

TEST(WindTerm, DragOpposesRelativeTangentialMotion) {
  const std::vector<double> q{0, 0, 0, 2, 0, 0, 0, 0, 3};
  const double d = 0.5, a = 3.0;
  const WindTerm t = make_term(Vec3(0, 0, 0), 2.0, d);
  const Vec3 ut(0.7, 0, -0.4);  // in the plane of the triangle
  std::vector<double> v;
  for (int j = 0; j < 3; ++j) v.insert(v.end(), {ut.x(), ut.y(), ut.z()});
  const Vec9 f = force(t, q, v);
  const Vec3 total = f.segment<3>(0) + f.segment<3>(3) + f.segment<3>(6);
  EXPECT_LT((total + d * a * ut).norm(), 1e-12);
  // Tangential wind over a resting triangle drags it along.
  const WindTerm breeze = make_term(ut, 2.0, d);
  const Vec9 g = force(breeze, q, std::vector<double>(9, 0.0));
  EXPECT_LT((g.segment<3>(0) * 3 - d * a * ut).norm(), 1e-12);
}

TEST(WindTerm, DissipatesInStillAir) {
  const WindTerm t = make_term(Vec3(0, 0, 0));
  for (const auto& s : states()) {
    const Vec9 f = force(t, s.q, s.v);
    const double power = f.dot(Eigen::Map<const Vec9>(s.v.data()));
    EXPECT_LE(power, 1e-14);
    const Vec3 mean = (Eigen::Map<const Vec3>(s.v.data()) + Eigen::Map<const Vec3>(s.v.data() + 3) +
                       Eigen::Map<const Vec3>(s.v.data() + 6)) /
                      3;
    if (mean.norm() > 1e-3) {
      EXPECT_LT(power, 0.0);
    }
  }
}

TEST(WindTerm, DegenerateTriangleGetsNoForce) {
  const WindTerm t = make_term(Vec3(0, 5, 0));
  for (const std::vector<double>& q : {std::vector<double>{0, 0, 0, 1, 1, 1, 2, 2, 2}, std::vector<double>(9, 0.3)}) {
    Vec9 f = Vec9::Zero();
    Eigen::Matrix<double, 9, 9> K = Eigen::Matrix<double, 9, 9>::Zero(), D = K;
    const std::vector<double> v(9, 0.1);
    t.evaluate(0, q.data(), v.data(), ElementOutput{f.data(), K.data(), D.data()});
    EXPECT_EQ(f.norm(), 0.0);
    EXPECT_EQ(K.norm(), 0.0);
    EXPECT_EQ(D.norm(), 0.0);
  }
}

TEST(WindTerm, RejectsBadParameters) {
  EXPECT_THROW(WindTerm(Vec3(0, 5, 0), -1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(WindTerm(Vec3(0, 5, 0), 2.0, -0.5), std::invalid_argument);
  EXPECT_THROW(WindTerm(Vec3(0, std::nan(""), 0), 2.0, 0.5), std::invalid_argument);
  const WindTerm t = make_term(Vec3(0, 5, 0));
  EXPECT_EQ(t.name(), "wind");
  EXPECT_FALSE(t.conservative());
  EXPECT_TRUE(t.has_velocity_jacobian());
}

}  // namespace
}  // namespace wl
