// The strain energy a crack releases where it opens (energy.csv's fracture column, F: the
// cracks' part of the energy balance, effect_energy.h; docs/energy.md), booked by the fracture
// effect at the end of a step that cut new cracks into the mesh (fracture_effect.h energy_step)
// and, for the fluid that fills them, by the flow effect (flow_effect.h):
//
//   fracture   F = Σ_steps that cracked ½ (r + ΔP)·d
//                  Derivation: cracks found in a step re-cut the mesh and the step is solved
//                  again from its start, carried onto the cut mesh with the same fields
//                  (state_transfer.h: K, U, V, S unchanged — no energy moves between columns at
//                  the cut). On the cut mesh that start is out of balance by B (N/m per unknown):
//                  the form and every effect at rest, without inertia (StepHost::force_at_rest),
//                  and for the contacts the end forces c_end of the closed contacts the last
//                  accepted step ended with, carried onto the cut mesh each on the piece it acts
//                  on (ContactEffect::add_ended_forces: their start forces are not evaluated,
//                  which would move their solve's starting point; a new face's contact has none).
//                  Measured by the stepper on the start of the step's last attempt:
//                  RunView::recut_start_work = r·d, EnergyStep::cut_work). B = r + h: r what
//                  the cut opened, h what the start was out of balance by before it — the
//                  inertia of DDA's static steps (M·v1_prev/Δt_prev, which the damped column
//                  books), a dynamic step's M·a0, the contact solve's tolerance, the loads of a
//                  run's first step (gravity put on a stress-free slope) — shared among the
//                  pieces of a cover the cut split by their mass moments (below). (Without the
//                  contacts' end forces in B, h held them too, and a split cover's pieces shared
//                  the force of a contact on one of them by mass.) The step
//                  solves A d = b + B (b what it would solve uncut: the loads' increments; A =
//                  K + a0 M, a0 = 2/Δt² with inertia in the matrix, 0 in static_mode
//                  "equilibrium"). With U(d) = U0 + f_int0·d + ½ dᵀK d a linear step's W − ΔU is
//                  (b + B)·d − ½ dᵀK d; in a static step (K d = b + B) that is ½ b·d + ½ B·d:
//                  ½ b·d is what every static step leaves (its load increment taken at the
//                  step's end, O(Δt): in R), ½ h·d the inertia's (in Q), and ½ r·d the strain
//                  energy the crack released, which the static step takes out (nothing keeps it
//                  as motion) — Irwin's crack-closure integral with the opening the faces reach,
//                  in the discrete model. Why B and not the traction σ0·n each side of a new face
//                  lost: the start was in balance cover by cover, not element by element, so a
//                  cover the crack splits in two has pieces out of balance by their faces'
//                  −∫ w σ0·n ds plus their share of the stress jumps between its elements and of
//                  the loads on them, which summed to nothing before the cut (measured on
//                  data/wellbore_hydrofrac.json's breakdown step: r·d = −49.5 J/m, the faces'
//                  traction alone −168.9). ½ r·d is exact for a linear static step (the faces'
//                  contacts closed or open throughout it); with inertia in the matrix the step's
//                  own loss is ½ dᵀK d + a0 dᵀM d (DDA's static steps, v = 0 after) or ½ dᵀK d
//                  (dynamic: a0 dᵀM d stays as K), so F books the release within a0 M/K of what
//                  the step takes out. Several re-cuts in one step: B is that of the start on the
//                  last mesh (every face cut since the last accepted step), d the final solution.
//                  A new face's contact that slides within the step starts at zero force (gap 0,
//                  no shear: state_transfer.h), so the step took its shear force from 0 to T
//                  along the slip: the friction column books |T|·slip, the step spent ½|T|·slip
//                  of the release on it, and the contact effect gives ½|T|·slip back from F
//                  (contact_effect.cpp energy_step): what the crack's faces took beyond their
//                  springs. (A face that opens or stays closed is linear: nothing to give back.)
//                  Softening crack faces (cohesive_law.h) add what their damage dissipated,
//                  Σ_steps Σ_faces L·[D(κ_end) − D(κ_start)] (D the work of the traction to κ on
//                  the envelope less the elastic energy the secant gives back: that part is in S
//                  as ½N·closure), and the work their cohesion does in slip moves from D to F.
//   h's share    h is a body force per unit mass f(x) (N/kg: gravity, −acceleration, ...) on
//                  the parent cover P: h_P,js = ∫_P ρ w p_j f_s dA, p_j its cover function's terms
//                  (cover_space.h: p_j((x − c)/h) about its node c). Where f is a polynomial of
//                  degree ≤ n over P, f_s = Σ_l p_l g_ls, so each piece i of P gets
//                    h_i = M_i g,   g = M_P⁻¹ h_P,   M_i,jl = ∫_i ρ w p_j p_l dA   (M_P = Σ_i M_i),
//                  the integral over the piece itself: its mass moments M_i (zeroth, first and
//                  second about c) turn the parent's force into the body force g that gives it,
//                  and g into the piece's. As h_P = Σ_i B_i (the faces' forces cancel in the sum),
//                  r_i = B_i − M_i M_P⁻¹ Σ_i' B_i'. Exact for gravity and for the inertia of an
//                  acceleration (or velocity) field of degree ≤ n over the cover: at n = 0 a
//                  uniform one (M_i = m_i, the mass share), at n = 1 a linear one — a bar's
//                  uniform stretching, a block's rotation. Sharing the linear terms by mass
//                  instead (the earlier rule at n ≥ 1) leaves the pieces' first moments out:
//                  under uniform gravity a piece's ξ-term gets m_i/m_P of the parent's ∫ ρ w ξ g,
//                  which may be of either sign, for its own ∫_i ρ w ξ g
//                  (Orders/FractureAtHigherOrder.ReleaseOfABodyForceIsNothing).
//   fluid on the new faces (hydraulic fracture, flow.md): B holds the fluid's force on the new
//                  faces at the start's pressure p0 (the pressures carried onto the cut network:
//                  flow_transfer.h); the step's solve carries it at p, the flow network's pressure
//                  at the step's end, ΔP = −Σ_faces ∫ w (p − p0) n ds more. load_work counts the
//                  fluid's work P·d in full (flow_effect.cpp), so the face traction goes from
//                  σ0·n to −p·n within the step and ½ (r + P0 + ΔP)·d = ½ (r + P)·d is what the
//                  crack released: F books ½ ΔP·d (crack_release_fluid, which the flow effect
//                  adds, as only it knows p) besides ½ B·d. With p linear along the edge (p_A at
//                  its start, p_B at its end) and Δu linear too,
//                    ∫ p Δu ds = L/6 · [(2 p_A + p_B) Δu_A + (p_A + 2 p_B) Δu_B]   (exact).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/mesh.h"
#include "solver/discretisation/configuration.h"
#include "solver/discretisation/effect_energy.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// N/m per unknown, r: what the cuts opened of B, the force the start s of a step is out of
/// balance by on a mesh re-cut within the step (in the unknowns of config's space:
/// StepHost::force_at_rest). The pieces of a cover the cuts split were one cover at the start,
/// out of balance by the sum of their B (the faces' forces cancel in it): each piece keeps
/// r = B − M_i M_P⁻¹ · that sum, M the mass moments (above; at cover order 0 the mass share
/// m_i/m_P); the others r = 0. `s` is the state config was placed on (its cover nodes centre the
/// cover functions). `cover_parent` ([cover] the cover of the step's start mesh it is a piece of:
/// RecutMap::cover_parent composed over the step's re-cuts); `removed` ([me] 1: excavated or
/// debris) elements carry no mass. Tied covers (cover_unknowns.h) count with their master.
Eigen::VectorXd cut_release_force(const Model& model, const Configuration& config, const RunState& s,
                                  const std::vector<std::uint8_t>& removed,
                                  const std::vector<std::int32_t>& cover_parent, const Eigen::VectorXd& B);

/// J/m, ½ r·d: the strain energy the faces a step cut released (EnergyStep::cut_work; 0 on a step
/// that changed no mesh).
inline double crack_release(const EnergyStep& e) { return e.changed_start ? 0.5 * e.cut_work : 0.0; }

/// J/m, ½ ΔP·d = −½ Σ_new faces ∫ (p − p0) n·Δu ds: the fluid's part of the release on the faces
/// the step cut, on `mesh` (the one the step ended on), the state s at the step's end and `start`
/// the step's start carried onto `mesh` (its loop_xy, loop_u are read); the faces on the scene's
/// joints from `first_new_joint` on are the step's new ones. `pressure` and `start_pressure`
/// ([2·v] Pa, FlowNetwork::face_pressures): the fluid's pressure at the start and the end of each
/// face edge v → next at the step's end and at its start, 0 on dry edges. Elements of excavated
/// bodies are left out.
double crack_release_fluid(const Mesh& mesh, const RunState& s, const RunState& start, std::size_t first_new_joint,
                           const std::vector<double>& pressure, const std::vector<double>& start_pressure);

}  // namespace nmm::solve
