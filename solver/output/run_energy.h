// The energy meter following a run step by step across the re-cuts its effects make: what
// nmm-solve writes to energy.csv (solve_run.cpp), nmm-study's fracture readings
// (studies/fracture_readings.cpp) and the fracturing matrix (tests/fracture_matrix.cpp) read,
// metered the same way.
//
// After every accepted step: if an effect changed the mesh in the step (RunView::topology), the
// meter's records are carried onto the new mesh by the step's re-cut map composed back to the
// mesh it last saw (RunView::recut, recut_start, recut_start_work; EnergyMeter::carry_over), so
// that a re-cut moves no energy between columns; then the effects are gathered again (a change
// of the mesh builds them again) and the step is measured (docs/energy.md).
#pragma once

#include <cstddef>

#include "solver/output/energy.h"
#include "solver/stepping/run_view.h"

namespace nmm::solve {

class RunEnergy {
 public:
  /// Starts metering `run` at its present state (the row before its first step, kept in rows()
  /// if `keep_start`). The run's model must outlive this object.
  RunEnergy(const RunView& run, bool keep_start);

  /// After an accepted step of `run`: follows a re-cut of the step, then measures; `keep` adds
  /// the row to rows(). Throws std::logic_error if the step's re-cut map does not lead back to
  /// the mesh of the last call.
  void after_step(const RunView& run, bool keep);

  /// The run stopped: the effects gathered as they are now (a run that stops in a step that
  /// re-cut the mesh has built them again since its last accepted step) and the last measured
  /// row kept.
  void finish(const RunView& run);

  const EnergyMeter& meter() const { return meter_; }
  /// The kept rows (EnergyMeter::rows).
  const std::vector<EnergyRow>& rows() const { return meter_.rows(); }
  /// The effects the meter sums, as of the last call.
  const EnergySources& sources() const { return sources_; }

 private:
  EnergyMeter meter_;
  EnergySources sources_;
  std::size_t topology_;  // the mesh the meter's records are of (RunView::topology)
};

}  // namespace nmm::solve
