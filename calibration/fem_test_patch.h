// Continuum patches kept over calibration's curve evaluations (docs/calibration.md §4):
// a fit evaluates every test curve hundreds of times at new parameters on the
// same patch, so the mesh, the terms' stencils, the assembly (pattern,
// colouring, slots), the crossing map and the equilibrium solver's reduced
// pattern are made once per test and the model is re-parameterized
// (FemModel::set_material). Each curve is bitwise run_fem_test()'s.
#pragma once
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "calibration/virtual_tests.h"
#include "models/fem/fem_material.h"

namespace wl {

class FemModel;

// One test's patch.
class FemTestPatch {
 public:
  FemTestPatch(const Scene& test_scene, const FemMaterial& material, const TestSpec& test);
  ~FemTestPatch();
  FemTestPatch(const FemTestPatch&) = delete;
  FemTestPatch& operator=(const FemTestPatch&) = delete;
  const TestSpec& test() const { return test_; }
  // = run_fem_test(test_scene, material, test, parameter_keys, options), bitwise.
  ResponseCurve run(const FemMaterial& material, const std::vector<std::string>& parameter_keys = {},
                    const EquilibriumOptions& options = {});

 private:
  std::unique_ptr<FemModel> model_;
  TestSpec test_;
  TestPoints points_;
  EquilibriumSolver eq_;
};

// The patches of every test a fit evaluates, one set per calling thread (a
// model is not shared between threads, docs/design.md §3.4): run() may be
// called from several threads at once.
class FemTestPatches {
 public:
  explicit FemTestPatches(Scene test_scene) : scene_(std::move(test_scene)) {}
  ResponseCurve run(const FemMaterial& material, const TestSpec& test,
                    const std::vector<std::string>& parameter_keys = {}, const EquilibriumOptions& options = {});

 private:
  struct Entry {
    std::thread::id thread;
    std::unique_ptr<FemTestPatch> patch;
  };
  Scene scene_;
  std::mutex mutex_;  // guards entries_ (each patch is used by its thread only)
  std::vector<Entry> entries_;
};

}  // namespace wl
