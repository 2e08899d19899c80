// `ida`, `arkode-dirk` and `be-newton` agree on the yarn model at small steps
// (as the integrator experiments assume): a 6×6 hanging cloth from the published scene (wind,
// gravity, two handles, all yarn forces), 5 ms simulated (the cloth falls
// ~0.1 mm; the stiff handle and stretch modes keep the adaptive steps at a few
// µs, so 20 ms would cost arkode-dirk about a minute).
//
// The tolerance is derived from backward Euler's first-order global error
// e(h) ≈ C h: two BE runs at h and 2h give e(h) ≈ x(2h) − x(h) (Richardson),
// so E = RMS_nodes ‖x_BE(2h) − x_BE(h)‖ estimates BE's own error at h. The
// high-order adaptive runs at rtol 1e-5 are accurate far below E, so
//   RMS ‖x_ida − x_BE(h)‖ and RMS ‖x_dirk − x_BE(h)‖  ≤ 2 E   (factor 2: the
//     error constant C is not exactly step-independent at these steps),
//   RMS ‖x_ida − x_dirk‖ ≤ E / 4 (two accurate methods agree beyond BE's error),
// and the Richardson-extrapolated BE 2x(h) − x(2h) (second order) is within
// E/4 of ida — which fails if BE, ida or dirk solve a different problem, or if
// BE were not first order (measured: |ida − BE| = 1.01 E, |ida − extrapolated|
// = 0.07 E, |ida − dirk| ~ 1e-4 E). E itself must be small against the
// displacement (E < 5% of the RMS node displacement), so the agreement means
// something.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "integrators/integrator.h"
#include "models/scene/scene.h"
#include "models/yarn/yarn_model.h"

namespace wl {
namespace {

constexpr int kNodes = 6;
constexpr double kDuration = 0.005;  // [s]; 20 ms would take arkode-dirk ~1 min (steps ~5 µs)

Scene agreement_scene() {
  Scene s = load_scene(std::string(WEAVELAB_SOURCE_DIR) + "/experiments/scenes/hanging_wind.toml");
  s.warps = s.wefts = kNodes;
  // The scene's handles hold the two top corners of a 17×17 cloth.
  s.handles.at(0).node = {0, 0};
  s.handles.at(1).node = {kNodes - 1, 0};
  return s;
}

struct Positions {
  std::vector<Vec3> x;
  double wall_s = 0.0;
};

Positions positions(const YarnModel& m, const Vec& q) {
  Positions p;
  for (int j = 0; j < kNodes; ++j)
    for (int i = 0; i < kNodes; ++i) p.x.push_back(m.position(q, i, j));
  return p;
}

double rms(const Positions& a, const Positions& b) {
  double s = 0.0;
  for (size_t k = 0; k < a.x.size(); ++k) s += (a.x[k] - b.x[k]).squaredNorm();
  return std::sqrt(s / a.x.size());
}

Positions run(const std::string& name, IntegratorOptions opt) {
  YarnModel model(agreement_scene());
  auto integ = make_integrator(name);
  const auto t0 = std::chrono::steady_clock::now();
  integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
  const StepResult r = integ->advance_to(kDuration);
  EXPECT_EQ(r.outcome, Outcome::ok) << name << ": " << r.message;
  Positions p = positions(model, integ->q());
  p.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const IntegratorStats& st = integ->stats();
  std::printf("[ run   ] %-12s steps %6ld rejected %5ld newton %6ld setups %6ld wall %.2f s\n", name.c_str(), st.steps,
              st.rejected_steps, st.nonlinear_iters, st.linear_setups, p.wall_s);
  std::fflush(stdout);
  return p;
}

IntegratorOptions fixed(double dt) {
  IntegratorOptions o;
  o.dt = dt;
  o.newton_tol = 1e-10;  // Newton error far below BE's truncation error
  return o;
}

IntegratorOptions tight() {
  IntegratorOptions o;
  o.adaptive = true;
  o.rtol = 1e-5;  // measured |ida − dirk| ~ 1e-4·E: far below BE's error (asserted)
  o.atol = 1e-8;  // positions ~1e-2 m, velocities ~1e-2 m/s  // positions ~1e-2 m, velocities ~1e-1 m/s
  o.dt = 1e-6;
  return o;
}

TEST(YarnAgreement, IdaArkodeDirkAndBackwardEulerAgreeAtSmallSteps) {
  const double h = 1e-5;
  const Positions be_h = run("be-newton", fixed(h));
  const Positions be_2h = run("be-newton", fixed(2 * h));
  const Positions ida = run("ida", tight());
  const Positions dirk = run("arkode-dirk", tight());
  const Positions start = positions(YarnModel(agreement_scene()), YarnModel(agreement_scene()).initial_q());

  const double displacement = rms(be_h, start);
  const double E = rms(be_2h, be_h);  // ≈ BE's global error at h
  Positions extrapolated = be_h;
  for (size_t k = 0; k < extrapolated.x.size(); ++k) extrapolated.x[k] = 2 * be_h.x[k] - be_2h.x[k];
  std::printf(
      "[ agree ] displacement %.3e m, BE error estimate %.3e m; |ida-BE| %.3e |dirk-BE| %.3e "
      "|ida-dirk| %.3e |ida-extrapolated BE| %.3e; wall BE %.2f+%.2f s ida %.2f s dirk %.2f s\n",
      displacement, E, rms(ida, be_h), rms(dirk, be_h), rms(ida, dirk), rms(ida, extrapolated), be_h.wall_s,
      be_2h.wall_s, ida.wall_s, dirk.wall_s);

  EXPECT_GT(displacement, 5e-5) << "the cloth did not move";
  EXPECT_LT(E, 0.05 * displacement);
  EXPECT_LE(rms(ida, be_h), 2 * E);
  EXPECT_LE(rms(dirk, be_h), 2 * E);
  EXPECT_LE(rms(ida, dirk), E / 4);
  EXPECT_LT(rms(ida, extrapolated), E / 4);
}

}  // namespace
}  // namespace wl
