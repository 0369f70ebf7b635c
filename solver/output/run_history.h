// run_history.csv: the solver's effort and the equilibrium indicators of every accepted step
// (open–close iterations, time-step cuts, closed contacts, unbalanced force ratios, largest
// velocity), drawn by the run's report (report/run_report.h, run_history.svg).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/output/run_driver.h"

namespace nmm::solve {

/// One accepted step's solver effort (run_history.csv).
struct StepRecord {
  std::int64_t step;     ///< accepted step number, from 1
  double time;           ///< s, simulated time after the step
  double dt;             ///< s, the step's length
  std::int64_t iterations;  ///< open–close iterations (solves) the step took, cut attempts included
  std::int64_t cuts;     ///< time-step cuts before the step was accepted
  std::int64_t closed_contacts;  ///< contacts closed after the step
  double max_unbalanced_ratio = 0;   ///< –, equilibrium_indicator.h
  double mean_unbalanced_ratio = 0;  ///< –
  double max_velocity = 0;           ///< m/s, largest cover velocity
};

/// Writes OUTDIR/run_history.csv ("step,time,dt,iterations,cuts,closed_contacts,
/// max_unbalanced_ratio,mean_unbalanced_ratio,max_velocity").
void write_run_history(const std::string& dir, const std::vector<StepRecord>& rows);

/// The observer that records a StepRecord after every accepted step (run_driver.h) and writes
/// them at the run's finish. Step numbers count as history.csv does (after a restart, on from
/// the checkpoint's); the per-step counts come from the running totals a restart brings.
class RunHistory : public StepObserver {
 public:
  explicit RunHistory(std::string dir) : dir_(std::move(dir)) {}
  void start(const RunView& run) override;
  void after_step(const RunView& run, std::int64_t n, bool last) override;
  void finish(const RunView& run, const Outcome& outcome, std::int64_t done) override;
  const std::vector<StepRecord>& rows() const { return rows_; }

 private:
  std::string dir_;
  std::vector<StepRecord> rows_;
  std::uint64_t iterations_ = 0, cuts_ = 0;  // running totals after the last step
  double t_prev_ = 0;                        // s, time after the last step
};

}  // namespace nmm::solve
