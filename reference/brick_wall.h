// The staggered brick wall, the DDA code's benchmark of many contacts: n × n bricks on a held
// base, settling under gravity. Its known answer is qualitative: the wall stands, settling onto
// its contacts in the first steps, then its top barely moves and no bed joint opens
// (tests/test_static_analysis.cpp). Used by the static-analysis tests and the contact, matrix,
// detection and effects benches.
#pragma once

#include "common/scene.h"

namespace nmm::reference {

/// n × n bricks (1 m × 0.5 m, odd rows shifted by half a brick, every brick touching its
/// neighbours) on a base 1 m thick held by fixed points every 0.5 m along y = −0.9;
/// E = 10 GPa, ν = 0.25, ρ = 2650 kg/m³; one interface set (DDA's point penalty, model
/// "penalty": kn = 20·E·1 m = 2e11 N/m per contact point, ks = kn/2.5, φ = 35°); mesh size
/// 0.5 m; gravity; Δt = 1e-3 s. `dynamic`: false gives the static (DDA) analysis.
SceneDef brick_wall(int n, bool dynamic);

/// The wall exactly as the DDA code compared with (docs/performance.md "Against a DDA code") is
/// given it by its wall generator, so both are timed on one problem: a rectangle nx m ×
/// ny·0.5 m cut by bed joints every 0.5 m and head joints every 1 m, odd rows offset by half a
/// brick (ending in two half bricks): nx·ny + ⌊ny/2⌋ blocks, on a base block (−1, −1)–(nx + 1, 0)
/// held by three fixed points at y = −0.5 (x = −0.5, nx/2, nx + 0.5); E = 10 MPa, ν = 0.25,
/// ρ = 2500 kg/m³, gravity 9.81 m/s²; DDA's point penalty kn = 50·E·(1 m) = 5e8 N/m per contact
/// point, ks = kn/2.5, φ = 30°, no cohesion or tension; Δt = 1e-3 s; mesh size `h` (m; 0.5 gives
/// about 22 unknowns per brick, the DDA code has 6).
SceneDef peer_wall(int nx, int ny, bool dynamic, double h = 0.5);

}  // namespace nmm::reference
