// What a run's steps have cost, part by part (summary.json "timings", bench/ CSVs): wall seconds
// from common/stopwatch.h, and the counts behind them.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace nmm::solve {

/// Seconds spent per part of the run.
struct StepTimings {
  double contact_detection = 0;
  double assembly = 0;
  double factorisation = 0;
  double solves = 0;
  double geometry_update = 0;  ///< stresses, loop vertices, covers and points moved after a solve
  double output = 0;
  long factorisations = 0;     ///< numeric factorisations of the system matrix
  long solves_count = 0;       ///< triangular solve pairs (direct solves and preconditioner applications)
  long reach_redos = 0;        ///< attempts taken again looking farther for contacts (step_control.h, the reach)
  /// s, what each effect that books its own part spent, by the name it books it under (its
  /// summary.json timings key: EffectOutput::timing_names), in the order first booked.
  std::vector<std::pair<std::string, double>> effects;

  /// Books `seconds` (s) to the effect's part `name`.
  void add(const char* name, double seconds) {
    for (auto& [n, s] : effects)
      if (n == name) {
        s += seconds;
        return;
      }
    effects.emplace_back(name, seconds);
  }
  /// s, what the effect's part `name` has cost so far (0: nothing booked).
  double effect(const std::string& name) const {
    for (const auto& [n, s] : effects)
      if (n == name) return s;
    return 0;
  }
};

}  // namespace nmm::solve
