// SIGINT and SIGTERM end a run cleanly: the handler only records the signal;
// the run driver checks it after every accepted step and at every output time,
// then writes the frames so far, a complete metrics.csv and a summary with
// outcome `interrupted`. A second signal of the same kind ends the process at
// once (default action). SIGPIPE is ignored, so a closed stderr pipe only
// silences the progress and never loses the record.
#pragma once
#include <csignal>
#include <string>

namespace wl {

void install_interrupt_handlers();
// The signal received since install_interrupt_handlers() (SIGINT, SIGTERM), or 0.
int interrupt_signal();
// Forgets the recorded signal (a host process that goes on after an interrupted run).
void clear_interrupt_signal();
// What a record says of a run the signal ended: "interrupted by SIGINT",
// "interrupted by SIGTERM" ("interrupted by a signal" for any other).
std::string interrupted_message(int signal);
// Conventional exit status of a process ended by `signal`: 128 + signal.
int interrupted_exit_code(int signal);

// Thrown from a step callback to end a run after the step a signal arrived in
// (integrators let an exception from on_step pass; the caller catches it and
// records outcome `interrupted`). A driver that writes the record of what was
// reached (driver/interrupted_record.h) passes it on with `stage` naming where.
struct Interrupted {
  std::string stage;  // e.g. "the continuum run"; empty until a driver names it
};
// Throws Interrupted when a signal was recorded.
void throw_if_interrupted();

// For a run inside a host process that has its own handlers (the Python
// module): install_interrupt_handlers() for the object's lifetime, with the
// recorded signal cleared first; the host's SIGINT and SIGTERM handlers come
// back afterwards and the signal is forgotten (a later call, on any thread,
// starts unstopped). SIGPIPE is left as the host set it.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  struct sigaction host_int_ {};
  struct sigaction host_term_ {};
};

}  // namespace wl
