// The step with contacts as the minimisation of a convex energy, solved by Newton's method with
// an exact line search; its linear systems by a reused factorisation (CHOLMOD) as the
// preconditioner of conjugate gradients. Equations and the convergence argument: contact_solve.cpp
// and docs/contact.md "The step's contact problem".
#pragma once

#include <string>

#include <Eigen/Dense>

#include "common/outcome.h"
#include "solver/contact/contact_problem.h"
#include "solver/discretisation/system_matrix.h"

namespace nmm::solve {

/// What the contact solves of a run cost (summary.json "contact_solve").
struct ContactSolveStats {
  long newton = 0;          ///< Newton iterations (one linear solve each)
  long cg_iterations = 0;   ///< preconditioned CG iterations (one factor solve pair each)
  long factorisations = 0;  ///< numeric factorisations
  long cg_aborted = 0;      ///< CG runs stopped at their budget (then a factorisation)
  long strength_updates = 0; ///< iterates after which friction strengths moved
  long unsettled = 0;       ///< steps whose friction strengths were frozen still moving
  long displacement_checks = 0;   ///< estimates ‖P⁻¹r‖∞ of an iterate in force balance (a solve pair each)
  long displacement_refusals = 0; ///< of them, above the displacement tolerance (the step iterated on)
  /// N, the largest force tolerance F_tol an accepted step used: no unknown was out of balance by
  /// more, no contact force off its law by more (contact_solve.cpp "Tolerance")
  double max_force_tolerance = 0;
  /// m, the largest F_tol / kn over the contacts carrying more than F_tol: how far the
  /// tolerance may leave a contact from where its spring would put it
  double max_gap_error = 0;
  /// m, the largest displacement error estimate ‖P⁻¹r‖∞ of an accepted step (at most the
  /// displacement tolerance; 0 where no factorisation was kept to estimate it with)
  double max_displacement_error = 0;
  /// Attempts solved again because contacts broke at their solution (ContactProblem::break_at_peak):
  /// steps, and the extra solves they took
  long steps_resolved_for_breaks = 0, break_resolves = 0;
  /// Attempts cut because their Newton iterations found no balance while a crack face softened
  /// (the static path snaps back there: ContactEffect::solve)
  long cohesive_unsettled = 0;
  /// Accepted steps in which a softening face's damage grew by w_c/4 or more at once: the crack
  /// released its energy faster than the steps followed (ContactEffect::commit)
  long snap_back_steps = 0;
  double factorisation_seconds = 0, cg_seconds = 0, line_search_seconds = 0;
};

/// u_tol = 3e-4·τ·w0 (m): the displacement twin of the force tolerance. An iterate in force
/// balance is accepted only if the displacement that would remove its residual, estimated with
/// the kept factorisation, is within it: a soft contact (a joint near its strength, whose tangent
/// is a fraction of its initial stiffness) turns a force error F_tol into a displacement error
/// F_tol / k_t that the force test alone does not see (contact_solve.cpp "Tolerance"). Applied
/// where a law softens (ContactSet::softening()); a constant spring's error is F_tol/k at most.
/// 3e-4, measured at τ = 1e-3 (docs/contact.md "Tolerance and error"): with 1e-3 the seed
/// study's joint sheared to 10 % of its strength slid 1.64 % short (0.5 µm of 31 µm), with
/// 3e-4 0.28 %; 1e-4 buys no more accuracy there (+0.26 %) and cost a wall of constant springs,
/// had the test applied to it, 16 instead of 13 solves per step (dynamic 20 × 20).
inline constexpr double kDisplacementTolerance = 3e-4;  ///< × τ·w0
inline double displacement_tolerance(double tau, double w0) { return kDisplacementTolerance * tau * w0; }

/// Where a step's Newton iterations begin (solve_contact_step).
enum class ContactStart {
  zero,   ///< d = 0, with the strengths the step started with
  warm,   ///< d as given, with the strengths the contacts hold (the same step solved again after
          ///< contacts broke at its solution)
  guess,  ///< d as given — the solution of the same step on the mesh before a re-cut, carried
          ///< onto the new covers (time_stepper.cpp) — with the strengths the step started with,
          ///< which follow the guess's normal forces from its first iterate on
};

/// Minimises Π(d) = ½dᵀAd − bᵀd + Σ contact energies over the step's increment d, with A and
/// b the system without contacts (`system` holds A in its saved values), to the force tolerance
/// τ (solver.contact_tolerance: the largest out-of-balance force on an unknown, as a fraction of
/// the largest contact force) and the displacement tolerance u_tol (m; 0: none,
/// displacement_tolerance()). On return d is the solution and, if asked for, *residual (N/m, in
/// unknown order) the out-of-balance force it leaves, with the friction strengths of its own
/// normal forces (block_momentum.h hands its blocks' share to the next step). The contacts'
/// states are left to the caller (ContactProblem::break_at_peak, settle_states). Returns ok, or
/// unconstrained (a factorisation failed), contact_not_converged or direction_not_finite (the
/// caller cuts the step) with the reason in words; its time is the caller's to set. `start`:
/// where the iterations begin (ContactStart).
Outcome solve_contact_step(SystemMatrix& system, ContactProblem& contacts, const Eigen::VectorXd& b,
                                       double tau, double u_tol, Eigen::VectorXd& d, ContactSolveStats& stats,
                                       Eigen::VectorXd* residual = nullptr, ContactStart start = ContactStart::zero);

}  // namespace nmm::solve
