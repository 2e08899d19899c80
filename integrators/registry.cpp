// The integrators by name (docs/design.md §6.1).
#include <stdexcept>

#include "integrators/arkode_integrator.h"
#include "integrators/backward_euler.h"
#include "integrators/ida_integrator.h"
#include "integrators/integrator.h"
#include "integrators/sdirk2.h"
#include "integrators/symplectic_euler.h"

namespace wl {

std::vector<std::string> integrator_names() {
  return {"be-linear", "be-newton", "sdirk2", "ida", "arkode-erk", "arkode-dirk", "arkode-imex", "symplectic"};
}

std::unique_ptr<Integrator> make_integrator(const std::string& name) {
  if (name == "be-linear") return std::make_unique<BackwardEuler>(BackwardEuler::Variant::linear);
  if (name == "be-newton") return std::make_unique<BackwardEuler>(BackwardEuler::Variant::newton);
  if (name == "sdirk2") return std::make_unique<Sdirk2>();
  if (name == "ida") return std::make_unique<IdaIntegrator>();
  if (name == "arkode-erk") return std::make_unique<ArkodeIntegrator>(ArkodeIntegrator::Variant::erk);
  if (name == "arkode-dirk") return std::make_unique<ArkodeIntegrator>(ArkodeIntegrator::Variant::dirk);
  if (name == "arkode-imex") return std::make_unique<ArkodeIntegrator>(ArkodeIntegrator::Variant::imex);
  if (name == "symplectic") return std::make_unique<SymplecticEuler>();
  std::string known;
  for (auto& n : integrator_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + name + "' (expected one of: " + known + ")");
}

}  // namespace wl
