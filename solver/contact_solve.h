// The step with contacts as the minimisation of a convex energy, solved by Newton's method with
// an exact line search; its linear systems by a reused factorisation (CHOLMOD) as the
// preconditioner of conjugate gradients. Equations and the convergence argument: contact_solve.cpp
// and docs/contact.md "The step's contact problem".
#pragma once

#include <string>

#include <Eigen/Dense>

#include "contact.h"
#include "system_matrix.h"

namespace nmm::solve {

/// What the contact solves of a run cost (summary.json "contact_solve").
struct ContactSolveStats {
  long newton = 0;          ///< Newton iterations (one linear solve each)
  long cg_iterations = 0;   ///< preconditioned CG iterations (one factor solve pair each)
  long factorisations = 0;  ///< numeric factorisations
  long cg_aborted = 0;      ///< CG runs stopped at their budget (then a factorisation)
  long cg_skipped = 0;      ///< CG runs not tried: H − P of rank above the budget
  long strength_rounds = 0; ///< inner solves after the first of a step (friction fixed point)
  long unsettled = 0;       ///< steps taken with friction strengths still moving
  double factorisation_seconds = 0, cg_seconds = 0, line_search_seconds = 0;
};

/// Minimises Π(d) = ½dᵀAd − bᵀd + Σ contact energies over the step's increment d, with A and
/// b the system without contacts (`system` holds A in its saved values). On return d is the
/// solution; an empty string, or why it failed (the step is then cut).
std::string solve_contact_step(SystemMatrix& system, ContactSet& contacts, const Eigen::VectorXd& b,
                               Eigen::VectorXd& d, ContactSolveStats& stats);

}  // namespace nmm::solve
