// A contact's data, by lifetime (docs/code-layout.md "The contact wing"; Box2D keeps its contact
// apart from the solver's per-step data in the same way):
//   ContactHistory   what an accepted step leaves for the next (ContactSet::history())
//   Contact          one contact of the step being solved: where, its law, its state, the last
//                    solve's forces (ContactSet::contacts(); output and diagnostics read it)
//   ContactWork      the inner solve's working values (contact_problem.h)
// ContactSet (contact_set.h) detects the contacts and carries their history from step to step;
// the step's ContactProblem (contact_problem.h) linearises them and holds the Newton kernels
// that contact_solve.cpp iterates with.
#pragma once

#include <cstdint>

#include "solver/contact/cohesive_law.h"
#include "solver/contact/contact_detection.h"
#include "solver/contact/joint_law.h"

namespace nmm::solve {

enum class ContactState : std::uint8_t { open, locked, sliding };

/// What a contact carries from one accepted step to the next: all a step needs of the past
/// (ContactSet::history(); with the rows' diagnostics, the checkpoint's CONTACT section). The
/// next step finds it again by its vertex, against the same block.
struct ContactHistory {
  std::int32_t vertex = -1;  ///< loop vertex P
  std::int32_t block = -1;   ///< block of the edge P was against
  ContactState state = ContactState::open;
  bool broken = false;       ///< cohesion and tensile strength lost (it reached its peak at an
                             ///< accepted state, or opened)
  std::int8_t slip_sign = 0; ///< direction of sliding along the edge (±1, 0 never slid)
  double shear_el = 0;       ///< m, elastic shear of the shear spring (return mapping)
  double normal_force = 0;   ///< N, compression > 0: the next step's first friction strength
  JointMemory joint;         ///< the joint law's own history (travel, dilation, largest closure)
  /// m, how deep the vertex was (−gap, ≥ 0) at the end of the last accepted step: the step after
  /// finds it against that block no deeper than this and a new contact's depth (closed_contacts())
  double depth = 0;
  /// a crack's face cut in this step (state_transfer.cpp): it starts locked, but it was never
  /// pressed in, so it licenses no depth beyond a new contact's (closed_contacts())
  bool fresh = false;
  /// A new crack's face: its cohesive softening's damage and slip (cohesive_law.h; on only
  /// where the crack's rock has a fracture energy)
  CohesiveMemory cohesive;
  /// N, the shear force at the end of the last accepted step: the next step's start force, the
  /// friction work's trapezoid (contact_effect.cpp energy_step). Not saved: a checkpoint's rows
  /// hold it (contact_history.cpp).
  double shear_force = 0;
};

/// One contact of the step being solved: rebuilt by every ContactSet::begin_step() from the
/// detection and the history, iterated by the step's ContactProblem, read by output and
/// diagnostics after the step. Its linearisation rows (unknowns, cn, cs) and the inner solve's
/// working values (ContactWork) are the ContactProblem's flat arrays, index-aligned with
/// ContactSet::contacts(); what it carries to the next step is a ContactHistory.
struct Contact {
  // Where, and the law (this step's detection).
  ContactCandidate at;  ///< vertex P, edge, elements, ω, gap at the start of the step
  /// The vertex of the other face at the same point whose contact against P's element would be
  /// this one seen from the other side (element_of(mirror) = at.elem_b), −1 if none: the same
  /// gap, shear and spring rows (contact_set.cpp begin_step), so a swap between the two is no change.
  std::int32_t mirror = -1;
  int law = 0;          ///< index into ContactSet::laws()
  double length = 0;    ///< m, tributary joint length of the contact point
  // State: from the history at the start of the step, the solution's at its end.
  ContactState state = ContactState::open;
  ContactState start_state = ContactState::open;  ///< state at the start of the step
  bool broken = false;       ///< cohesion and tensile strength lost: from the history, then set
                             ///< by break_at_peak() and settle_states() at the step's solution
  double shear_el = 0;       ///< m, elastic shear of the shear spring at the start of the step
                             ///< (at its end after end_step())
  int slip_sign = 0;         ///< direction of sliding along the edge (±1)
  JointMemory joint;         ///< the joint law's history at the start of the step (at its end
                             ///< after end_step()); the gap below is net of joint.dilation
  // The last solve (output and diagnostics).
  double normal_force = 0;   ///< N, compression > 0
  double gap = 0;            ///< m, gap after the last solve (< 0: penetration), net of the
                             ///< joint's dilation (the faces stand apart by it at gap 0)
  double shear = 0;          ///< m, trial elastic shear after the last solve (shear_el + slip)
  double shear_force = 0;    ///< N
  /// N, the shear force at the start of the step (the last accepted step's end, 0 where the
  /// contact starts it open): friction's work over the step is ½(T_start + T)·slip (energy.h)
  double start_shear_force = 0;
  double kn_now = 0;         ///< N/m, tangent normal stiffness at the last solve
  double ks_now = 0;         ///< N/m, tangent shear stiffness at the last solve (0 sliding)
  bool capped = false;       ///< closure held below Vm at the last solve
  double dilation_step = 0;  ///< m, the joint's dilation over the accepted step (end_step();
                             ///< Barton–Bandis, < 0 sliding back toward the start; energy.h)
  /// A new crack's face with cohesive softening: the damage and slip at the start of the step
  /// (at its end after end_step())
  CohesiveMemory cohesive;
  double cohesive_step = 0;  ///< J/m, what its softening dissipated in the accepted step (energy.h)
  double cohesion_slip_work = 0;  ///< J/m, the work its cohesion did in slip in the accepted step
                                  ///< (in the friction work too: energy.h takes it out there)
};

}  // namespace nmm::solve
