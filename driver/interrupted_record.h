// The record a signal leaves in a study's output folder (README, "Exit codes"):
// SIGINT or SIGTERM ends the current step (an integrator step, a Newton or
// energy-descent iteration, a tile sample); the study's JSON then says outcome
// "interrupted", the stage the signal ended (interrupted_in) and which signal,
// beside what was reached, and every table begun is committed with its rows so
// far (no .part file is left). The driver throws Interrupted{stage} on, and the
// command line (cli/exit_codes.h, interruptible) exits 130 / 143.
#pragma once
#include <string>

#include "driver/interrupt.h"
#include "output/json_writer.h"

namespace wl {

// True once a signal was recorded: the stop hook of equilibrium solves
// (EquilibriumOptions::stop_requested) and fits.
bool signal_received();

// Sets "outcome": "interrupted", "interrupted_in": stage and "message": "interrupted by SIGTERM".
void mark_interrupted(Json& record, const std::string& stage);

}  // namespace wl
