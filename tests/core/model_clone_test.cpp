// Model::clone (docs/design.md §3.4): a clone gives bitwise the original's
// results, stays independent of it, and clones run concurrently in threads
// give bitwise the results of the same runs done one after another.
#include <gtest/gtest.h>

#include <thread>

#include "integrators/integrator.h"
#include "models/model_factory.h"
#include "tests/support/advanced_model.h"

namespace wl {
namespace {

// What one worker computes from its model, starting at (q, v): a full
// evaluation, the potential energy, the F_n of an output frame, and the state
// after a few be-newton steps (evaluations, friction history, accepted steps).
struct Work {
  Vec force, dfdq, dfdv, mass;
  double energy = 0.0;
  std::vector<double> frame_fn;
  Vec q_after;
};

Work work(Model& model, const Vec& q, const Vec& v) {
  Work w;
  Evaluation ev;
  model.evaluate(0.0, q, v, kForce | kDfdq | kDfdv | kMass, ev);
  w.force = ev.force;
  w.dfdq = Eigen::Map<const Vec>(ev.dfdq.valuePtr(), ev.dfdq.nonZeros());
  w.dfdv = Eigen::Map<const Vec>(ev.dfdv.valuePtr(), ev.dfdv.nonZeros());
  w.mass = Eigen::Map<const Vec>(ev.mass.valuePtr(), ev.mass.nonZeros());
  w.energy = model.potential_energy(q);
  for (const DataArray& a : model.frame(0.0, q, v).point_data)
    if (a.name == "F_n") w.frame_fn = a.values;
  auto integrator = make_integrator("be-newton");
  IntegratorOptions opt;
  opt.dt = 1e-3;
  integrator->initialize(model, 0.0, q, v, opt);
  EXPECT_EQ(integrator->advance_to(5e-3).outcome, Outcome::ok);
  w.q_after = integrator->q();
  return w;
}

void expect_identical(const Work& a, const Work& b, const std::string& what) {
  EXPECT_TRUE(a.force == b.force) << what;
  EXPECT_TRUE(a.dfdq == b.dfdq) << what;
  EXPECT_TRUE(a.dfdv == b.dfdv) << what;
  EXPECT_TRUE(a.mass == b.mass) << what;
  EXPECT_EQ(a.energy, b.energy) << what;
  EXPECT_EQ(a.frame_fn, b.frame_fn) << what;
  EXPECT_TRUE(a.q_after == b.q_after) << what;
}

void check_clones(const std::string& model_name, const std::string& extra_toml = "") {
  Vec q, v;
  auto original = test::advanced_model(model_name, extra_toml, q, v);
  constexpr int kWorkers = 4;
  // Worker k starts from the advanced state nudged by k·10 µm along a fixed pattern.
  std::vector<Vec> starts;
  for (int k = 0; k < kWorkers; ++k) {
    Vec nudge = Vec::LinSpaced(q.size(), -1.0, 1.0).array().sin();
    starts.push_back(q + 1e-5 * k * nudge);
  }
  Evaluation ev;
  original->evaluate(0.0, q, v, kForce, ev);
  const double energy_before = original->potential_energy(q);

  std::vector<std::unique_ptr<Model>> clones;
  for (int k = 0; k < kWorkers; ++k) clones.push_back(original->clone());
  std::vector<Work> serial;
  for (int k = 0; k < kWorkers; ++k) serial.push_back(work(*original->clone(), starts[k], v));

  std::vector<Work> parallel(kWorkers);
  std::vector<std::thread> threads;
  for (int k = 0; k < kWorkers; ++k) threads.emplace_back([&, k] { parallel[k] = work(*clones[k], starts[k], v); });
  for (auto& t : threads) t.join();

  for (int k = 0; k < kWorkers; ++k)
    expect_identical(parallel[k], serial[k], model_name + " worker " + std::to_string(k));
  // The workers differ from each other (the comparison above is not vacuous).
  EXPECT_FALSE(serial[0].q_after == serial[1].q_after);
  // The clones' evaluations and steps left the original as it was: its
  // potential energy reads the auxiliaries of its own last evaluation.
  EXPECT_EQ(original->potential_energy(q), energy_before) << model_name;
  // And the original, used directly, gives what its clone gave.
  expect_identical(work(*original, starts[0], v), serial[0], model_name + " original");
}

TEST(ModelClone, YarnClonesRunConcurrentlyWithTheSerialResults) { check_clones("yarn"); }

TEST(ModelClone, YarnWithCirioFrictionClonesRunConcurrentlyWithTheSerialResults) {
  check_clones("yarn", "[contact]\nfriction_model = \"cirio\"\nshear_model = \"cirio\"\n");
}

TEST(ModelClone, FemClonesRunConcurrentlyWithTheSerialResults) { check_clones("fem"); }

}  // namespace
}  // namespace wl
