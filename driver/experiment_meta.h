// Shared pieces of the experiment metadata JSON (work-precision, stability):
// the scene block, the integrator statistics, a UTC time stamp, a text hash
// and the provenance (git revision, machine, OpenMP threads).
#pragma once
#include <filesystem>
#include <map>
#include <string>

#include "integrators/integrator.h"
#include "models/scene/scene.h"
#include "output/json_writer.h"

namespace wl {

std::string utc_now();  // "2026-01-31T12:00:00Z"
// FNV-1a 64 of a text as 16 hex digits (scene hashes, reference cache files).
std::string text_hash(const std::string& text);
Json statistics_json(const IntegratorStats& stats);
// file, name, text, overrides, duration_s, output_interval_s, nodes (warps × wefts)
Json scene_json(const std::filesystem::path& path, const std::string& text, const Scene& scene,
                const std::map<std::string, std::string>& overrides);
// Sets git_revision, machine, threads (the OpenMP and OpenBLAS thread counts in
// force, determinism.h) and environment (OMP_NUM_THREADS, OPENBLAS_NUM_THREADS) on an object.
void add_provenance(Json& j);

}  // namespace wl
