// What a run's steps have cost, part by part (summary.json "timings", bench/ CSVs): wall seconds
// from common/stopwatch.h, and the counts behind them.
#pragma once

namespace nmm::solve {

/// Seconds spent per part of the run.
struct StepTimings {
  double contact_detection = 0;
  double assembly = 0;
  double factorisation = 0;
  double solves = 0;
  double geometry_update = 0;  ///< stresses, loop vertices, covers and points moved after a solve
  double output = 0;
  double fracture = 0;         ///< keeping each step's start, strength checks, crack paths, re-cutting and carrying the state over
  long factorisations = 0;     ///< numeric factorisations of the system matrix
  long solves_count = 0;       ///< triangular solve pairs (direct solves and preconditioner applications)
};

}  // namespace nmm::solve
