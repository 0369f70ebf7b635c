// The force each support exerts on the body (reactions.csv; docs/interface.md "Support
// reactions"), from the same penalty springs the step assembles (integrators.h support_terms,
// boundary_conditions.h edge_support), evaluated on an accepted state:
//
//   R_d = −k_s Σ_edges ∫ (u_d − h_d) ds  +  Σ_edges ∫ (σ_insitu·n)_d ds     d a held direction
//   R_d = 0                                                                 d a free direction
//   h   = velocity·F(t),  F(t) = ∫0^t f dt'  (f the support's velocity table, 1 without)
//   travel = |velocity|·F(t)  (m along the velocity; negative once a reversal has brought it back
//   past its start; 0 for a held support)
//
// with u the displacement since the start, linear along each edge between its loop vertices
// (what the next step's assembly integrates), so ∫ (u − h) ds = L·((u_a + u_b)/2 − h) exactly,
// and k_s = Model::support_stiffness() (N/m²). The second term is the in-situ stress's reaction
// that supports carry locked in from the start (support_terms), integrated along the edge by the
// same Gauss rule as the assembly. Edges of removed elements (excavated, debris) carry nothing.
// Summing the force over the covers' shape functions gives the same R at cover order 0 (the
// weights sum to 1); at order n ≥ 1 the spring's displacement inside an edge is of degree n + 1,
// and R uses its linear part between the vertices, as the next step's force does.
// Units: N per m of thickness (forces), m (travel).
#pragma once

#include <cstdint>
#include <vector>

#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// One support's reaction on the body in an accepted state.
struct SupportReaction {
  double fx = 0, fy = 0;  ///< N/m, the force the support exerts on the body (global x, y)
  double travel = 0;      ///< m, how far the held position has moved along the velocity (0: held)
  double dx = 0, dy = 0;  ///< –, the unit direction of its velocity (0, 0 for a held support)
  /// N/m, the force along the direction of travel (fx·dx + fy·dy): the load a moving support
  /// applies (a platen that pushes or pulls: positive); 0 for a held support.
  double load() const { return fx * dx + fy * dy; }
};

/// Every support's reaction (the scene's `supports`, in its order) in state s at its time s.time;
/// `removed`: [me] 1 for the elements out of the model (empty: none).
std::vector<SupportReaction> support_reactions(const Model& model, const RunState& s,
                                               const std::vector<std::uint8_t>& removed);

}  // namespace nmm::solve
