// The run summary JSON: scene, model, integrator, options, statistics,
// outcome, git revision and machine (docs/design.md §9).
#pragma once
#include <string>

#include "driver/run.h"
#include "integrators/integrator.h"
#include "models/core/model.h"

namespace wl {

// The summary's JSON text.
std::string run_summary_json(const Scene& scene, const RunOptions& options, const Model& model,
                             const Integrator& integrator, const RunReport& report);

}  // namespace wl
