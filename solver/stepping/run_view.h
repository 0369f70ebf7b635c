// What the outputs read of a run: one read-only view of a TimeStepper (time_stepper.h) — the
// state a next step starts from and what the run was built from and has cost — for the
// observers after each step (run_driver.h: frames, histories, contacts, energy, checkpoint,
// progress, summary), the studies, the tests and the benches. The stepper keeps the phases
// (attempt, step, run_until, restart); everything one reads of it is here, by const reference,
// valid while the stepper lives and current after every step.
//
// The quantities derived from the view (mean and point stresses, the effects, the state hash)
// are the functions below, each forwarding to the unit that computes it.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/mesh.h"
#include "solver/discretisation/configuration.h"
#include "solver/contact/contact_set.h"
#include "solver/contact/contact_solve.h"
#include "preprocess/recut.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/effect.h"
#include "solver/stepping/equilibrium_indicator.h"
#include "solver/stepping/mesh_change.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/step_timings.h"
#include "solver/discretisation/support_reaction.h"
#include "solver/discretisation/system_matrix.h"

namespace nmm::solve {

struct RunView {
  const Mesh& mesh;                    ///< the mesh the run steps on
  const Model& model;                  ///< derived once from mesh and scene (model.h)
  const CoverSpace& space;             ///< order, unknowns of each cover, shapes (cover_space.h)
  /// The space placed on the cover positions at the start of the last step (configuration.h).
  const Configuration& configuration;
  /// The whole state a next step starts from (run_state.h; the contact history: contacts).
  const RunState& state;
  const ContactSet& contacts;          ///< contacts, their history and events (contact.h)
  /// The system of the last step: pattern, factorisation statistics (system_matrix.h).
  const SystemMatrix& system;
  const StepTimings& timings;          ///< s and counts, per part of the run
  /// What the contact solves of the run have cost so far (summary.json "contact_solve").
  const ContactSolveStats& contact_solve;
  /// The equilibrium indicators of the last accepted step (equilibrium_indicator.h).
  const EquilibriumSample& equilibrium;
  const bool& stopped_at_ratio;        ///< the last run_until stopped at solver.stop_at_ratio
  const int& threads;                  ///< threads the factorisation uses (solver_threads.h)
  /// How many times an effect has changed the mesh (mesh_change.h; 0: the mesh as preprocessed); an observer that
  /// keeps arrays of the mesh carries them over with `recut` when it changes.
  const std::size_t& topology;
  /// From the mesh now back to the mesh of topology `recut_from`: that of the last accepted step
  /// before the last step that re-cut it, composed over every re-cut of that step (a step may
  /// re-cut several times). An observer called after every accepted step sees topology change
  /// from recut_from to topology.
  const pre::RecutMap& recut;
  const std::size_t& recut_from;
  /// The state the last step that re-cut the mesh started from, carried onto the mesh now
  /// (mesh_change.h): its fields are those of the accepted state before that step.
  const RunState& recut_start;
  /// J/m, r·d over that step: r what the cut opened of the force its start on the mesh now is out
  /// of balance by (the form and every effect at rest, no inertia: StepHost::force_at_rest), d
  /// the step's solution on that mesh (solver/fracture/crack_release.h cut_release_force).
  const double& recut_start_work;
  /// The effects with state the run's steps call (effect.h; mesh_bound.h lists them).
  const std::vector<Effect*>& effects;
  /// The effects that change the mesh (mesh_change.h; mesh_bound.h MeshChanges lists them).
  const std::vector<MeshChange*>& changes;
  /// The effects whose state the checkpoint holds, in the order of their sections (mesh_bound.h).
  const std::vector<Effect*>& checkpointed;
  /// What reports its part of the energy balance, in the meter's order (mesh_bound.h).
  const std::vector<const EffectEnergy*>& metered;
};

/// The first effect of the run (of its steps, or one that changes the mesh) of type E, or null:
/// what an observer reads of the state one effect keeps for itself.
template <class E>
const E* find_effect(const RunView& v) {
  for (const Effect* e : v.effects)
    if (const auto* x = dynamic_cast<const E*>(e)) return x;
  for (const MeshChange* c : v.changes)
    if (const auto* x = dynamic_cast<const E*>(c)) return x;
  return nullptr;
}

/// [3·me] Pa, the mean stress of each element (stress_field.h; n = 0: the stress itself).
std::vector<double> mean_stress(const RunView& v);
/// Pa, σxx σyy τxy of element e at the point (x, y) (m) of its current configuration.
std::array<double, 3> stress_at(const RunView& v, std::size_t e, double x, double y);
/// What reports its part of the run's energy balance, in the order the meter sums it: `metered`,
/// then the changes of the mesh (effect_energy.h; solver/output/energy.h).
std::vector<const EffectEnergy*> energy_sources(const RunView& v);
/// The physical effects the run computes (run_effects.h; summary.json "effects").
std::vector<std::string> run_effects(const RunView& v);
/// Every support's reaction in the run's state (support_effect.h; the scene's order).
std::vector<SupportReaction> support_reactions(const RunView& v);
/// The checkpoint's sections of the run's state: the run state's own (run_state.h) and those of
/// the effects that carry state (effect_output.h checkpoint_sections), in the file's order.
CheckpointSections state_sections(const RunView& v);
/// SHA-256 (hex) of the physical state and contact history: equal hashes, equal states. The hash
/// of state_sections (run_state.h state_hash), and for each mesh change that carries state of its
/// own (MeshChange::hashed_state) the SHA-256 of that hash's hex digits and its bytes.
std::string state_hash(const RunView& v);

}  // namespace nmm::solve
