// Interrupting a run with SIGINT (Ctrl-C) or SIGTERM: the signal only sets a flag; the time
// stepping checks it between steps, so the step under way finishes, and the run then writes
// history.csv, summary.json (status "interrupted") and the checkpoint like any stopped run.
// nmm-solve exits with 130 (128 + SIGINT, the shell's convention). A second signal while the
// run is finishing its step ends the process at once (the default action is restored).
#pragma once

namespace nmm::solve {

/// Exit status of a run stopped by SIGINT or SIGTERM.
inline constexpr int kExitInterrupted = 130;

/// Installs the SIGINT and SIGTERM handlers (idempotent).
void install_interrupt_handlers();

/// True once SIGINT or SIGTERM arrived (or request_interrupt() was called).
bool interrupt_requested();

/// Sets the flag as a signal would (tests).
void request_interrupt();

}  // namespace nmm::solve
