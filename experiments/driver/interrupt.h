// SIGINT and SIGTERM end a run cleanly: the handler only records the signal;
// the run driver checks it after every accepted step and at every output time,
// then writes the frames so far, a complete metrics.csv and a summary with
// outcome `interrupted`. A second signal of the same kind ends the process at
// once (default action). SIGPIPE is ignored, so a closed stderr pipe only
// silences the progress and never loses the record.
#pragma once

namespace wl {

void install_interrupt_handlers();
// The signal received since install_interrupt_handlers() (SIGINT, SIGTERM), or 0.
int interrupt_signal();
// Conventional exit status of a process ended by `signal`: 128 + signal.
int interrupted_exit_code(int signal);

}  // namespace wl
