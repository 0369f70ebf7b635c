// A run of nmm-solve as a pipeline: the stepping core (TimeStepper::run_until: attempts under
// Shi's step control, step_control.h) and, after each accepted step, the observers in turn:
//
//   frames, histories, contacts   OutputWriter: history.csv rows every history_every steps,
//                                 frames and contacts.csv every output_every and at the end
//   checkpoint                    checkpoint.nmmstate every checkpoint_every steps and at the end
//   the caller's observers        energy (energy.h), progress (progress.h), run history...
//   summary                       summary.json once the run has stopped (run_summary.h)
//
// The stepping core knows nothing of files: what a run writes is the driver's and its
// observers', each reading the run's view (run_view.h), never the stepper itself. Output seconds (summary.json timings.output) are those of the frames, histories
// and checkpoints.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/outcome.h"
#include "solver/output/output_writer.h"
#include "solver/stepping/run_view.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {

/// Something a run does after each accepted step.
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  /// Before the first step, with the state the run starts from.
  virtual void start(const RunView&) {}
  /// After accepted step n of this run (1, 2, ...); `last`: the run's last step (its steps are
  /// done or solver.stop_at_ratio is met).
  virtual void after_step(const RunView& run, std::int64_t n, bool last) = 0;
  /// Once the run has stopped after `done` steps, with how it ended.
  virtual void finish(const RunView&, const Outcome& /*outcome*/, std::int64_t /*done*/) {}
};

/// An observer of one function (after_step only).
class StepFunction : public StepObserver {
 public:
  using Function = std::function<void(const RunView&, std::int64_t n, bool last)>;
  explicit StepFunction(Function f) : f_(std::move(f)) {}
  void after_step(const RunView& run, std::int64_t n, bool last) override { f_(run, n, last); }

 private:
  Function f_;
};

class RunDriver {
 public:
  /// A run of `stepper` (solver.steps steps on from its current time) writing into `out`.
  RunDriver(TimeStepper& stepper, OutputWriter& out);

  /// Adds an observer, called after the frames and the checkpoint (it must outlive run()).
  void add(StepObserver& observer) { observers_.push_back(&observer); }

  /// Runs all steps, calling the observers; writes and returns the summary.
  nlohmann::json run();
  /// How the last run() ended.
  const Outcome& outcome() const { return outcome_; }

 private:
  TimeStepper& stepper_;
  OutputWriter& out_;
  std::vector<StepObserver*> observers_;
  Outcome outcome_;
};

/// The whole run without further observers (tests, benches): RunDriver(stepper, out).run().
nlohmann::json run_to_end(TimeStepper& stepper, OutputWriter& out);

}  // namespace nmm::solve
