#include "driver/diagnose.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

#include "driver/energy_split.h"
#include "driver/experiment_meta.h"
#include "driver/interrupted_record.h"
#include "driver/recorded_run.h"
#include "driver/time_error.h"
#include "models/core/term_model.h"
#include "models/fem/fem_material.h"
#include "models/fem/fem_model.h"
#include "models/model_factory.h"
#include "output/atomic_file.h"
#include "output/csv_table.h"
#include "output/json_writer.h"
#include "output/pvd_series.h"

namespace wl {
namespace {

// Energies of one model along its run: at every output frame the kinetic
// energy, each conservative term's potential and each other term's work so far.
class EnergyLedger {
 public:
  EnergyLedger(std::string model, const Scene& scene) : model_(std::move(model)), scene_(scene) {}
  // After every accepted step (and once at t = 0): W_k += ½(P_k(t₀) + P_k(t₁))(t₁ − t₀).
  void step(Model& model, double t, const Vec& q, const Vec& v) {
    if (!split_) split_ = std::make_unique<EnergySplit>(model, scene_);
    model_at_ = &model;
    q_ = q;
    auto& terms = dynamic_cast<TermModel&>(model);
    std::vector<TermModel::TermReading> now = terms.term_readings(t, q, v);
    if (!last_.empty())
      for (size_t k = 0; k < now.size(); ++k) work_[k] += 0.5 * (last_[k].power_W + now[k].power_W) * (t - t_);
    else work_.assign(now.size(), 0.0);
    Evaluation scratch;
    kinetic_ = model.kinetic_energy(t, q, v, scratch);
    last_ = std::move(now);
    t_ = t;
  }
  // Rows (time, model, quantity, joules) at the state of the last step.
  void frame_rows(CsvTable& csv) const {
    auto row = [&](const std::string& what, double value) {
      csv.row({csv_number(t_), model_, what, csv_number(value)});
    };
    row("kinetic", kinetic_);
    for (size_t k = 0; k < last_.size(); ++k) {
      if (last_[k].mass) continue;  // in the kinetic energy
      if (last_[k].conservative) row(last_[k].name, last_[k].energy_J);
      else row("work of " + last_[k].name, work_[k]);
    }
  }
  // Rows (time, model, term, warp part, weft part) at the state of the last step.
  void direction_rows(CsvTable& csv) const {
    const std::vector<EnergyPart> parts = split_->parts(*model_at_, q_);
    for (size_t k = 0; k + 1 < parts.size(); k += 2)
      csv.row(
          {csv_number(t_), model_, parts[k].term, csv_number(parts[k].energy_J), csv_number(parts[k + 1].energy_J)});
  }

 private:
  std::string model_;
  const Scene& scene_;
  std::unique_ptr<EnergySplit> split_;  // built at the first step, for the run's model
  const Model* model_at_ = nullptr;     // the model and state of the last step
  Vec q_;
  std::vector<TermModel::TermReading> last_;
  std::vector<double> work_;
  double kinetic_ = 0, t_ = 0;
};

const DataArray& frame_point_array(const Frame& f, const std::string& name) {
  for (const DataArray& a : f.point_data)
    if (a.name == name) return a;
  throw std::logic_error("diagnose: frame without point data '" + name + "'");
}

struct ModelRun {
  RecordedRun run;
  std::vector<Frame> frames;
};

// The model a side of the comparison builds: the scene's yarn level ("yarn" or "knit") or "fem".
std::string model_of_side(const Scene& s, const std::string& side) {
  return side == "fem" ? side : yarn_level_model(s);
}

// `side` is "yarn" (the scene's yarn level) or "fem".
ModelRun run_with_ledger(const Scene& s, const std::string& side, EnergyLedger& ledger, CsvTable& energies,
                         CsvTable& directions, bool progress) {
  const std::string model = model_of_side(s, side);
  ModelRun out;
  {  // the initial state
    std::unique_ptr<Model> m = make_model(s, model);
    ledger.step(*m, 0.0, m->initial_q(), m->initial_v());
    ledger.frame_rows(energies);
    ledger.direction_rows(directions);
  }
  RecordOptions rec;
  rec.progress = progress;
  rec.label = model;
  rec.step_ends = true;
  rec.stop_at_signal = true;
  rec.on_step = [&](Model& m, double t, const Vec& q, const Vec& v) { ledger.step(m, t, q, v); };
  rec.on_frame = [&](const Frame& f) {
    ledger.frame_rows(energies);
    ledger.direction_rows(directions);
    out.frames.push_back(f);
  };
  if (progress) std::fprintf(stderr, "diagnose: %s model, %s\n", model.c_str(), s.integrator.c_str());
  out.run = run_recorded(s, model, s.integrator, scene_integrator_options(s), rec);
  if (out.run.result.outcome != Outcome::ok)
    throw std::runtime_error("the " + model + " run ended '" + to_string(out.run.result.outcome) +
                             "' at t = " + std::to_string(out.run.end_time) + " s: " + out.run.result.message);
  return out;
}

double time_error_of(const Scene& s, const std::string& side, const RecordedRun& run, const DiagnoseConfig& c,
                     Json& record, TimeErrorEstimate& e) {
  const std::string model = model_of_side(s, side);
  e.second_run.outcome = Outcome::not_offered;
  if (!c.error_estimate) return NAN;
  if (c.progress) std::fprintf(stderr, "diagnose: %s time error\n", model.c_str());
  e = estimate_time_error(s, model, s.integrator, scene_integrator_options(s), run);
  record.set(side + "_time_error", e.to_json());
  return e.ok() ? e.mean_rms : NAN;
}

}  // namespace

DiagnoseResult run_diagnosis(const DiagnoseConfig& c) {
  Scene yarn_scene = at_time_steps(c.scene, c.time_steps);
  Scene fem_scene = yarn_scene;
  if (c.fem_params) fem_scene.fem.parameter_file = c.fem_params->string();
  (void)fem_material(fem_scene);  // a bad file: FemParameterError, before anything is written
  // Each side's initial state, as `run` checks it (a node inside an obstacle: invalid_argument).
  for (const auto& [scene, side] : {std::pair{&yarn_scene, "yarn"}, std::pair{&fem_scene, "fem"}})
    (void)make_model(*scene, model_of_side(*scene, side));

  Json record = Json::object();
  record.set("scene", scene_json(c.scene_path, c.scene.text, c.scene, c.overrides));
  record.set("resolution", c.time_steps.describe());
  record.set("continuum_parameters",
             c.fem_params ? c.fem_params->string() : "the scene's (first guess without a file)");
  std::filesystem::create_directories(c.out_dir);
  CsvTable energies(c.out_dir / "energies.csv", {"time_s", "model", "quantity", "value_J"});
  EnergyLedger yarn_ledger("yarn", yarn_scene), fem_ledger("fem", fem_scene);
  CsvTable directions(c.out_dir / "energy_directions.csv", {"time_s", "model", "term", "warp_J", "weft_J"});
  // A signal ends the stage under way at its step: the energies so far and diagnosis.json
  // with outcome interrupted (driver/interrupted_record.h).
  std::string stage = "the yarn-level run";
  auto record_interruption = [&] {
    energies.commit();
    directions.commit();
    mark_interrupted(record, stage);
    record.set("created", utc_now());
    add_provenance(record);
    write_file_atomically(c.out_dir / "diagnosis.json", record.dump());
    return Interrupted{stage};
  };
  ModelRun yarn, fem;
  try {
    yarn = run_with_ledger(yarn_scene, "yarn", yarn_ledger, energies, directions, c.progress);
    stage = "the continuum run";
    fem = run_with_ledger(fem_scene, "fem", fem_ledger, energies, directions, c.progress);
  } catch (const Interrupted&) {
    throw record_interruption();
  }
  energies.commit();
  directions.commit();

  // Per crossing: its grid position (from the rest material coordinates) and distance per frame.
  const Frame& first = yarn.frames.front();
  const DataArray &u0 = frame_point_array(first, "u"), &v0 = frame_point_array(first, "v");
  const double L = c.scene.spacing_m;
  const int crossings = static_cast<int>(first.points.rows());
  std::vector<int> row_of(crossings);
  std::vector<char> border(crossings);
  int rows = 0;
  for (int n = 0; n < crossings; ++n) {
    const int i = static_cast<int>(std::lround(u0.values[n] / L)), j = static_cast<int>(std::lround(v0.values[n] / L));
    row_of[n] = j;
    border[n] = i == 0 || j == 0 || i == c.scene.wefts - 1 || j == c.scene.warps - 1;
    rows = std::max(rows, j + 1);
  }
  const FemModel geometry(fem_scene);
  CsvTable distance(c.out_dir / "distance.csv",
                    {"time_s", "rms_m", "max_m", "border_rms_m", "interior_rms_m", "farthest_crossing"});
  PvdSeries series(c.out_dir, "distance");
  std::vector<double> row_sum(rows, 0.0), crossing_sum(crossings, 0.0);
  std::vector<long> row_count(rows, 0);
  double sum_rms = 0, border_sum = 0, interior_sum = 0;
  long border_count = 0, interior_count = 0;
  const size_t frames = std::min(yarn.frames.size(), fem.frames.size());
  for (size_t k = 0; k < frames; ++k) {
    Frame f = yarn.frames[k];
    const DataArray &u = frame_point_array(f, "u"), &v = frame_point_array(f, "v");
    const Vec q = Eigen::Map<const Vec>(fem.frames[k].points.data(), fem.frames[k].points.size());
    DataArray d{"distance_to_continuum_m", 1, {}};
    double sum = 0, max = 0, b = 0, in = 0;
    long nb = 0, ni = 0;
    int farthest = 0;
    for (int n = 0; n < crossings; ++n) {
      Vec3 s;
      const double x = geometry.surface_point(q, Vec2(u.values[n], v.values[n]), &s)
                           ? (s - f.points.row(n).transpose()).norm()
                           : NAN;  // slid out of the mesh
      d.values.push_back(x);
      if (std::isnan(x)) continue;
      sum += x * x;
      if (x > max) max = x, farthest = n;
      (border[n] ? b : in) += x * x;
      ++(border[n] ? nb : ni);
      row_sum[row_of[n]] += x * x;
      ++row_count[row_of[n]];
      crossing_sum[n] += x * x;
    }
    const long compared = nb + ni;
    const double rms = compared ? std::sqrt(sum / compared) : NAN;
    sum_rms += rms;
    border_sum += b, interior_sum += in, border_count += nb, interior_count += ni;
    distance.row({csv_number(f.time), csv_number(rms), csv_number(max), csv_number(nb ? std::sqrt(b / nb) : NAN),
                  csv_number(ni ? std::sqrt(in / ni) : NAN), std::to_string(farthest)});
    f.point_data.push_back(std::move(d));
    series.add(f);
  }
  distance.commit();
  CsvTable by_row(c.out_dir / "rows.csv", {"row", "rms_m"});
  for (int j = 0; j < rows; ++j)
    by_row.row({std::to_string(j), csv_number(row_count[j] ? std::sqrt(row_sum[j] / row_count[j]) : NAN)});
  by_row.commit();

  DiagnoseResult r;
  r.mean_rms_m = frames > 0 ? sum_rms / double(frames) : NAN;  // one frame after t = 0 is a valid run
  r.border_rms_m = border_count ? std::sqrt(border_sum / border_count) : NAN;
  r.interior_rms_m = interior_count ? std::sqrt(interior_sum / interior_count) : NAN;

  record.set("distance_mean_rms_m", r.mean_rms_m);
  record.set("border_rms_m", r.border_rms_m);
  record.set("interior_rms_m", r.interior_rms_m);
  record.set("yarn_steps", yarn.run.stats.steps);
  record.set("fem_steps", fem.run.stats.steps);
  TimeErrorEstimate ye, fe;
  stage = "the yarn-level time error";
  r.yarn_time_error_m = time_error_of(yarn_scene, "yarn", yarn.run, c, record, ye);
  if (interrupt_signal()) throw record_interruption();  // the estimate ends its second run at a signal
  stage = "the continuum time error";
  r.fem_time_error_m = time_error_of(fem_scene, "fem", fem.run, c, record, fe);
  if (interrupt_signal()) throw record_interruption();
  r.verdict = error_budget_verdict(r.mean_rms_m, ye, fe);
  record.set("verdict", r.verdict);
  std::vector<int> order(crossings);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return crossing_sum[a] > crossing_sum[b]; });
  Json farthest = Json::array();
  for (int k = 0; k < std::min(crossings, 5); ++k) {
    const int n = order[k];
    farthest.push(Json::object()
                      .set("crossing", n)
                      .set("u_m", u0.values[n])
                      .set("v_m", v0.values[n])
                      .set("rms_m", std::sqrt(crossing_sum[n] / std::max<size_t>(frames, 1))));
  }
  record.set("farthest_crossings", std::move(farthest));
  record.set("created", utc_now());
  add_provenance(record);
  write_file_atomically(c.out_dir / "diagnosis.json", record.dump());
  return r;
}

}  // namespace wl
