// The sliding block, DDA's first reference problem: a rigid block on a plane inclined at α with
// joint friction φ < α slides from rest with constant acceleration, and after time t has moved
//   s(t) = ½ g (sin α − cos α tan φ) t²                                    (φ < α; else 0)
// along the plane (g = 9.81 m/s²). Two ways to build the plane: gravity tilted by α over a flat
// base (no mesh line crosses the contact at an angle), or a real incline the mesh cuts at an
// angle (data/block_on_incline.json at α = 30°, φ = 20°: 0.906 m in 1 s). Used by the contact
// tests, nmm-study (docs/accuracy.md) and the state-hash table (tests/state_hashes.txt).
#pragma once

#include "common/scene.h"

namespace nmm::reference {

/// m, s(t) above for α and φ in degrees, t in s; 0 when the block holds (φ ≥ α).
double sliding_distance(double alpha_deg, double friction_deg, double t);

/// The block on a flat base with gravity tilted by α (degrees): a 2 m × 1 m block placed
/// touching a 12 m × 1 m base held along its bottom (fixed points every 0.25 m along y = 0.1); it
/// slides along +x. Rock and interface as reference::interface_scene, mesh size h (m), cover
/// order `order`, time step dt (s), DDA's point penalty kn = kn_over_e·E per contact point (N/m),
/// ks = kn/2.5. Measure point 0: the block's centre (2, 1.5).
SceneDef sliding_block_tilted(double alpha_deg, double friction_deg, double h = 0.5, int order = 0,
                              double dt = 1e-3, double kn_over_e = 20);

/// The block on a real incline of α (degrees) cut by the mesh at an angle: a 2 m × 1 m block
/// touching the incline, the base held along its bottom. Measure point 0: the block's centre.
/// Down the slope is (−cos α, −sin α). `margin` > 0 (m): a compact base instead, the incline
/// reaching `margin` beyond the block on each side and standing 1 m above the base's held bottom
/// at its low end (the same incline line, so the mesh cuts it the same way).
SceneDef sliding_block_incline(double alpha_deg, double friction_deg, double h = 0.5,
                               int order = 0, double margin = -1);

}  // namespace nmm::reference
