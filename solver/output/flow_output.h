// flow.csv (docs/interface.md "Fluid flow in joints and cracks"; docs/flow.md): per output step
// (frame 0, every solver.output_every steps and the last), one row per node of the flow network
// (solver/flow/flow_network.h): step,time,node,x,y,pressure,aperture — x, y where the node is in
// the mesh as cut (m), the pressure (Pa) and the mean hydraulic aperture of the segment ends there
// (m), as the accepted state holds them. Written when the run finishes; nothing without flow.
#pragma once

#include <cstdint>
#include <string>

#include "solver/output/run_driver.h"

namespace nmm::solve {

class FlowOutput : public StepObserver {
 public:
  FlowOutput(std::string dir, std::int64_t output_every) : dir_(std::move(dir)), output_every_(output_every) {}
  void start(const RunView& run) override { add_rows(run); }
  void after_step(const RunView& run, std::int64_t n, bool last) override {
    if (last || n % output_every_ == 0) add_rows(run);
  }
  void finish(const RunView& run, const Outcome& outcome, std::int64_t done) override;

 private:
  void add_rows(const RunView& run);
  std::string dir_;
  std::int64_t output_every_;
  std::int64_t last_step_ = -1;  // the step of the last rows (a last step is also an output step)
  std::string rows_;
};

}  // namespace nmm::solve
