// Reference slides with a closed-form factor of safety (docs/physics.md §5), as scene documents,
// shared by the tests (tests/test_fos.cpp), the benchmark (bench/fos_bench.cpp) and the examples
// (data/planar_slide.json is the planar slide as a file).
//
// Block on a plane: a block resting on a plane dipping α, joint friction φ, no cohesion:
//   F = tan φ / tan α.
// Planar slide with a vertical tension crack (Hoek & Bray, Rock Slope Engineering; dry): a slope
// of height H and face angle ψ_f, a failure plane dipping ψ_p through the toe, a vertical crack
// from the top surface down to the plane at distance x_c from the toe. With plane length A (per
// unit width) and wedge weight W:
//   F = (c·A + W cos ψ_p tan φ) / (W sin ψ_p).
// With the tension crack filled to a depth z_w and the water draining along the plane to the
// toe (Hoek & Bray's standard case: pressure γw·z_w at the crack's foot falling linearly to 0 at
// the toe), the water pushes on the wedge's back with V = ½·γw·z_w² and lifts it off the plane
// with U = ½·γw·z_w·A:
//   F = (c·A + (W cos ψ_p − U − V sin ψ_p) tan φ) / (W sin ψ_p + V cos ψ_p).
// The scene gives this water as a phreatic surface, the straight line from the water level in
// the crack to the toe: hydrostatic below it, it is exactly the pressures above on both faces.
// Both are modelled in the frame of the plane: the plane is horizontal (no slivers where a
// dipping surface would cross the mesh lattice at a shallow angle) and gravity is turned by the
// dip, g = (−g sin ψ, −g cos ψ): the same mechanics. The block or wedge is a body of its own
// resting on a base body; their touching edge is the contact interface (joint set "plane"). The
// rock behind the dry, open tension crack exerts no force and is left out.
//
// What the closed forms assume, the scenes build: (1) a rigid foundation — the base body of the
// planar slide is held by fixed points on a 0.5 m grid. Held at three points only, the 1.1 m
// thick base sags like a beam under the wedge, which then rests on its crack-end corner and a
// 1.5 m patch over the middle support: 3/4 of the sliding plane stays open and, having no
// contact, no cohesion (F came out 0.90 with perfectly plastic joints, 1.24 with the grid).
// (2) Perfectly plastic Mohr–Coulomb: Hoek & Bray mobilise c over the whole plane at once, so
// the plane's joint set keeps its cohesion after slip (residual_cohesion = cohesion,
// docs/contact.md). With the default brittle joint (cohesion lost where a contact reaches its peak) the
// elastic shear concentrations at the toe and the crack end fail first and the plane unzips:
// F = 1.12 from a settled intact state, 0.92 from the initial one, against 1.253 (nmm-fos,
// docs/fos-and-sweeps.md).
#pragma once

#include <nlohmann/json.hpp>

namespace nmm::reference {

struct ReferenceSlide {
  nlohmann::json scene;  ///< scene document (a measure point on the sliding body)
  double fos = 0;        ///< closed-form factor of safety
  double weight = 0;     ///< N per m, W
  double plane_length = 0;  ///< m, A
  double uplift = 0;        ///< N per m, U (water on the plane)
  double crack_thrust = 0;  ///< N per m, V (water in the tension crack)
};

/// A 3 m × 0.5 m block on a plane dipping alpha_deg, friction phi_deg; trial of `duration` s.
ReferenceSlide block_on_plane(double alpha_deg, double phi_deg, double duration = 0.4);

/// Hoek & Bray planar slide: height H, face ψ_f, plane ψ_p, crack at x_c from the toe (must lie
/// behind the crest: x_c > H cot ψ_f), friction φ, cohesion c (Pa). `plastic`: the plane keeps c
/// after slip (residual_cohesion = c, the closed form's assumption); false: brittle.
/// `water_depth` z_w > 0: the crack filled to z_w, draining at the toe (the scene's "water").
ReferenceSlide planar_slide(double height, double face_deg, double plane_deg, double crack_x,
                            double phi_deg, double cohesion, double duration = 0.4,
                            bool plastic = true, double water_depth = 0);

}  // namespace nmm::reference
