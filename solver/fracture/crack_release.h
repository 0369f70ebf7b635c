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
//   fluid on the new faces (hydraulic fracture, flow.md): the step's solve also carries the
//                  fluid's force on the new faces, P = −Σ_faces ∫ w_k p n ds with p the flow
//                  network's pressure at the step's end (it fills them in the step), which was not
//                  in the start's balance: A d = b + r + P. load_work counts P·d in full (the
//                  fluid's pressure at the step's end on every face, flow_effect.cpp), so a static
//                  step's W − ΔU is ½ b·d + ½ (r + P)·d: the face traction goes from σ0·n to −p·n
//                  within the step, and the crack-closure integral of that change,
//                    ½ (r + P)·d = −½ Σ_new faces Σ_sides ∫ (σ0 n + p n)·Δu ds,
//                  is what the crack released. The part −½ ∫ p n·Δu ds is half the fluid's work
//                  p·ΔV on the new faces, the half the opening does not store (a dynamic step would
//                  show it as motion, then damped): F books it (crack_release_fluid, which the
//                  flow effect adds, as only it knows p), R keeps only ½ b·d. With p linear along
//                  the edge (p_A at its start, p_B at its end) and Δu linear too,
//                    ∫ p Δu ds = L/6 · [(2 p_A + p_B) Δu_A + (p_A + 2 p_B) Δu_B]   (exact).
#pragma once

#include <cstddef>
#include <vector>

#include "common/mesh.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// J/m, ½ r·d of the faces the step cut: on `mesh` (the one the step ended on), the state s at
/// the step's end and `start` the step's start carried onto `mesh` (its loop_xy, loop_u, stress
/// are read); the faces on the scene's joints from `first_new_joint` on are the step's new ones.
/// Elements of excavated bodies are left out.
double crack_release(const Mesh& mesh, const RunState& s, const RunState& start, std::size_t first_new_joint);

/// J/m, ½ P·d = −½ Σ_new faces ∫ p n·Δu ds: the fluid's part of the release on the faces the step
/// cut (same arguments as crack_release), `pressure` ([2·v] Pa, the step's end) the fluid's
/// pressure at the start and the end of each face edge v → next (FlowNetwork::face_pressures),
/// 0 on dry edges.
double crack_release_fluid(const Mesh& mesh, const RunState& s, const RunState& start, std::size_t first_new_joint,
                           const std::vector<double>& pressure);

}  // namespace nmm::solve
