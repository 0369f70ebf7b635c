// Crack tips that grow by their toughness (docs/crack-tips.md): linear elastic
// fracture mechanics on the tips of crack_tips.h with the stress intensity factors of
// interaction_integral.h.
//
// A tip in a material with a toughness K_Ic grows when its equivalent K under the maximum
// tangential stress criterion (Erdogan & Sih 1963) reaches K_Ic:
//     θ = 2·atan((K_I − √(K_I² + 8K_II²)) / (4K_II))            (0 for K_II = 0)
//     K_eq = cos(θ/2)·(K_I·cos²(θ/2) − 3/2·K_II·sin θ)  ≥  K_Ic
// with K_I taken as max(K_I, 0) (faces pressed together do not open) and K from the interaction
// integral with the faces' traction where their contacts close them (a flaw under compression:
// K_II is the shear its friction does not hold, and a pure mode II tip grows at ∓70.53°,
// K_eq = (2/√3)·|K_II|)
// by one segment of fracture.tip_step (the mesh size if not given) from the tip in the direction
// θ from the crack's own: the segment may end inside an element (its covers cut partially, as a
// joint that ends inside a body), and stops where it meets the body's boundary or another joint
// or crack, overshooting it by 1e-8·h as the strength rule's segments do (fracture.h); one that
// would stop within half a step of such a line runs on to it. The step
// is then solved again on the cut mesh (stepping/fracture_effect.h), so a tip grows as far as
// the load of the step drives it. With fracture.viscous_tip a tip of a crack that carries fluid
// grows against max(K_Ic, the viscous fluid's apparent toughness at its speed), one tip step a
// step (tip_growth.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "solver/discretisation/run_state.h"
#include "solver/fracture/fracture.h"

namespace nmm::solve {

/// Pa·√m, the equivalent K of the maximum tangential stress criterion at the direction θ (rad)
/// of mts_angle (interaction_integral.h).
double mts_equivalent_k(double k1, double k2, double theta);

/// Pa·√m, the apparent toughness of a tip moving at `speed` (m/s) driven by a fluid of
/// `viscosity` (Pa·s) in rock of plane modulus `e_prime` (Pa), read at `distance` (m) behind the
/// tip: √(π/32)·β_m·E′^(2/3)·(12μ·V)^(1/3)·s^(1/6) (tip_growth.cpp).
double apparent_toughness(double e_prime, double viscosity, double speed, double distance);

/// Some material of the scene has a toughness (a fracture run without one looks at no tip here).
bool any_toughness(const SceneDef& scene);

/// The segments the tips of the solved state `s` grow by (above), on `mesh` with the run's
/// `cracks` so far; `skip` [me] 1: excavated or debris; `face_pressure` [2·v] Pa: a fluid's
/// pressure on the crack faces (interaction_integral.h; null: none); `loaded` [v] 1: the face
/// v → next carries its closed contact's traction (Effect::loaded_faces; null: every face is
/// free). Empty where no material has a toughness.
std::vector<CrackSegment> grow_by_toughness(const Mesh& mesh, const SceneDef& scene,
                                            const std::vector<CrackSegment>& cracks, const RunState& s,
                                            const std::vector<std::uint8_t>& skip,
                                            const std::vector<double>* face_pressure = nullptr,
                                            const std::vector<std::uint8_t>* loaded = nullptr);

}  // namespace nmm::solve
