// In-process runs for the integrator experiments: a scene run with one model
// and integrator, recording node positions at the output times (no VTU
// output), its outcome, statistics and timings. Uses only the Model and
// Integrator interfaces (models/core/model.h, integrators/integrator.h).
#pragma once
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "integrators/integrator.h"
#include "models/core/frame.h"
#include "models/scene/scene.h"

namespace wl {

// Node positions (Model::frame(...).points, i.e. the x DoFs of every node) at
// the output times t_k = k·output_interval_s, k = 1 … ⌊duration/interval⌉ (the
// last one clamped to the duration; t = 0 is left out, it is the same for all
// runs). positions.col(k) = (x₀, y₀, z₀, x₁, …) at times[k].
struct Trajectory {
  std::vector<double> times;
  Eigen::MatrixXd positions;  // 3·nodes × times
  int nodes() const { return static_cast<int>(positions.rows() / 3); }
};

// The output times of a scene (see Trajectory).
std::vector<double> output_times(const Scene& scene);

struct RecordedRun {
  StepResult result;            // outcome, message and, for a SUNDIALS failure, its flag
  IntegratorStats stats;        // the integrator's own statistics
  double cpu_s = 0.0;           // process CPU time of initialize + advance_to (all threads), frames excluded
  double wall_s = 0.0;          // wall time of the same
  double end_time = 0.0;        // time reached
  double max_node_speed = 0.0;  // largest Model::max_node_speed over all accepted steps [m/s]
  int dofs = 0;
  Trajectory trajectory;  // the output times reached
  // Kinetic ½vᵀM(q)v and potential energy at the output times reached, when
  // RecordOptions::energies (outside the timed sections) [J].
  std::vector<double> kinetic_J, potential_J;
  double initial_energy_J = 0.0;  // T + V at t = 0, when RecordOptions::energies [J]
  std::vector<double> step_ends;  // the time after each accepted step, when RecordOptions::step_ends [s]
};

struct RecordOptions {
  // A run whose max node speed exceeds this stops with Outcome::diverged (it is
  // also passed as IntegratorOptions::runaway_speed when smaller) [m/s].
  double speed_bound = std::numeric_limits<double>::infinity();
  bool progress = false;  // a line on stderr every few seconds
  std::string label;      // prefix of the progress lines
  // Called with every recorded output frame (after the trajectory column is stored).
  std::function<void(const Frame&)> on_frame;
  // Called after every accepted step with the model and the state at its end
  // (inside the timed section: a diagnostic, not for timed runs).
  std::function<void(Model&, double t, const Vec& q, const Vec& v)> on_step;
  bool energies = false;   // fill RecordedRun::kinetic_J and potential_J
  bool step_ends = false;  // fill RecordedRun::step_ends
  // Throw Interrupted (driver/interrupt.h) after the step a SIGINT or SIGTERM arrived in.
  bool stop_at_signal = false;
  // Step ends to take one fixed step each, in increasing order and holding every
  // output time (a replay of a recorded step sequence; the integrator must
  // declare replays_steps). Empty: the integrator chooses its steps.
  std::vector<double> schedule;
};

// Runs `scene` with `model_name` ("yarn", "fem") and `integrator_name` to the
// scene's duration. A numerical failure is an outcome, not an exception;
// std::invalid_argument for an unknown model or integrator.
RecordedRun run_recorded(const Scene& scene, const std::string& model_name, const std::string& integrator_name,
                         const IntegratorOptions& options, const RecordOptions& record = {});

}  // namespace wl
