// The progress line of a run: percentage of the simulated time, simulated time, step, wall time
// spent and an estimate of the time left (wall time so far × remaining / done simulated time).
//
// On a terminal the line is rewritten in place about every 0.5 s; otherwise (a log file, a CI
// job) one plain line is printed about every 5 s, so long runs are never silent and logs stay
// short. Mode::off (nmm-solve --quiet) prints nothing.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>

namespace nmm::solve {

class ProgressLine {
 public:
  enum class Mode { off, terminal, plain };
  /// `t_end`: simulated time at the end of the run, s. `out`: where the lines go (stderr).
  ProgressLine(Mode mode, double t_end, std::FILE* out = stderr,
               double terminal_period = 0.5, double plain_period = 5.0);
  /// A warning for the user (nmm-solve: slow BLAS kernels, blas_info.h), printed on a line of its
  /// own before the first progress line: so a long run shows it, while a short run that fails
  /// keeps the one line that says why, and --quiet prints nothing.
  void set_warning(std::string text) { warning_ = std::move(text); }
  /// After an accepted step: prints when the period has passed since the last line.
  void update(std::int64_t step, double time);
  /// At the end of a run that ended ok: the last line, with `note` after it (nmm-solve: the
  /// status and the equilibrium verdict). Any other end prints nothing (the caller's one line
  /// says why), a terminal's in-place line is only ended.
  void finish(std::int64_t step, double time, bool ended_ok, const std::string& note = "");
  /// The text of one line (no line ending), for tests.
  std::string line(std::int64_t step, double time, double wall_seconds) const;

  /// Mode::terminal when `out` is a terminal, else Mode::plain; Mode::off when quiet.
  static Mode choose(bool quiet, std::FILE* out = stderr);

 private:
  using Clock = std::chrono::steady_clock;
  double seconds_since_start() const;

  Mode mode_;
  double t_end_;  // s
  std::FILE* out_;
  double period_;     // s of wall time between lines
  Clock::time_point start_;
  double last_ = 0;   // s since start when the last line was printed
  bool printed_ = false;
  std::string warning_;  // printed once, before the first line (set_warning)
  void print_warning();
};

}  // namespace nmm::solve
