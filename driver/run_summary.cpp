#include "driver/run_summary.h"

#include "driver/experiment_meta.h"
#include "driver/memory_estimate.h"

namespace wl {
namespace {

// The scene's [measures] taken on the run's last frame (docs/models.md §3.11.6).
Json measures_json(const Scene& scene, const RunReport& report) {
  Json measures = Json::object();
  if (report.drape) {
    const DrapeGeometry g = drape_geometry(scene);
    Json d = Json::object();
    if (*report.drape) {
      d.set("time_s", (*report.drape)->time_s);
      d.set("coefficient", (*report.drape)->coefficient);
      d.set("folds", (*report.drape)->folds);
      d.set("projected_area_m2", (*report.drape)->projected_area_m2);
    } else {
      d.set("error", "the last frame's shadow spans more than " + std::to_string(long(kMaxShadowPixels)) +
                         " pixels (the run blew up?): not measured");
    }
    d.set("cloth_area_m2", g.cloth_area_m2);
    d.set("pedestal_radius_m", g.pedestal_radius_m);
    d.set("pixel_m", g.pixel_m);
    d.set("fold_prominence_m", g.fold_prominence_m);
    measures.set("drape", d);
  }
  return measures;
}

}  // namespace

std::string run_summary_json(const Scene& scene, const RunOptions& options, const Model& model,
                             const Integrator& integrator, const RunReport& report) {
  Json j = Json::object();
  Json s = scene_json(scene.source, scene.text, scene, options.overrides);
  s.set("dt_s", scene.dt_s);
  j.set("scene", s);
  Json m(model.describe());
  m.set("name", model.name());
  j.set("model", m);
  Json in = Json::object();
  in.set("name", integrator.name());
  const bool adaptive = scene.adaptive || report.accuracy;
  in.set("adaptive", adaptive);
  if (adaptive) {
    in.set("rtol", report.accuracy ? report.accuracy->rtol : scene.rtol);
    in.set("atol", report.accuracy ? report.accuracy->atol : scene.atol);
  }
  j.set("integrator", in);
  j.set("statistics", statistics_json(report.stats));
  Json mem = Json::object();
  const double peak = peak_resident_bytes();
  mem.set("peak_resident_bytes", peak);
  mem.set("peak_bytes_per_dof", peak / std::max(1, model.num_dofs()));
  mem.set("estimate_bytes", estimate_run_memory(scene, options.model).bytes);
  j.set("memory", mem);
  Json out = Json::object();
  out.set("outcome", to_string(report.result.outcome));
  out.set("message", report.result.message);
  out.set("end_time_s", report.end_time);
  out.set("frames", report.frames);
  j.set("result", out);
  if (report.time_error) j.set("time_error", report.time_error->to_json());
  if (report.accuracy) j.set("accuracy", report.accuracy->to_json());
  if (report.settled) {
    Json b = Json::object();
    b.set("after_s", scene.settle_after_s);
    b.set("dt_s", scene.settle_dt_s);
    b.set("max_free_dof_force_N", report.settled->max_force_N);
    b.set("max_mass_diagonal_times_g_N", report.settled->heaviest_weight_N);
    b.set("kinetic_J", report.settled->kinetic_J);
    j.set("settle", b);
  }
  if (report.drape) j.set("measures", measures_json(scene, report));
  add_provenance(j);
  j.set("finished_utc", utc_now());
  return j.dump();
}

}  // namespace wl
