// SIGINT/SIGTERM handling: see interrupt.h. A handler may only touch a volatile sig_atomic_t
// and call async-signal-safe functions (signal() is one), so it sets the flag and restores the
// default action; everything else happens between steps.
#include "solver/stepping/interrupt.h"

#include <csignal>

namespace nmm::solve {
namespace {

volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_interrupt(int sig) {
  g_interrupted = 1;
  std::signal(sig, SIG_DFL);  // a second Ctrl-C ends the process at once
}

}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
}

bool interrupt_requested() { return g_interrupted != 0; }

void request_interrupt() { g_interrupted = 1; }

}  // namespace nmm::solve
