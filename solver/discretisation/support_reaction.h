// The force each support exerts on the body (reactions.csv; docs/interface.md "Support
// reactions"): the force of its penalty springs as the step's assembly builds them (integrators.h
// support_terms, boundary_conditions.h edge_support), at the solution of the accepted step:
//
//   R_d = −k_s Σ_edges ∫ (u_d(s) − h_d) ds  +  Σ_edges ∫ (σ_insitu·n)_d ds   d a held direction
//   R_d = 0                                                                  d a free direction
//   u(s) = the step's start displacement, linear along the edge between its vertices, plus the
//          step's increment Σ_k φ_k(s)·d_k (the element's shape functions on the step's frame)
//   h   = velocity·F(t_end),  F(t) = ∫0^t f dt'  (f the support's velocity table, 1 without)
//   travel = |velocity|·F(t)  (m along the velocity; it comes back under a reversal; 0 when held)
//
// on the edges in the step's start position, with the assembly's Gauss rule (n + 2 points at
// cover order n: exact), k_s = Model::support_stiffness() (N/m²); the second term is the in-situ
// stress's reaction a support carries locked in from the start (support_terms). This is the sum
// of the springs' rows over a rigid translation (the constant cover functions sum to 1), so the
// reactions balance every other force of the step's solve. Edges of removed elements (excavated,
// debris) carry nothing. Units: N per m of thickness (forces), m (travel).
//
// Of a state alone (a run's first state, a restart's before its first step) the increment is not
// known: R takes the state's displacement linear along each edge — the same at cover order 0, and
// at order n ≥ 1 short of the increment's part of degree n + 1 inside the edges.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/step_context.h"

namespace nmm::solve {

/// One support's reaction on the body.
struct SupportReaction {
  double fx = 0, fy = 0;  ///< N/m, the force the support exerts on the body (global x, y)
  double travel = 0;      ///< m, how far the held position has moved along the velocity (0: held)
  double dx = 0, dy = 0;  ///< –, the unit direction of its velocity (0, 0 for a held support)
  /// N/m, the force along the direction of travel (fx·dx + fy·dy): the load a moving support
  /// applies (a platen that pushes or pulls along its motion: positive); 0 for a held support.
  double load() const { return fx * dx + fy * dy; }
};

/// Every support's reaction (the scene's `supports`, in its order) at the solution d (every
/// unknown's increment) of the step in `step`.
std::vector<SupportReaction> support_reactions(const Model& model, const StepContext& step, const Eigen::VectorXd& d);

/// Every support's reaction in state s alone, at its time s.time; `removed`: [me] 1 for the
/// elements out of the model (empty: none).
std::vector<SupportReaction> support_reactions(const Model& model, const RunState& s,
                                               const std::vector<std::uint8_t>& removed);

}  // namespace nmm::solve
