// Adds the wall and CPU time of a scope to IntegratorStats (all integrators).
#pragma once
#include <chrono>
#include <ctime>

#include "integrators/integrator.h"

namespace wl {

class StepClock {
 public:
  explicit StepClock(IntegratorStats& stats)
      : stats_(stats), wall0_(std::chrono::steady_clock::now()), cpu0_(std::clock()) {}
  ~StepClock() {
    stats_.wall_s += elapsed_wall();
    stats_.cpu_s += double(std::clock() - cpu0_) / CLOCKS_PER_SEC;
  }
  StepClock(const StepClock&) = delete;
  StepClock& operator=(const StepClock&) = delete;
  double elapsed_wall() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  }

 private:
  IntegratorStats& stats_;
  std::chrono::steady_clock::time_point wall0_;
  std::clock_t cpu0_;
};

}  // namespace wl
