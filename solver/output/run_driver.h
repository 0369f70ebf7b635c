// A run of nmm-solve as a pipeline: the stepping core (TimeStepper::run_until: attempts under
// Shi's step control, step_control.h) and, after each accepted step, the observers in turn:
//
//   frames, histories, tables     OutputWriter: history.csv rows every history_every steps,
//                                 frames every output_every and at the end, and with each frame
//                                 the rows of every effect's files (Effect::write_outputs,
//                                 effect_output.h write_outputs); the
//                                 effects' whole files (write_files) at the end
//   checkpoint                    checkpoint.nmmstate every checkpoint_every steps and at the end
//   the caller's observers        energy (energy.h), progress (progress.h), run history...
//   summary                       summary.json once the run has stopped (run_summary.h)
//
// The stepping core knows nothing of files: what a run writes is the driver's and its
// observers', each reading the run's view (run_view.h), never the stepper itself. Output seconds (summary.json timings.output) are those of the frames, histories
// and checkpoints.
//
// A run has three phases: start() (frame 0), advance() as often as the caller likes (nmm-solve:
// once, to the end of solver.steps; the Python module: step(), run(), run_until()), and finish()
// (the last frame, history.csv, the checkpoint, summary.json); run() is all three. Steps are
// counted over the whole run, so frames fall every output_every steps however it was advanced.
// Without an OutputWriter nothing is written, and summary() is still the run's summary.
//
// An output that cannot be written (common/error.h WriteError: a full disk, a folder gone) ends
// the run: the step it failed after is complete and every observer still sees it, then the run
// stops with StopCode::output_failed and the file and why in its reason (nmm-solve: exit status
// 3). finish() then writes summary.json first — the one file that says what happened, so it is
// the one that gets the room there is — then the rest as before, each on its own (a file that
// cannot be written does not keep the others from being tried); the checkpoint is written whole
// or not at all (common/atomic_file.h), so a failed write leaves the last one written whole. A
// write that fails in finish() itself turns an ended run into one stopped with output_failed,
// and summary.json is written again to say so.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/outcome.h"
#include "solver/contact/contact_readout.h"
#include "solver/output/output_writer.h"
#include "solver/output/run_summary.h"
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
  /// Adds what it measured to the run's summary (summary.json), after run_summary().
  virtual void summarise(nlohmann::json& /*summary*/) const {}
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
  /// A run of `stepper` writing into `out` (null: nothing is written).
  RunDriver(TimeStepper& stepper, OutputWriter* out);
  RunDriver(TimeStepper& stepper, OutputWriter& out) : RunDriver(stepper, &out) {}
  ~RunDriver();

  /// Adds an observer, called after the frames and the checkpoint (it must outlive the run).
  void add(StepObserver& observer) { observers_.push_back(&observer); }

  /// Before the first step: frame 0 and the observers' start. Once, before advance().
  void start();
  /// Steps until simulated time t_end (s), after `max_steps` accepted steps at the most (< 0: no
  /// limit), calling the observers after each; a step that reaches t_end (or stops at
  /// solver.stop_at_ratio) is a last step (it gets a frame). Returns how the steps ended.
  Outcome advance(double t_end, std::int64_t max_steps = -1);
  /// The end of the run so far: the last frame, history.csv, the checkpoint, the observers'
  /// finish and summary.json; returns the summary. The run may advance again after it.
  nlohmann::json finish();
  /// start(), advance() by solver.steps steps of solver.time_step, finish(): nmm-solve's run.
  nlohmann::json run();

  /// The summary of the run so far (summary.json's keys).
  nlohmann::json summary() const;
  /// How the last advance() ended.
  const Outcome& outcome() const { return record_.outcome; }
  /// Accepted steps since start().
  std::int64_t steps_done() const { return record_.done; }

 private:
  class FrameOutput;
  class CheckpointOutput;
  /// The run's summary with the observers' parts (summarise).
  nlohmann::json full_summary() const;
  /// Calls f; a WriteError it throws becomes the run's stop (output_failed) unless the run has
  /// already stopped on a failure, and is kept in `first` (null: the first so far).
  void guarded(const std::function<void()>& f, std::exception_ptr& first);
  TimeStepper& stepper_;
  OutputWriter* out_;
  std::vector<StepObserver*> observers_;
  std::unique_ptr<FrameOutput> frames_;           // with an OutputWriter
  std::unique_ptr<CheckpointOutput> checkpoint_;  // with an OutputWriter
  RunRecord record_;
  bool started_ = false;
  bool output_failed_ = false;  // a write failed (guarded): the run takes no more steps
};

/// The whole run without further observers (tests, benches): RunDriver(stepper, out).run().
nlohmann::json run_to_end(TimeStepper& stepper, OutputWriter& out);

/// The rows contacts.csv gets of the current state: its closed contacts (all of them with
/// `open_too`), where they are, their state, forces, stiffnesses, lengths and joint-law state
/// (contact_readout.h).
std::vector<ContactSample> contact_samples(const RunView& run, bool open_too = false);

}  // namespace nmm::solve
