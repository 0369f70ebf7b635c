// summary.json of a run (docs/output.md lists its keys): what the run did, how it ended, what
// it cost. Built from the run's view (run_view.h) after the run has stopped.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "common/outcome.h"
#include "solver/stepping/run_view.h"

namespace nmm::solve {

/// How a run went, as the run driver saw it (run_driver.h).
struct RunRecord {
  Outcome outcome;              ///< how it ended (common/outcome.h)
  std::int64_t done = 0;        ///< steps completed by this run
  std::int64_t first_step = 0;  ///< steps before this run (a restart from a checkpoint)
  double wall_seconds = 0;      ///< s, the whole run
  double output_seconds = 0;    ///< s, frames, histories and checkpoints
};

/// The summary of a run (its view once it has stopped) (every key of summary.json).
nlohmann::json run_summary(const RunView& run, const RunRecord& record);

}  // namespace nmm::solve
