// The state moved on by a step's solved increment d (the cover unknowns, cover_space.h), in the
// configuration the step was assembled in (configuration.h):
//
//   stress          σ_e += D·B·d_e   (n = 0: the element's constant stress; n ≥ 1: the strain
//                   polynomials of degree n, ε = B·d_e, then D per coefficient)
//   geometry        every loop vertex, tracked point (fixed, load, measure) and cover node moves
//                   by the displacement field u(x) = Σ_a φ_a(x)·d_a of its element: large
//                   displacement over many small steps
//   covers          u_c += d_c (a tied cover takes its master's increment, and so keeps its
//                   master's velocity); dynamic runs: v, a by Newmark (newmark.h)
//
// The stress is not rotated with the element: rotations per step are small (Shi's DDA does the
// same).
#pragma once

#include <Eigen/Dense>

#include "solver/discretisation/configuration.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/step_context.h"

namespace nmm::solve {

/// Moves s (the state `step` started from) on by the increment d solved in the step's frames.
void update_state(const Model& model, const StepContext& step, const Eigen::VectorXd& d, RunState& s);

/// m, the farthest any loop vertex of s would move by the increment d (what update_state moves it
/// by, |u(x)| at the vertex), without moving anything: the stepper's reach check.
double largest_loop_move(const Model& model, const StepContext& step, const Eigen::VectorXd& d,
                         const RunState& s);

}  // namespace nmm::solve
