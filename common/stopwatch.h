// Wall-clock seconds of a piece of work (steady clock: never jumps with the system time). One
// stopwatch for the tools' timings (the preprocessor's phases, nmm-study's runs) and the
// benches.
#pragma once

#include <chrono>

namespace nmm {

class Stopwatch {
 public:
  Stopwatch() : start_(Clock::now()) {}
  /// Starts again from zero.
  void restart() { start_ = Clock::now(); }
  /// s since construction or the last restart.
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

}  // namespace nmm
