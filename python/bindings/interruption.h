// Ctrl-C during a long call (docs/python.md, "Interrupting"): on Python's main
// thread the run driver's handlers (driver/interrupt.h) stand in
// for Python's during the call, so the step under way ends and the call
// returns what it has, with outcome "interrupted"; a second Ctrl-C ends the
// process, as on the command line. Calls from other threads keep Python's
// handlers (Python delivers signals to its main thread only).
#pragma once
#include <optional>

#include "driver/interrupt.h"

namespace wl::python {

class CallInterruption {
 public:
  CallInterruption();  // with the GIL held
  // A signal arrived during the call (thrown from a step callback to end it there).
  bool requested() const { return scope_ && interrupt_signal() != 0; }

 private:
  std::optional<InterruptScope> scope_;
};

}  // namespace wl::python
