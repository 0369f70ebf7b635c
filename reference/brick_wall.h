// The staggered brick wall, the DDA code's benchmark of many contacts: n × n bricks on a held
// base, settling under gravity. Its known answer is qualitative: the wall stands, settling onto
// its contacts in the first steps, then its top barely moves and no bed joint opens
// (tests/test_static_analysis.cpp). Used by the static-analysis tests and the contact, matrix,
// detection and effects benches.
#pragma once

#include "scene.h"

namespace nmm::reference {

/// n × n bricks (1 m × 0.5 m, odd rows shifted by half a brick, every brick touching its
/// neighbours) on a base 1 m thick held by fixed points every 0.5 m along y = −0.9;
/// E = 10 GPa, ν = 0.25, ρ = 2650 kg/m³; one interface set (DDA's point penalty, model
/// "penalty": kn = 20·E·1 m = 2e11 N/m per contact point, ks = kn/2.5, φ = 35°); mesh size
/// 0.5 m; gravity; Δt = 1e-3 s. `dynamic`: false gives the static (DDA) analysis.
SceneDef brick_wall(int n, bool dynamic);

}  // namespace nmm::reference
