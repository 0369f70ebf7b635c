// What the run writes of an effect (docs/code-layout.md "Effects"): its rows of the CSV files at
// each output step, the files it writes whole once the run has stopped, and its part of
// summary.json — one small interface that the effects of a step (effect.h: bolts, contacts,
// absorbing boundaries) and the effects that change the mesh (solver/stepping/mesh_change.h:
// cracks) both implement, so the driver (solver/output/run_driver.h) calls every effect at every
// output step and names none. Adding an effect's output touches no file outside the effect.
//
//   output_files   the file names it may write (whether or not the scene calls for it): a run
//                  removes them from its folder at its start, so an earlier run's never mix in
//   write_outputs  at every output step (frames: every solver.output_every steps, and the last
//                  state), its rows of out.tables on the accepted state (output_tables.h)
//   write_files    once the run has stopped (nmm-solve: at its end; Python: at finish()), the
//                  files it writes whole into the folder (cracks.csv)
//   summarise      its part of summary.json
//   effect_names   what it adds to summary.json "effects" when it takes part (docs/interface.md)
//   frame_parts    at every frame, grids of its own shown beside the elements (the flow network:
//                  frames/flow_<step>.vtu, a part of the same time step in frames.pvd)
//   checkpoint_sections  the checkpoint's sections of what it keeps beyond the run state (the
//                  cracks' MESH and FRACTURE; docs/checkpoint-format.md); what it keeps in
//                  RunState is written with the state (run_state.h)
// Its carried state is RunState's, and so the checkpoint's (run_state.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/checkpoint_file.h"
#include "common/mesh.h"
#include "common/vtk_writer.h"
#include "solver/discretisation/output_tables.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// An output step of the run, as the effects write it.
struct OutputStep {
  std::int64_t step;      ///< the step number (counted over the whole run, restarts included)
  double time;            ///< s, the state's time
  const Mesh& mesh;       ///< the mesh the state is on (cracks re-cut it)
  const RunState& state;  ///< the accepted state
  OutputTables& tables;   ///< the CSV files of the output steps (output_tables.h)
};

/// A grid an effect adds to a frame: written as frames/<name>_<step>.vtu and listed in
/// frames.pvd as a part of the frame's time step (ParaView shows the parts as blocks).
struct FramePart {
  std::string name;  ///< lower-case letters: the file's prefix ("flow")
  PolygonGrid grid;
};

class EffectOutput {
 public:
  /// The files (names in the output folder) write_outputs and write_files may write.
  virtual std::vector<std::string> output_files() const { return {}; }
  /// Its rows of out.tables at an output step.
  virtual void write_outputs(OutputStep& /*out*/) const {}
  /// The files it writes whole into folder `dir` once the run has stopped (WriteError when it
  /// cannot).
  virtual void write_files(const OutputStep& /*out*/, const std::string& /*dir*/) const {}
  /// The grids it adds to the frame of an output step (none: the frame is the elements alone).
  virtual void frame_parts(const OutputStep& /*out*/, std::vector<FramePart>& /*parts*/) const {}
  /// Its part of summary.json for the run in state s (the bolts' "bolts"), added to `summary`.
  virtual void summarise(const RunState& /*s*/, nlohmann::json& /*summary*/) const {}
  /// The names it adds to summary.json "effects" for the run in state s (none: it takes no part).
  virtual void effect_names(const RunState& /*s*/, std::vector<std::string>& /*names*/) const {}
  /// Appends the checkpoint's sections of what it keeps beyond the run state, of a run on `mesh`.
  virtual void checkpoint_sections(const Mesh& /*mesh*/, CheckpointSections& /*sections*/) const {}

 protected:
  EffectOutput() = default;
  ~EffectOutput() = default;
};

}  // namespace nmm::solve
