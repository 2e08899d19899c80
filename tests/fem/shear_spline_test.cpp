// The spline shear law (docs/models.md §6.4.1): its tangent-stiffness curve against an independent
// quadrature, the law nested in the linear one, and energy, force, Jacobian and every parameter
// derivative through the finite-difference checker at sheared states on every knot interval.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "models/fem/deformation_gradient.h"
#include "models/fem/fem_material.h"
#include "models/fem/terms/in_plane_shear.h"
#include "models/fem/terms/shear_stiffness_spline.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

const Vec2 kUv0(0.001, 0.002), kUv1(0.013, 0.001), kUv2(0.004, 0.011);
const std::vector<double> kKnotsRad{0.1, 0.2, 0.3, 0.4};
const std::vector<double> kKnotValues{3.2, 2.1, 0.9, 0.5};  // N/m, softening; k_sh = 3.5

std::array<int, 9> iota9() { return {0, 1, 2, 3, 4, 5, 6, 7, 8}; }

// The triangle under warp/weft stretch (1 + ε_u, 1 + ε_v) and shear angle γ, turned out of plane,
// with a small random jitter: states on every interval of the knots, beyond the last and negative.
std::vector<test::LocalState> sheared_states() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  const Mat3 turn = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<test::LocalState> states;
  for (double g : {-0.33, 0.04, 0.13, 0.26, 0.37, 0.55, 0.9}) {
    Eigen::Matrix<double, 3, 2> F;
    F.col(0) = 1.02 * Vec3(std::cos(g / 2), std::sin(g / 2), 0);
    F.col(1) = 0.97 * Vec3(std::sin(g / 2), std::cos(g / 2), 0);
    test::LocalState s{std::vector<double>(9), std::vector<double>(9, 0.0)};
    const Vec2 uv[3] = {kUv0, kUv1, kUv2};
    for (int k = 0; k < 3; ++k) {
      const Vec3 x = turn * (F * uv[k]);
      for (int c = 0; c < 3; ++c) s.q[3 * k + c] = x[c] + 1e-5 * d(rng);
    }
    states.push_back(s);
  }
  return states;
}

// s = cos of the warp/weft angle at a state.
double shear_sine(const TriangleRest& r, const std::vector<double>& q) {
  const Vec3 wu = warp_vector(r, q.data()), wv = weft_vector(r, q.data());
  return wu.dot(wv) / (wu.norm() * wv.norm());
}

TEST(ShearStiffnessSpline, IntegralsMatchQuadratureOfTheHermiteStiffness) {
  // κ written out here from its definition, σ and E by Simpson's rule over it.
  std::vector<double> a{0.0}, k{3.5};
  for (size_t i = 0; i < kKnotsRad.size(); ++i) {
    a.push_back(std::sin(kKnotsRad[i]));
    k.push_back(kKnotValues[i]);
  }
  const ShearStiffnessSpline curve({a.begin() + 1, a.end()});
  auto kappa = [&](double x) {
    for (size_t i = 0; i + 1 < a.size(); ++i)
      if (x < a[i + 1]) {
        const double t = (x - a[i]) / (a[i + 1] - a[i]);
        return k[i] + (k[i + 1] - k[i]) * (3 * t * t - 2 * t * t * t);
      }
    return k.back();
  };
  const int n = 20000;
  const double top = 0.75, h = top / n;
  double sigma = 0.0, energy = 0.0, prev_sigma = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double x0 = (i - 1) * h, x1 = i * h;
    sigma += h / 6 * (kappa(x0) + 4 * kappa(0.5 * (x0 + x1)) + kappa(x1));
    energy += 0.5 * h * (prev_sigma + sigma);  // trapezoid on σ: error O(h²) ≈ 1e-9
    prev_sigma = sigma;
    if (i % 1000 != 0) continue;
    double e, de, dde;
    curve.evaluate(x1, k.data(), &e, &de, &dde);
    EXPECT_NEAR(dde, kappa(x1), 1e-12) << x1;
    EXPECT_NEAR(de, sigma, 1e-10) << x1;
    EXPECT_NEAR(e, energy, 1e-7 * energy) << x1;
    double em, dem, ddem;
    curve.evaluate(-x1, k.data(), &em, &dem, &ddem);  // even energy, odd stress
    EXPECT_EQ(em, e);
    EXPECT_EQ(dem, -de);
    EXPECT_EQ(ddem, dde);
    // monotone between its knot values: κ within [min k, max k], so the stress rises
    EXPECT_GE(dde, 0.5 - 1e-12);
    EXPECT_LE(dde, 3.5 + 1e-12);
  }
  double e, de, dde;  // convex near 0: ½k_0 s²
  curve.evaluate(1e-4, k.data(), &e, &de, &dde);
  EXPECT_NEAR(e, 0.5 * 3.5 * 1e-8, 1e-15);
  EXPECT_THROW(ShearStiffnessSpline({0.2, 0.1}), std::invalid_argument);
}

TEST(InPlaneShearSpline, WithEveryKnotAtTheSmallAngleStiffnessIsTheLinearLaw) {
  for (bool locking : {false, true}) {
    const double gl = locking ? 0.45 : 0.0, m = locking ? 3.0 : 0.0;
    InPlaneShearTerm linear(3.5, gl, m), spline(3.5, gl, m, kKnotsRad, std::vector<double>(4, 3.5));
    const TriangleRest r = triangle_rest(kUv0, kUv1, kUv2);
    linear.add(iota9(), r);
    spline.add(iota9(), r);
    for (const test::LocalState& s : sheared_states()) {
      Eigen::Matrix<double, 9, 1> fl = Eigen::Matrix<double, 9, 1>::Zero(), fs = fl;
      ElementOutput ol, os;
      ol.force = fl.data();
      os.force = fs.data();
      linear.evaluate(0, s.q.data(), s.v.data(), ol);
      spline.evaluate(0, s.q.data(), s.v.data(), os);
      EXPECT_NEAR(spline.energy(0, s.q.data()), linear.energy(0, s.q.data()), 1e-12 * linear.energy(0, s.q.data()));
      EXPECT_LT((fs - fl).norm(), 1e-12 * fl.norm());
      EXPECT_GT(fl.norm(), 0.0);
    }
  }
}

TEST(InPlaneShearSpline, SoftensBetweenTheKnots) {
  // The law's tangent stiffness in s is κ + ½k_sh ψ_lock''; without the lock, κ at each knot is its value.
  InPlaneShearTerm t(3.5, 0.0, 0.0, kKnotsRad, kKnotValues);
  for (size_t i = 0; i < kKnotsRad.size(); ++i) {
    double e, de, dde;
    t.density(std::sin(kKnotsRad[i]), &e, &de, &dde);
    EXPECT_NEAR(dde, kKnotValues[i], 1e-12);
  }
  double e, de, dde;
  t.density(0.0, &e, &de, &dde);
  EXPECT_EQ(dde, 3.5);
}

TEST(InPlaneShearSpline, ForcesAndJacobianMatchFiniteDifferences) {
  for (bool locking : {false, true}) {
    InPlaneShearTerm t(3.5, locking ? 0.45 : 0.0, locking ? 3.0 : 0.0, kKnotsRad, kKnotValues);
    const TriangleRest r = triangle_rest(kUv0, kUv1, kUv2);
    t.add(iota9(), r);
    const auto states = sheared_states();
    EXPECT_GT(std::abs(shear_sine(r, states.back().q)), std::sin(kKnotsRad.back()));  // the tail is sampled
    const auto rep = test::check_element(t, 0, states);
    EXPECT_TRUE(rep.ok) << (locking ? "with the lock\n" : "") << rep.detail;
  }
}

TEST(InPlaneShearSpline, EveryParameterDerivativeMatchesFiniteDifferences) {
  // k_sh, γ_lock, m, k_1 … k_4 (with the lock), and k_sh, k_1 … k_4 without it.
  for (bool locking : {true, false}) {
    std::vector<double> base{3.5};
    if (locking) base.insert(base.end(), {0.45, 3.0});
    base.insert(base.end(), kKnotValues.begin(), kKnotValues.end());
    const int lock_params = locking ? 2 : 0;
    {
      InPlaneShearTerm probe(3.5, locking ? 0.45 : 0.0, locking ? 3.0 : 0.0, kKnotsRad, kKnotValues);
      ASSERT_EQ(probe.parameter_keys().size(), base.size());
      EXPECT_EQ(probe.parameter_keys().back(), "fem.shear_knot4_N_per_m");
    }
    for (size_t k = 0; k < base.size(); ++k) {
      auto make = [&](double p) {
        std::vector<double> v = base;
        v[k] = p;
        const double gl = locking ? v[1] : 0.0, m = locking ? v[2] : 0.0;
        auto t = std::make_unique<InPlaneShearTerm>(v[0], gl, m, kKnotsRad,
                                                    std::vector<double>(v.begin() + 1 + lock_params, v.end()));
        t->add(iota9(), triangle_rest(kUv0, kUv1, kUv2));
        return std::unique_ptr<Term>(std::move(t));
      };
      const auto r = test::check_parameter_derivative(make, base[k], static_cast<int>(k), 0, sheared_states());
      EXPECT_TRUE(r.ok) << "parameter " << k << (locking ? " with the lock" : "") << "\n" << r.detail;
    }
  }
}

}  // namespace
}  // namespace wl
