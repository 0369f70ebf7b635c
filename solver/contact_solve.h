// The step with contacts as the minimisation of a convex energy, solved by Newton's method with
// an exact line search; its linear systems by a reused factorisation (CHOLMOD) as the
// preconditioner of conjugate gradients. Equations and the convergence argument: contact_solve.cpp
// and docs/contact.md "The step's contact problem".
#pragma once

#include <string>

#include <Eigen/Dense>

#include "solver/contact.h"
#include "solver/system_matrix.h"

namespace nmm::solve {

/// What the contact solves of a run cost (summary.json "contact_solve").
struct ContactSolveStats {
  long newton = 0;          ///< Newton iterations (one linear solve each)
  long cg_iterations = 0;   ///< preconditioned CG iterations (one factor solve pair each)
  long factorisations = 0;  ///< numeric factorisations
  long cg_aborted = 0;      ///< CG runs stopped at their budget (then a factorisation)
  long strength_updates = 0; ///< iterates after which friction strengths moved
  long unsettled = 0;       ///< steps whose friction strengths were frozen still moving
  /// N, the largest force tolerance F_tol an accepted step used: no unknown was out of balance by
  /// more, no contact force off its law by more (contact_solve.cpp "Tolerance")
  double max_force_tolerance = 0;
  /// m, the largest F_tol / kn over the contacts carrying more than F_tol: how far the
  /// tolerance may leave a contact from where its spring would put it
  double max_gap_error = 0;
  double factorisation_seconds = 0, cg_seconds = 0, line_search_seconds = 0;
};

/// How a step's contact solve ended.
struct ContactSolveOutcome {
  enum class Status {
    converged,              ///< within the tolerance
    not_positive_definite,  ///< a factorisation failed (an unconstrained cover)
    not_converged,          ///< the Newton iterations ran out (the step is cut)
    not_finite,             ///< a direction was not finite (the step is cut)
  };
  Status status = Status::converged;
  std::string reason;  ///< in words, for the run's status when the step cannot be cut further
  bool ok() const { return status == Status::converged; }
};

/// Minimises Π(d) = ½dᵀAd − bᵀd + Σ contact energies over the step's increment d, with A and
/// b the system without contacts (`system` holds A in its saved values), to the force tolerance
/// τ (solver.contact_tolerance: the largest out-of-balance force on an unknown, as a fraction of
/// the largest contact force). On return d is the solution.
ContactSolveOutcome solve_contact_step(SystemMatrix& system, ContactSet& contacts, const Eigen::VectorXd& b,
                                       double tau, Eigen::VectorXd& d, ContactSolveStats& stats);

}  // namespace nmm::solve
