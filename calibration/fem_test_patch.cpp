#include "calibration/fem_test_patch.h"

#include "models/fem/fem_model.h"

namespace wl {

FemTestPatch::FemTestPatch(const Scene& test_scene, const FemMaterial& material, const TestSpec& test)
    : model_(std::make_unique<FemModel>(test_scene, material_test_mesh(test_scene), material)),
      test_(test),
      points_(continuum_test_points(test_scene, *model_)),
      eq_(*model_, held_dofs(points_, test)) {}

FemTestPatch::~FemTestPatch() = default;

ResponseCurve FemTestPatch::run(const FemMaterial& material, const std::vector<std::string>& keys,
                                const EquilibriumOptions& options) {
  model_->set_material(material);
  eq_.restart();
  return run_material_test(*model_, eq_, points_, test_, keys, options);
}

ResponseCurve FemTestPatches::run(const FemMaterial& material, const TestSpec& test,
                                  const std::vector<std::string>& keys, const EquilibriumOptions& options) {
  FemTestPatch* patch = nullptr;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::thread::id me = std::this_thread::get_id();
    for (Entry& e : entries_)
      if (e.thread == me && e.patch->test().kind == test.kind && e.patch->test().rotated == test.rotated &&
          e.patch->test().ladder == test.ladder)
        patch = e.patch.get();
    if (!patch) {
      entries_.push_back({me, std::make_unique<FemTestPatch>(scene_, material, test)});
      patch = entries_.back().patch.get();
    }
  }
  return patch->run(material, keys, options);
}

}  // namespace wl
