// The energy meter following a run across its re-cuts (run_energy.h).
#include "solver/output/run_energy.h"

#include <stdexcept>
#include <string>

namespace nmm::solve {

RunEnergy::RunEnergy(const RunView& run, bool keep_start)
    : meter_(run.model, &run.space), sources_(energy_sources(run)), topology_(run.topology) {
  meter_.after_step(run.state, sources_, keep_start);
}

void RunEnergy::after_step(const RunView& run, bool keep) {
  if (run.topology != topology_) {  // an effect changed the mesh in this step (mesh_change.h)
    // The step's re-cuts, composed back to the mesh the meter last saw (run_view.h).
    if (run.recut_from != topology_)
      throw std::logic_error("energy meter: the re-cut map leads back to mesh " + std::to_string(run.recut_from) +
                             ", the meter's is " + std::to_string(topology_));
    meter_.carry_over(run.model, &run.space, run.recut, run.recut_start, run.recut_start_work);
    topology_ = run.topology;
  }
  sources_ = energy_sources(run);  // a change of the mesh builds the effects again
  meter_.after_step(run.state, sources_, keep);
}

void RunEnergy::finish(const RunView& run) {
  sources_ = energy_sources(run);
  meter_.keep_last();
}

}  // namespace nmm::solve
