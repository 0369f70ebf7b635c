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
//   timing_names   the keys it adds to summary.json "timings" (what it booked in StepTimings)
//   warnings       what nmm-solve warns of on stderr once the run has stopped, read from the
//                  run's summary.json (the cracks' snap-back)
//   frame_parts    at every frame, grids of its own shown beside the elements (the flow network:
//                  frames/flow_<step>.vtu, a part of the same time step in frames.pvd)
//   checkpoint_sections  the checkpoint's sections of the state it carries (docs/checkpoint-format.md:
//                  the absorbing boundaries' ABSORB, the bolts' BOLTS, the flow's FLOW, the cracks'
//                  MESH and FRACTURE), written after the run state's own sections and hashed with
//                  them (summary.json state_hash: solver/stepping/run_view.h)
//   restore_sections  the same sections read back from a checkpoint (a restart)
// Its carried state is RunState's (run_state.h), or its own (the cracks': mesh_change.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/checkpoint_file.h"
#include "common/mesh.h"
#include "common/vtk_writer.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/output_tables.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

class Effect;

/// An output step of the run, as the effects write it.
struct OutputStep {
  std::int64_t step;      ///< the step number (counted over the whole run, restarts included)
  double time;            ///< s, the state's time
  const Mesh& mesh;       ///< the mesh the state is on (cracks re-cut it)
  const RunState& state;  ///< the accepted state
  OutputTables& tables;   ///< the CSV files of the output steps (output_tables.h)
  const Model& model;     ///< the run's model on `mesh` (scene, materials: model.h)
  const CoverSpace& space;  ///< the cover space on `mesh` (stresses: stress_field.h)
  /// The effects of the run's steps (effect.h), for what one effect's output reads of the others
  /// (the faces the contacts load: Effect::loaded_faces).
  const std::vector<Effect*>& effects;
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
  /// The keys it adds to summary.json "timings", the names it books its costs under in the run's
  /// StepTimings (StepTimings::add): written whether or not it took part, 0 where it spent nothing.
  virtual std::vector<std::string> timing_names() const { return {}; }
  /// The names it adds to summary.json "effects" for the run in state s (none: it takes no part).
  virtual void effect_names(const RunState& /*s*/, std::vector<std::string>& /*names*/) const {}
  /// Appends what the user is warned of once the run has stopped, from its summary.json
  /// (`summary`): a line each, without the tool's "nmm-solve: warning: ".
  virtual void warnings(const nlohmann::json& /*summary*/, std::vector<std::string>& /*lines*/) const {}
  /// Appends the checkpoint's sections of the state it carries, of a run in state s on `mesh`
  /// (none: it carries nothing, or nothing yet — a run without it keeps its checkpoint's bytes).
  virtual void checkpoint_sections(const RunState& /*s*/, const Mesh& /*mesh*/, CheckpointSections& /*sections*/) const {}
  /// Reads its sections of a checkpoint (`name` names the file in an InputError) into s, the state
  /// read from the run state's sections on `mesh`; a checkpoint without them leaves s as it is.
  virtual void restore_sections(const CheckpointSections& /*sections*/, const Mesh& /*mesh*/,
                                const std::string& /*name*/, RunState& /*s*/) const {}

 protected:
  EffectOutput() = default;
  ~EffectOutput() = default;
};

}  // namespace nmm::solve
