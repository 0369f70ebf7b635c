// Newmark time integration of the step (γ = 1, β = solver.newmark_beta; Shi 1988, 1991;
// docs/physics.md §2). Each step solves for the cover increment d
//     (K + M/(βΔt²)) d = F_ext − F_int + M·[v0/(βΔt) + (1/(2β) − 1)·a0]     (dynamic)
//     (K + 2M/Δt²) d = F_ext − F_int                           (static, static_mode "dda")
//     K d = F_ext − F_int                              (static, static_mode "equilibrium")
// (the inertia term is integrators.h's, with the coefficients below), then
//     a1 = (d − Δt·v0 − (½ − β)Δt²·a0)/(βΔt²),   v1 = v0 + Δt·a1,
// and the next step starts from v0 = k·v1, a0 = k·a1 (k = solver.dynamic_factor; static runs
// keep v = a = 0).
//
// β = ½ is Shi's DDA scheme exactly: (K + 2/Δt² M) d = F + 2/Δt M v0, v1 = 2d/Δt − v0. It is
// stable but keeps no damping at high frequency: where a stiff contact stops a cover (d ≈ 0) its
// velocity flips sign every step (v1 = −v0) for ever, and blocks resting on each other rock and
// then launch. With β > ½ (and γ = 1, still 2β ≥ γ: unconditionally stable) the stiff limit
// damps: its amplification matrix [[1 − 1/β, 1 − 1/(2β)], [−1/β, 1 − 1/(2β)]] has spectral
// radius 0.41 at β = 0.6 (the default, near the minimum), while constant acceleration is still
// integrated exactly (free fall, a sliding block) and slow vibrations barely feel it.
//
// Static analysis is DDA's (Shi 1988): every step starts from rest (v0 = a0 = 0) but keeps the
// inertia term 2M/Δt² (β = ½) in its matrix. A block held only by contacts is then well posed
// (its rigid-body modes have mass), and an out-of-balance force F moves it by at most ½(F/m)Δt²
// per step, so a block system settles over steps onto its equilibrium instead of the step being
// singular. The pure equilibrium solve K d = F (a continuum held by fixed points, reached in
// one step) is static_mode "equilibrium"; it needs every block held by two fixed points
// (static_support.h).
#pragma once

#include "common/scene.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// The Newmark coefficients of the inertia term (0 without it).
struct InertiaCoefficients {
  double on_d = 0;  ///< 1/s², on the increment: 1/(βΔt²)
  double on_v = 0;  ///< 1/s, on v0: 1/(βΔt)
  double on_a = 0;  ///< –, on a0: 1/(2β) − 1
};

/// –, β of the step taken from state s. Until one step has given the acceleration, a0 is
/// unknown: that step takes β = ½, for which a0 drops out, so constant acceleration is exact
/// from the first step on. A static step starts from rest: β = ½ (Shi's 2M/Δt²).
inline double step_beta(const SolverDef& sv, const RunState& s) {
  return s.accel_known && sv.dynamic ? sv.newmark_beta : 0.5;
}

/// The inertia term's coefficients for β and a step of dt (s).
inline InertiaCoefficients inertia_coefficients(double beta, double dt) {
  return {1.0 / (beta * dt * dt), 1.0 / (beta * dt), 1.0 / (2 * beta) - 1.0};
}

/// One unknown's v (m/s) and a (m/s²) moved to the step's end: increment d (m) over dt (s),
/// then both scaled by k = solver.dynamic_factor.
inline void newmark_advance(double d, double dt, double beta, double k, double& v, double& a) {
  const double a1 = (d - dt * v - (0.5 - beta) * dt * dt * a) / (beta * dt * dt);
  v = k * (v + dt * a1);
  a = k * a1;
}

}  // namespace nmm::solve
