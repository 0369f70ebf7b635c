// An effect with state of its own in the step (docs/code-layout.md "Effects"): contacts, bolts,
// absorbing boundaries, the supports' reactions — each behind this one interface, so the stepper
// (solver/stepping/time_stepper.cpp) loops over the effects a scene calls for
// (solver/stepping/mesh_bound.h builds the list) and names none.
//
// Effects without state of their own (elasticity, gravity, loads, supports, tractions, water
// pressure, in-situ traction) are integrators of the step's form instead (form.h,
// integrators.h): they only add terms to K and F. An Effect is what does more than that in a
// step — keeps unknowns of its own, solves the system its own way, judges the solution (a bolt
// that yields: solve again), rejects a step (a contact that penetrated: cut it), commits on the
// accepted state — as Box2D v3's solver stages share one step context (b2StepContext): here
// EffectStep.
//
// A step calls the effects in the list's order at each stage:
//   number        unknowns of its own after the covers' (and earlier effects'), its coupling
//                 groups after the elements' (and earlier effects')
//   begin_step    linearise at the step's start, detect; may change the pattern
//   assemble      its terms into K and F (every solve round)
//   solve         at most one effect solves the system its own way (the contacts' problem)
//   judge         at the solution: true → the step is solved again from there
//   penetration   what the solved step added to its contacts' depths: step control rejects it
//                 (cuts Δt) beyond its limits (step_control.h)
//   commit        the accepted step into the state (history is committed here, never on an iterate)
// and what the run writes of it (effect_output.h): its rows of the output steps' CSV files, the
// files it writes at the end, its part of summary.json; and its part of the energy balance
// (effect_energy.h: what it stores, works and dissipates, summed by the energy meter).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json_fwd.hpp>

#include "common/mesh.h"
#include "common/outcome.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/effect_energy.h"
#include "solver/discretisation/effect_output.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/step_context.h"
#include "solver/discretisation/system_matrix.h"
#include "solver/discretisation/step_timings.h"

namespace nmm::solve {

/// What the stepper offers the effects beyond a step's context.
class StepHost {
 public:
  /// N/m per unknown: the out-of-balance force of the state the step starts from with d = 0 and no
  /// inertia — the form at the state's own time and every effect's terms at rest (add_at_rest).
  /// Overwrites the step's system and right-hand side (it is taken before the step's assembly).
  virtual const Eigen::VectorXd& force_at_rest() = 0;

 protected:
  ~StepHost() = default;
};

/// How deep step control lets a step make a contact it deepens (solver/stepping/step_control.h):
/// no deeper than `cap`, or than `sink` below where the contact started, whichever is deeper.
struct PenetrationAllowance {
  double cap = 0;   ///< m, 2·g2·w0
  double sink = 0;  ///< m, what a contact that starts at or past the cap may sink in one step
  /// m, how deep a contact that starts the step `start` deep (m) may end it.
  double deepest(double start) const { return start + sink > cap ? start + sink : cap; }
};

/// What a solved step attempt did to the depths of its contacts, as step control judges it
/// (solver/stepping/step_control.h rejection).
struct StepPenetration {
  /// m, the most the step deepened one contact past its depth at the step's start (past touching,
  /// for a contact that started open or is new); < 0: no effect judges the step's penetration.
  double added = -1;
  /// m, the deepest of the contacts the step made deeper (0: none).
  double deepest = 0;
  /// m, of the contacts the step made deeper, the one furthest past its allowance
  /// (PenetrationAllowance::deepest): its depth at the step's start and at its end (0, 0: none).
  double worst_start = 0, worst_end = 0;
};

/// One stage of one step attempt, as the effects see it.
struct EffectStep {
  const StepContext& context;  ///< Δt, the step's end, frames, the state it starts from (read)
  RunState& s;                 ///< the state the step starts from: an effect writes its own fields
  SystemMatrix& system;        ///< the step's system (pattern, matrix, factorisation)
  Eigen::VectorXd& rhs;        ///< N/m per unknown, the step's right-hand side
  double search_distance;      ///< m, how far apart two faces may be and still touch within the step (step_control.h)
  PenetrationAllowance allowance;  ///< how deep the step may make a contact it deepens (step_control.h)
  StepTimings& timings;        ///< s, what the step's parts cost
  StepHost& host;
  bool pattern_changed = false;  ///< set by begin_step: the coupling groups changed, the stepper builds the pattern again
  /// m, how far apart two faces are looked for in this attempt (the stepper's reach, at most
  /// search_distance: time_stepper.cpp); 0: search_distance
  double reach = 0;
  /// m, set by begin_step of an effect that looked only `reach` far (0: none did): the stepper
  /// redoes the attempt looking farther if a loop vertex moves more than half of it
  double checked_reach = 0;
};

/// Where the pieces of a mesh that cracks re-cut came from (preprocess/recut.h RecutMap: the
/// solver's discretisation does not see the preprocessor), for Effect::carry_over.
struct MeshPieces {
  const Mesh& old;                                  ///< the mesh before the re-cut
  const CoverSpace& old_space;                      ///< its cover space (unknowns, ties)
  const std::vector<std::int32_t>& element_parent;  ///< [new me] the old element it is (a piece of)
  const std::vector<std::int32_t>& cover_parent;    ///< [new pc] the old cover it is (a piece of)
  /// [new loop vertex] the old loop vertex at the same point, or -1 (a vertex the cut made)
  const std::vector<std::int32_t>& vertex_parent;
};

/// What a solve of the step gives back (Effect::solve).
struct StepSolution {
  Eigen::VectorXd d;         ///< the increment of every unknown
  Eigen::VectorXd residual;  ///< N/m, the out-of-balance force handed on (block_momentum.h)
  bool iterated = false;     ///< the solve took an iterative (Newton) direction
  /// d holds a start guess for the first solve of the attempt (the same step's solution on the
  /// mesh before a re-cut, carried onto the new covers: time_stepper.cpp attempt); an effect that
  /// solves iteratively may start from it, a direct solve ignores it.
  bool guess = false;
};

class Effect : public EffectOutput, public EffectEnergy {
 public:
  virtual ~Effect() = default;
  Effect() = default;
  Effect(const Effect&) = delete;
  Effect& operator=(const Effect&) = delete;

  /// Takes part in the steps of this run (false: the scene does not call for it).
  virtual bool active() const = 0;

  // ---- unknowns and coupling groups ----------------------------------------------------------
  /// State installed or carried on: called when the run starts and after a restart, with the
  /// state read from the checkpoint (`name` names it in an InputError). False: what it carried no
  /// longer fits the checkpoint's factorisation (a bolt installed now adds unknowns).
  virtual bool install(RunState& /*s*/, const std::string& /*name*/) { return true; }
  /// Numbers its unknowns from first_unknown and its coupling groups from first_group.
  virtual void number(const RunState& /*s*/, int /*first_unknown*/, std::size_t /*first_group*/) {}
  virtual int unknowns() const { return 0; }
  /// How many coupling groups it adds to the pattern (after number()).
  virtual std::size_t groups(const RunState& /*s*/) const { return 0; }
  /// Appends its coupling groups' unknowns to a pattern's offsets and dofs (system_matrix.h).
  virtual void add_groups(const RunState& /*s*/, std::vector<int>& /*offsets*/, std::vector<int>& /*dofs*/) const {}
  /// After cracks re-cut the mesh (solver/stepping/mesh_change.h), on this effect's new mesh:
  /// carries what it keeps in s, given on `from.old`, onto this mesh (the step's start is taken
  /// again on it). The cover fields, the stress and the tracked points of RunState are carried
  /// by the re-cut itself (solver/fracture/state_transfer.h); what an effect keeps of its own
  /// that names elements, covers or unknowns of the mesh (a bolt's ties, the absorbing
  /// boundaries' carried reaction) is the effect's to carry.
  virtual void carry_over(const MeshPieces& /*from*/, RunState& /*s*/) const {}
  /// "the slip of bolt 2 at its point 5" for an unknown of its own, "" for another.
  virtual std::string describe_unknown(int /*unknown*/) const { return {}; }

  // ---- a step -------------------------------------------------------------------------------
  /// At the start of an attempt, before assembly; a stop ends the attempt.
  virtual Outcome begin_step(EffectStep& /*step*/) { return {}; }
  /// Its terms of the state at rest (StepHost::force_at_rest): d = 0, no inertia.
  virtual void add_at_rest(EffectStep& /*rest*/) {}
  /// Its terms into step.system and step.rhs, in every solve round.
  virtual void assemble(EffectStep& /*step*/) {}
  /// True: it solves the step's system its own way (solve), keeping a factorisation from step
  /// to step (a checkpoint's FACTOR section) and changing the pattern as it goes; at most one
  /// effect of a run does.
  virtual bool solves() const { return false; }
  /// Solves the assembled system; `again`: a further round of the same step (from x.d).
  virtual Outcome solve(EffectStep& /*step*/, bool /*again*/, StepSolution& /*x*/) { return {}; }
  /// At a solution d of the step: true → what it assembles changed, solve the step again.
  virtual bool judge(const Eigen::VectorXd& /*d*/) { return false; }
  /// Solves of one step its judging may ask for; past them the step stops with not_settled().
  virtual int max_solves() const { return 1; }
  /// Why the step stops when judge() still asks for another solve after max_solves() solves, at
  /// time t (s).
  virtual Outcome not_settled(double /*t*/) const { return {}; }
  /// What the solved step did to the depths of its contacts (the contacts'), or added < 0: this
  /// effect does not judge the step. Step control (step_control.h rejection) runs when an effect
  /// judges; it also bounds the covers' largest move.
  virtual StepPenetration penetration(EffectStep& /*step*/) const { return {}; }
  /// The solved step was rejected: covers_d its covers' increment (for a trace).
  virtual void rejected(const EffectStep& /*step*/, const Eigen::VectorXd& /*covers_d*/) const {}
  /// The accepted step into the state step.s (before the covers move: state_update.h).
  virtual void commit(EffectStep& /*step*/, const Eigen::VectorXd& /*d*/) {}

  // ---- what others read of it ---------------------------------------------------------------
  /// Marks (1) in `loaded` ([loop vertex]: the face from that vertex to the next) the faces its
  /// accepted state s puts a traction on — the contacts' closed faces; a crack tip's interaction
  /// integral counts what loads its faces (solver/fracture/crack_tip_readout.h).
  virtual void loaded_faces(const RunState& /*s*/, std::vector<std::uint8_t>& /*loaded*/) const {}
  /// Adds to `pressure` ([2·v] Pa, v the mesh's loop vertices: the start and the end of the face
  /// v → next) the fluid pressure its accepted state s puts on the crack and joint faces — the
  /// flow network's (docs/flow.md "Hydraulic fracturing"); the tips' integral takes it as t = −p·n.
  virtual void face_pressures(const RunState& /*s*/, std::vector<double>& /*pressure*/) const {}
};

}  // namespace nmm::solve
