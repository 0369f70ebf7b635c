// An effect that changes the mesh a run steps on (docs/code-layout.md "Effects"): at the solution
// of a step it may re-cut the mesh (mesh_bound.h MeshChanges lists those of the kind), and the
// step is then taken again from its start on the new mesh, with the state and the contact
// history of the step's start carried onto it, until the step's solution changes nothing more. The stepper (time_stepper.cpp) builds again what is derived from
// the mesh (mesh_bound.h) and keeps the map of the re-cuts for the observers (run_view.h); it
// names no such effect. What the run writes of it goes through the effects' one output interface
// (solver/discretisation/effect_output.h), its part of the energy balance through theirs
// (solver/discretisation/effect_energy.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/checkpoint_file.h"
#include "common/mesh.h"
#include "common/outcome.h"
#include "common/scene.h"
#include "preprocess/recut.h"
#include "solver/contact/contact_history.h"
#include "solver/discretisation/effect.h"
#include "solver/discretisation/effect_energy.h"
#include "solver/discretisation/effect_output.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/step_timings.h"

namespace nmm::solve {

/// A new mesh and scene for the run, with what is carried onto it.
struct NewMesh {
  std::unique_ptr<Mesh> mesh;
  std::unique_ptr<SceneDef> scene;            ///< the run's scene with what made the mesh (the joints it added)
  pre::RecutMap map;                          ///< from the new mesh back to the one it replaces
  std::vector<ContactHistory> history;        ///< the contact history, carried onto the new mesh
};

class MeshChange : public EffectOutput, public EffectEnergy {
 public:
  virtual ~MeshChange() = default;
  /// Takes part in the run (false: the scene does not call for it).
  virtual bool active() const = 0;
  /// How many of the scene's joints (its last ones) it added (MeshBound: its faces tie small covers).
  virtual std::size_t joints_added() const = 0;
  /// [me] 1: elements it took out of the model (debris), or empty.
  virtual const std::vector<std::uint8_t>& removed() const = 0;
  /// Re-cuts a step may make before the step is cut (a cascade that a shorter step spreads).
  virtual int max_per_step() const = 0;
  /// Why the step is cut after max_per_step() re-cuts, at time t (s).
  virtual Outcome cascade(double t) const = 0;
  /// At the solution `solved` of a step on mesh and scene (removed: [me] 1 out of the model):
  /// false, nothing changes; true, `out` is the new mesh and `start` (the state the step started
  /// from) and `out.history` (its contact history, given in `history`) are carried onto it.
  /// `effects`: the step's effects at that solution (what loads a crack's faces: Effect::loaded_faces).
  virtual bool change(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name, const RunState& solved,
                      const std::vector<std::uint8_t>& removed, int dofs_per_cover, RunState& start,
                      const std::vector<ContactHistory>& history, const std::vector<Effect*>& effects,
                      NewMesh& out, StepTimings& timings) = 0;
  /// What the stepper spent for it (keeping each step's start, taking the new mesh), booked in
  /// its timing.
  virtual void book(double seconds, StepTimings& timings) const = 0;
  /// A step was taken again after a change (summary.json).
  virtual void count_resolve() = 0;
  /// What of its own state the run's state hash covers (run_view.h state_hash), or nothing yet.
  virtual std::string hashed_state() const { return {}; }
  /// From a checkpoint's sections (`path` names it in errors): true, `out` is the changed mesh it
  /// was written on (its history empty: the checkpoint's follows).
  virtual bool restart(const CheckpointSections& sections, const Mesh& mesh, const SceneDef& scene,
                       const std::string& path, NewMesh& out) = 0;
};

}  // namespace nmm::solve
