// Excavation (scene key "excavate": [body, ...], in the scene, a --config or --set, usually at a
// restart): the bodies listed are removed at the start of the run.
//
// - Their covers and elements drop out of the system: the elements add no stiffness, mass or
//   force, their covers' unknowns are held at zero (a diagonal pin, so that the unknowns and the
//   sparsity pattern stay those of the mesh and a restart stays exact), no contact is detected
//   on them, and frames show them with zero stress.
// - The stress they carried is released onto the remaining rock through the new free face: the
//   locked-in in-situ traction t = σ_insitu·n on each face the removed body shared with the
//   rock (insitu_stress.h) — the equivalent nodal forces f = ∫ Nᵀ σ n ds of the removed body's
//   stress — is taken off, either at once (solver.excavation_steps = 1, the default: the sudden
//   excavation of a dynamic analysis, or a static analysis's one-step answer) or in equal parts
//   over solver.excavation_steps steps (a gradual release, less dynamic overshoot):
//       f_applied = f · max(0, 1 − k/N)   in the k-th step after the excavation (k = 1, 2, ...)
//   Forces the removed body carried through contacts (its weight on the rock, say) vanish with
//   its contacts at once.
// At cover order n ≥ 1 the same: f is integrated with the run's shape functions (polynomials of
// degree n + 1; the (n + 2)-point Gauss rule along each face is exact for them and the linear
// field), the removed elements' stress polynomials are zeroed, their covers' n-th order
// unknowns pinned like the constant ones.
// The step a body was removed at is part of the run state, so a restart in the middle of a
// gradual release goes on releasing it.
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// Marks `bodies` removed at the state's current step (bodies already removed stay as they
/// were) and zeroes their elements' stress: all `stress_terms` polynomial coefficients of each
/// (T = (n+1)(n+2)/2 at cover order n; s.stress holds 3·T per element).
void excavate_bodies(const std::vector<int>& bodies, const Mesh& mesh, std::size_t stress_terms,
                     RunState& s);

/// [me] 1 for elements of removed bodies.
std::vector<std::uint8_t> removed_elements(const Mesh& mesh, const RunState& s);

/// The covers of removed elements (`removed` [me] 1: removed_elements, or debris the cracks cut
/// off: fracture.h) keep no velocity: they stand still, held at zero (dofs_per_cover unknowns
/// per cover in s.velocity and s.accel); their blocks hand no force on (s.block_force).
void hold_removed_covers(const Mesh& mesh, int dofs_per_cover, const std::vector<std::uint8_t>& removed,
                         RunState& s);

/// Fraction of the locked-in traction on a face towards `body` still applied in the step after
/// `s.step`: 1 while the body is there, then 1 − k/N.
double interface_traction_factor(const RunState& s, std::int32_t body, std::int64_t release_steps);

}  // namespace nmm::solve
