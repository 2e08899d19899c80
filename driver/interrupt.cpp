#include "driver/interrupt.h"

namespace wl {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void record_signal(int sig) { g_signal = sig; }

// Records the signal; a second one takes the default action.
struct sigaction recording_action() {
  struct sigaction sa {};
  sa.sa_handler = record_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND | SA_RESTART;
  return sa;
}

}  // namespace

void install_interrupt_handlers() {
  const struct sigaction sa = recording_action();
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGPIPE, &ignore, nullptr);
}

int interrupt_signal() { return g_signal; }

void clear_interrupt_signal() { g_signal = 0; }

std::string interrupted_message(int signal) {
  return std::string("interrupted by ") + (signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal");
}

int interrupted_exit_code(int signal) { return 128 + signal; }

void throw_if_interrupted() {
  if (g_signal) throw Interrupted{};
}

InterruptScope::InterruptScope() {
  clear_interrupt_signal();
  const struct sigaction sa = recording_action();
  sigaction(SIGINT, &sa, &host_int_);
  sigaction(SIGTERM, &sa, &host_term_);
}

InterruptScope::~InterruptScope() {
  sigaction(SIGINT, &host_int_, nullptr);
  sigaction(SIGTERM, &host_term_, nullptr);
  clear_interrupt_signal();
}

}  // namespace wl
