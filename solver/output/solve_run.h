// A run of a mesh as nmm-solve makes it, as a library: the embedded scene with the run's variants
// (run_config.h), the time stepper (time_stepper.h, started from a checkpoint when asked) and,
// when an output folder is given, everything nmm-solve writes there — frames, history.csv,
// contacts.csv, checkpoint.nmmstate, summary.json (run_driver.h), energy.csv (energy.h),
// run_history.csv (run_history.h) — and, when asked, its progress line (progress.h).
//
// nmm-solve (tools/nmm_solve.cpp) and the Python module (python/: nmm.Solver, nmm.solve) both
// run through it, so a mesh with the same variants gives the same run, bit for bit (the same
// summary.json state_hash). The tool advances once, by solver.steps steps, and finishes; Python
// advances as its caller asks (a step, some steps, up to a time) and finishes when outputs are
// due. The observers after each accepted step are, in this order: frames and histories, the
// checkpoint, run_history.csv's row, the energy terms, the progress line, then the caller's.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/mesh.h"
#include "common/outcome.h"
#include "common/run_config.h"
#include "solver/output/energy.h"
#include "solver/output/output_writer.h"
#include "solver/output/progress.h"
#include "solver/output/run_driver.h"
#include "solver/output/run_history.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {

/// What a run is made from and what it writes (nmm-solve's options).
struct SolveOptions {
  std::string config_path;                 ///< --config: the merge patch's file ("" none)
  std::optional<std::string> config_text;  ///< the merge patch's text in memory instead, named
                                           ///< config_path in errors
  std::vector<std::string> sets;           ///< --set PATH=VALUE, in order
  std::string restart_path;                ///< --restart: the checkpoint to continue from ("" none)
  int threads = 0;                         ///< --threads of the factorisation (0: by size)
  std::string out_dir;                     ///< -o: the output folder ("" writes nothing)
  FrameFormat frame_format = FrameFormat::compressed;  ///< --text-frames
  int contacts_every = 1;                  ///< --contacts-every
  bool contacts_gzip = false;              ///< --contacts-gzip
  nlohmann::json inputs;                   ///< summary.json "inputs" (what nmm-report reads)
  ProgressLine::Mode progress = ProgressLine::Mode::off;  ///< the progress line on stderr
};

/// summary.json "inputs" of a run: what it was made from (`mesh_path`, "" when the mesh has no
/// file; --config, --set, --restart, as absolute paths; a merge patch in memory whole, as
/// "config_patch") and drawn with (`picture_field`, `exaggerate`, null: automatic) and written
/// as, so that nmm-report can redraw any frame.
nlohmann::json run_inputs(const std::string& mesh_path, const SolveOptions& options,
                          const std::string& picture_field, const nlohmann::json& exaggerate);

class SolveRun {
 public:
  /// Builds the run: the variants applied to the mesh's scene (InputError naming them), the
  /// stepper (from the checkpoint when options.restart_path is given), the output folder
  /// created and cleaned of an earlier run's files. `mesh_name` names the mesh in errors (the
  /// mesh file's path); `mesh` must outlive the run.
  SolveRun(const Mesh& mesh, const std::string& mesh_name, SolveOptions options);
  ~SolveRun();
  SolveRun(const SolveRun&) = delete;
  SolveRun& operator=(const SolveRun&) = delete;

  /// Asked before every step: true stops the run, interrupted (interrupt.h).
  void set_stop_check(std::function<bool()> f) { stepper_.set_stop_check(std::move(f)); }
  /// Adds an observer after the run's own (it must outlive the run).
  void add(StepObserver& observer) { driver_->add(observer); }

  /// Steps until simulated time t_end (s), `max_steps` accepted steps at the most (< 0: no
  /// limit), on the calling thread (its solver threads set first: solver_threads.h); the
  /// progress line, when asked for, runs over an advance without a step limit.
  Outcome advance(double t_end, std::int64_t max_steps = -1);
  /// s, the time `steps` steps of solver.time_step after the current state's.
  double time_after(std::int64_t steps) const;
  /// The end of the run so far: the outputs a finished run has (run_driver.h finish(),
  /// energy.csv, run_history.csv, summary.json) and the progress line's last line; returns the
  /// summary. The run may advance again after it.
  nlohmann::json finish();
  /// nmm-solve's run: advance by solver.steps steps, then finish().
  nlohmann::json run();

  /// The summary of the run so far (summary.json's keys; nothing written).
  nlohmann::json summary() const { return driver_->summary(); }
  /// How the last advance ended.
  const Outcome& outcome() const { return driver_->outcome(); }
  /// Accepted steps of this run (not counting a checkpoint's).
  std::int64_t steps_done() const { return driver_->steps_done(); }
  /// The run's state and what it was built from (run_view.h).
  RunView view() const { return stepper_.view(); }
  /// The scene the run steps: the mesh's with the variants (and the document, for the outputs).
  const RunScene& scene() const { return run_; }
  const SolveOptions& options() const { return options_; }

 private:
  class EnergyOutput;
  SolveOptions options_;
  RunScene run_;
  TimeStepper stepper_;
  std::unique_ptr<OutputWriter> out_;        // with an output folder
  std::unique_ptr<EnergyOutput> energy_;     // with an output folder
  std::unique_ptr<RunHistory> history_;      // with an output folder
  std::unique_ptr<ProgressLine> progress_;   // over an advance, when asked for
  std::unique_ptr<StepFunction> progress_line_;
  std::unique_ptr<RunDriver> driver_;
};

}  // namespace nmm::solve
