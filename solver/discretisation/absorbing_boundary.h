// Absorbing (viscous) boundaries: Lysmer–Kuhlemeyer dashpots on the body boundary under a
// polyline (scene key "absorbing", docs/absorbing-boundaries.md), in Shi's implicit step.
//
// On an edge a → b under an absorbing polyline (current positions, outward normal n, unit
// tangent s), of its element's material — density ρ, P-wave modulus D₀₀ (λ + 2G in plane strain,
// E/(1 − ν²) in plane stress: the 2-D model's) and shear modulus D₂₂ = G, so cp² = D₀₀/ρ and
// cs² = G/ρ — the boundary carries the traction (Lysmer & Kuhlemeyer 1969)
//     t = −C·v + 2·C·v_in(t),        C = ρ·(cp·n nᵀ + cs·s sᵀ)                  Pa
// the second term only with an input velocity v_in (the incoming wave's particle velocity; a
// compliant base: it lets that wave in and absorbs what comes back). With the element's shape
// functions N (2 × 2nf) along the edge,
//     C_e = ∫ Nᵀ C N ds,     f_in = ∫ Nᵀ 2 C v_in ds                       N·s/m, N
// integrated exactly by the (n + 2)-point Gauss rule (boundary_conditions.h).
//
// How the dashpot enters the step. Shi's step is Newmark with γ = 1 (newmark.h); the velocity
// at its end is
//     v1 = v0 + Δt·a1 = d/(βΔt) − (1/β − 1)·v0 − (1/(2β) − 1)·Δt·a0,
// so the dashpot force −C_e·v1 at the step's end — where the implicit step takes every force —
// moves to the left-hand side as
//     K += C_e/(βΔt),      F += C_e·[(1/β − 1)·v0 + (1/(2β) − 1)·Δt·a0] + f_in(t_end)
// (β = ½, Shi's scheme: K += 2C_e/Δt, F += C_e·v0, i.e. v1 = 2d/Δt − v0). The coefficients are
// the step's inertia coefficients: 1/(βΔt) = c_v, 1/β − 1 = Δt·c_v − 1, 1/(2β) − 1 = c_a. The
// term adds to the symmetric positive definite matrix a symmetric positive semidefinite one,
// so the step stays the minimiser of a convex energy (the contact solve's premise). Only in
// dynamic steps: a static step starts from rest and has no velocity to damp.
//
// The static reaction (as UDEC does when it switches from static to dynamic). A dashpot has no
// stiffness: a boundary that held the model statically (the supports of an earlier stage, or
// the reaction of an in-situ stress) would let the model drift once it absorbs instead. So at
// the first step in which a set of absorbing boundaries acts, the state's out-of-balance force
// on the unknowns of the elements owning their edges — F_ext − F_int with d = 0 and no inertia,
// contact and bolt forces included — is balanced by a force stored
// (RunState::absorbing_reaction, checkpointed) and applied as a constant load from then on. A
// state in equilibrium stays in it; what moves the model after that (an excavation, a wave) is
// absorbed. The reaction is taken again only when a restart's scene changes the absorbing
// polylines.
//
// Cracks that re-cut the mesh (docs/fracture.md) leave the dashpots as they were per length: the
// model built on the new mesh lays them on its boundary edges under the polylines, an edge a crack
// reaches split in two, each with C of its own length. The carried reaction is a force on the
// unknowns of the mesh before; each cover's part follows it onto the pieces of the cover
// (absorbing_reaction_onto): a cover not cut keeps it bit for bit, a cover a crack parts shares it
// out by the pieces' weight on the absorbing edges, w_c = ∫ φ_c ds over them (the boundary
// carries the reaction), or where none of its pieces has such an edge by their weight over their
// elements, ∫ φ_c dA (at cover order 0 φ_c is the triangle's linear weight, so both are exact as
// length × φ_c at the edge's middle and area × φ_c at the element's centroid). The parts sum to
// the cover's, so the reaction's resultant is unchanged.
//
// Energy (energy.csv, docs/energy.md): each accepted step adds the dashpots' work
// v1_eᵀ·C_e·d_e (≥ 0: the energy they take out) to RunState::absorbed_work, and the work of the
// input traction and of the carried reaction, (f_in + r)ᵀ·d, to RunState::absorbing_load_work.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/step_context.h"
#include "solver/discretisation/system_matrix.h"

namespace nmm::solve {

/// The dashpots and input traction of a dynamic step, and the carried reaction (always) into the
/// system's element groups and the rhs.
void absorbing_terms(const Model& model, const StepContext& step, SystemMatrix& system, Eigen::VectorXd& rhs);

/// The scene's absorbing polylines as numbers (count, then per polyline its point count and
/// coordinates): what a state's carried reaction was taken for (RunState::absorbing_key).
std::vector<double> absorbing_key(const SceneDef& scene);

/// True when the state carries no reaction for the scene's absorbing boundaries yet (none taken,
/// or taken for other polylines): the step about to start takes it (absorbing_reaction_of).
bool absorbing_reaction_due(const SceneDef& scene, const RunState& s);

/// The carried reaction from `residual` (N/m, the state's out-of-balance force F_ext − F_int on
/// every unknown with d = 0): the force that balances it, −residual, on the unknowns of the
/// elements owning an absorbing edge, 0 elsewhere; `cover_unknowns` entries (the bolts' unknowns
/// beyond them carry none).
std::vector<double> absorbing_reaction_of(const Model& model, const Configuration& config,
                                          const Eigen::VectorXd& residual, int cover_unknowns);

/// The carried reaction r (on the unknowns of `old_space`, the cover space of the mesh before a
/// re-cut) carried onto `model`'s mesh, re-cut from it (cover_parent: [new cover] the old cover
/// it is a piece of), whose cover space is `space`; see "Cracks that re-cut the mesh" above.
std::vector<double> absorbing_reaction_onto(const std::vector<double>& r, const CoverSpace& old_space,
                                            const std::vector<std::int32_t>& cover_parent, const Model& model,
                                            const CoverSpace& space);

/// The work of an accepted step of increment d (J/m): the dashpots' v1ᵀC_e d (≥ 0) and the
/// input traction's and the carried reaction's (f_in + r)ᵀd, as absorbing_terms() applied them.
struct AbsorbingWork {
  double absorbed = 0;  ///< J/m, taken out by the dashpots
  double loads = 0;     ///< J/m, done by the input traction and the carried reaction
};
AbsorbingWork absorbing_work(const Model& model, const StepContext& step, const Eigen::VectorXd& d);

}  // namespace nmm::solve
