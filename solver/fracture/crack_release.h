// The strain energy a crack releases where it opens (energy.csv's fracture column, F: the
// cracks' part of the energy balance, effect_energy.h; docs/energy.md), booked by the fracture
// effect at the end of a step that cut new cracks into the mesh (fracture_effect.h energy_step):
//
//   fracture   F = Σ_steps that cracked ½ r·d = −½ Σ_new faces Σ_sides ∫ (σ0 n)·Δu ds
//                  the strain energy the cracks released (a column of its own, before residual,
//                  only where the rock can break). Derivation: cracks found in a step re-cut the
//                  mesh and the step is solved again from its start, carried onto the cut mesh
//                  with the same fields (state_transfer.h: K, U, V, S unchanged — no energy moves
//                  between columns at the cut). On the cut mesh the start state is out of balance
//                  by r: each side of a new face lost the traction σ0·n the uncut element
//                  carried across it, so its covers get r_k = −∫ w_k σ0 n ds (w_k their weights,
//                  n the side's outward normal, σ0 its element's start stress). The step solves
//                  A d = b + r (b what it would solve uncut; A = K + a0 M, a0 = 2/Δt² with
//                  inertia in the matrix, 0 in static_mode "equilibrium"). With U(d) = U0 +
//                  f_int0·d + ½ dᵀK d a linear step's W − ΔU is b·d + r·d − ½ dᵀK d; in a static
//                  step (K d = b + r) that is ½ b·d + ½ r·d: ½ b·d is what every static step
//                  leaves (its load increment taken at the step's end, O(Δt)), and
//                  ½ r·d = −½ Σ ∫ (σ0 n)·Δu ds — Irwin's crack-closure integral with the opening
//                  the faces reach: the strain energy the crack released, which the static step
//                  takes out (nothing keeps it as motion). It is exact for a linear static step
//                  (the faces' contacts closed or open throughout it); with inertia in the
//                  matrix the step's own loss is ½ dᵀK d + a0 dᵀM d (DDA's static steps, v = 0
//                  after) or ½ dᵀK d (dynamic: a0 dᵀM d stays as K), so F books the release
//                  within a0 M/K of what the step takes out — in a dynamic run the release that
//                  becomes motion (≤ ½ a0 dᵀM d) is booked at once and the scheme's damping of it
//                  later shows in R as that much less. Δu is linear along the edge and σ0
//                  constant (cover order 0: fracturing needs it): the sum is exact. Several re-cuts
//                  in one step: r is that of every face cut since the last accepted step, d the
//                  final solution. Softening crack faces (cohesive_law.h) add what their damage
//                  dissipated, Σ_steps Σ_faces L·[D(κ_end) − D(κ_start)] (D the work of the
//                  traction to κ on the envelope less the elastic energy the secant gives back:
//                  that part is in S as ½N·closure), and the work their cohesion does in slip
//                  moves from D to F; a stiff face takes the traction at the cut, so ½ r·d
//                  is then small.
#pragma once

#include <cstddef>

#include "common/mesh.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// J/m, ½ r·d of the faces the step cut: on `mesh` (the one the step ended on), the state s at
/// the step's end and `start` the step's start carried onto `mesh` (its loop_xy, loop_u, stress
/// are read); the faces on the scene's joints from `first_new_joint` on are the step's new ones.
/// Elements of excavated bodies are left out.
double crack_release(const Mesh& mesh, const RunState& s, const RunState& start, std::size_t first_new_joint);

}  // namespace nmm::solve
