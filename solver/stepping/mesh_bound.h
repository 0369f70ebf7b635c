// What a run derives from its mesh and scene (model, form, cover space, frames, masses) and the
// effects with state the scene calls for (solver/discretisation/effect.h), built with the
// stepper and built again when cracks re-cut the mesh. The members hold references to each other
// and to the mesh and scene, so the whole is replaced at once (time_stepper.h).
//
// The effects' list is the one place that names them: the stepper loops over `effects` in this
// order — bolts (unknowns and coupling groups right after the covers' and the elements'), contacts
// (the pairs' groups after the bolts'; the one effect that solves the step its own way), absorbing
// boundaries (their reaction taken from the force at rest, which needs the contacts detected),
// supports (their reactions at each accepted step: no term, no unknown);
// flow along the joints (its pressures solved at the step's start, a load on the joint faces).
// A new effect is a member here and an entry in the list. The effects that change the mesh
// (mesh_change.h: cracks) outlive a MeshBound: MeshChanges below.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "preprocess/recut.h"
#include "solver/contact/contact_effect.h"
#include "solver/discretisation/absorbing_effect.h"
#include "solver/discretisation/configuration.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/effect.h"
#include "solver/discretisation/form.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/support_effect.h"
#include "solver/flow/flow_effect.h"
#include "solver/reinforcement/bolt_effect.h"
#include "solver/stepping/block_momentum.h"
#include "solver/stepping/equilibrium_indicator.h"
#include "solver/stepping/fracture_effect.h"
#include "solver/stepping/mesh_change.h"

namespace nmm::solve {

struct MeshBound {
  /// `cracks`: how many of the scene's joints (its last ones) are cracks grown in the run.
  MeshBound(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name, std::size_t cracks = 0);
  MeshBound(const MeshBound&) = delete;
  MeshBound& operator=(const MeshBound&) = delete;

  Model model;                      // derived once from mesh and scene (model.h)
  Form form;                        // the integrators the scene calls for (form.h)
  CoverSpace space;                 // order, unknowns of each cover and element, shapes
  Configuration config;             // the space on the step's cover positions: frames, bases
  EquilibriumIndicator indicator;   // lumped cover masses (derived from the mesh: no run state)
  BlockMomentum momentum;           // each block's covers and mass shares (block_momentum.h)
  BoltEffect bolts;                 // rock bolts and cables (bolt_effect.h)
  ContactEffect contact;            // detection, history, the step's contact problem (contact_effect.h)
  AbsorbingEffect absorbing;        // the absorbing boundaries' carried reaction and work
  SupportEffect supports;           // the supports' reactions at each accepted step (support_effect.h)
  FlowEffect flow;                  // fluid flow along the joints (flow_effect.h)
  std::vector<Effect*> effects;     // the above, in the order the step calls them
  /// The effects that carry state of their own in the checkpoint, in the order of their sections
  /// (docs/checkpoint-format.md: ABSORB, BOLTS, FLOW — the file's order since they were added,
  /// so a checkpoint and a state hash keep their bytes); a new one goes at the end.
  std::vector<Effect*> checkpointed;
  /// What reports its part of the energy balance (effect_energy.h), in the order the meter sums
  /// it (energy.csv's bytes since each was added: the contacts' springs before the bolts'); a new
  /// one goes at the end. The water in the joints is an integrator of the form, not an effect, but
  /// its work on the faces is metered the same way.
  std::vector<const EffectEnergy*> metered;

  /// Numbers every effect's unknowns (after the covers') and coupling groups (after the
  /// elements') on state s; returns the system's unknowns.
  int number(const RunState& s);
  /// The sparse pattern's groups: each element's unknowns, then each effect's groups.
  void pattern_groups(const RunState& s, std::vector<int>& offsets, std::vector<int>& dofs) const;
  /// What describes an effect's unknown (beyond the covers') in a message: "the slip of bolt 2 at
  /// its point 5".
  std::string describe_unknown(int unknown) const;
  /// Carries on from the contacts of `before` (the mesh before a re-cut) with `history`, and
  /// carries the flow state in `s` (on `before`'s network) onto this mesh's; with `map` (the
  /// re-cut from `before`'s mesh: null at a restart, whose state is read afterwards) every
  /// effect carries its own part of s over (Effect::carry_over).
  void continue_from(MeshBound& before, std::vector<ContactHistory> history, const pre::RecutMap* map,
                     RunState& s);
  /// The contact history: with the RunState, what a step carries to the next (run_state.h).
  const std::vector<ContactHistory>& contact_history() const { return contact.set().history(); }
  /// Restores the contact history from a checkpoint's bytes (`name` names it in errors).
  void restore_contact_history(const std::string& bytes, const std::string& name);
  /// An effect solves the steps its own way, keeping a factorisation from step to step and
  /// changing the pattern as it goes (the contacts: effect.h solves()).
  bool solved_by_effect() const;
  /// [me] 1: elements out of the model (excavated, debris): no contact is detected on them.
  void set_removed(const std::vector<std::uint8_t>& removed);
};

/// The effects that change the mesh (mesh_change.h): they live as long as the run, across the
/// re-cuts that rebuild a MeshBound. A new one is a member here and an entry in the list.
struct MeshChanges {
  /// The changes of a run on `mesh` (the file's) of `scene`.
  MeshChanges(const Mesh& mesh, const SceneDef& scene) : fracture(mesh, scene), list{&fracture} {}
  MeshChanges(const MeshChanges&) = delete;
  MeshChanges& operator=(const MeshChanges&) = delete;

  FractureEffect fracture;         // intact rock that breaks (fracture_effect.h)
  std::vector<MeshChange*> list;   // the above
  /// The one that takes part in the run, or null (two that re-cut the same step would need a rule
  /// for which cuts first; there is one today).
  MeshChange* active() const;
  /// Joints the changes added to the scene so far (MeshBound's `cracks`).
  std::size_t joints_added() const;
};

}  // namespace nmm::solve
