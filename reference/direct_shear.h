// Displacement-controlled direct shear of one Barton–Bandis joint, through and past the peak: the
// single-joint specimen (joint_specimen.h: two 2 m × 1 m blocks of stiff rock, the joint at y = 1)
// with a constant normal stress σn on the top face (loads) and the upper block's left face pushed
// along the joint at a constant velocity v (a support moving in x, free in y: a shear box's
// actuator and its guided, dilating upper half). Its closed form is Barton's model at constant
// normal stress (Barton & Choubey 1977; Barton 1982; Barton, Bandis & Bakhtar 1985):
//     τ(δ) = σn·tan(φr + JRC·r(δ/δp)·log10(JCS/σn)),   τp = τ(δp) = σn·tan(φr + JRC·log10(JCS/σn))
//     r: Barton's dimensionless table JRC_mob/JRC_p against δ/δp, linear between its rows
//         δ/δp   0       0.3  0.6   1  2     4    10   25   100
//         r      −φr/i   0    0.75  1  0.85  0.7  0.5  0.4  0      (i = JRC·log10(JCS/σn), °)
//     d_mob(δ) = ½·JRC·r·log10(JCS/σn) (held at 0 where r < 0),   v(δ) = ∫0^δ tan d_mob dδ'
// (the roughness term capped so that the friction angle stays ≤ 70°, Barton 1976). Written here
// from the papers, apart from solver/contact/barton_bandis.cpp, so that the solver is checked against an
// independent statement of the model. Used by tests/test_barton_bandis.cpp and nmm-joint-study.
#pragma once

#include "common/scene.h"

namespace nmm::reference {

/// A Barton–Bandis joint at field scale (after any scale correction).
struct BartonJoint {
  double jrc = 0;        ///< –, JRC_n
  double jcs = 0;        ///< Pa, JCS_n
  double phi_r_deg = 0;  ///< degrees, residual friction angle φr
  double peak_slip = 0;  ///< m, δp
};

/// –, Barton's table r(δ/δp) above, with its first row −φr/i (i in degrees; r = 1 when i ≤ 0).
double barton_jrc_ratio(double travel_ratio, double phi_r_deg, double i_deg);

/// Pa, τ(δ) at normal stress σn (Pa, > 0) after a shear travel δ (m).
double barton_shear_stress(const BartonJoint& j, double sigma_n, double travel);

/// degrees, the mobilised dilation angle d_mob(δ) at σn (Pa) and travel δ (m).
double barton_dilation_angle(const BartonJoint& j, double sigma_n, double travel);

/// m, the opening v(δ) = ∫0^δ tan d_mob dδ' at constant σn (Simpson's rule on each of the table's
/// intervals, where the integrand is smooth).
double barton_opening(const BartonJoint& j, double sigma_n, double travel);

/// The shear box reversed: sheared to +A, back through the start position to −A (travel 3A), at
/// constant σn (the extended model of solver/contact/barton_bandis.cpp written out again: Plesha 1987's position and
/// direction, Fei & Choo 2022's zero dilation at the start). Along the path's travel s (m):
///   0 ≤ s ≤ A     u = s         τ = τ(s),  v = v(s)                          (forward: Barton)
///   A < s < 2A    u = 2A − s    τ = σn·tan(φr + JRC·r(s/δp)·log10(JCS/σn) − d_mob(s) − ψ),
///                               ψ = atan(v(A)/A),  v = v(A)·u/A             (back down the asperities)
///   2A ≤ s ≤ 3A   u = 2A − s    τ = τ(s),  v = v(s) − v(2A)                 (forward again, degraded)
/// with τ(δ), d_mob(δ) and v(δ) = ∫0^δ tan d_mob of the monotonic model above (the roughness and
/// the dilation read Barton's table at the cumulative travel).
struct ReversedShearPoint {
  double position = 0;      ///< m, u: the upper block's shear displacement from the start
  double shear_stress = 0;  ///< Pa, |τ| (it acts against the motion)
  double opening = 0;       ///< m, v
};
ReversedShearPoint barton_reversed_shear(const BartonJoint& j, double sigma_n, double amplitude, double travel);

/// The specimen (joint_specimen_scene(joint, E = 500 GPa, h = 0.25 m)) under σn (Pa) on its top
/// face, the upper block's left face (x = 0, 1 ≤ y ≤ 2) driven in x at `velocity` (m/s) by a
/// moving support of stiffness 1e14 N/m²; quasi-static steps of 1 ms.
SceneDef direct_shear_scene(const JointSetDef& joint, double sigma_n, double velocity);

}  // namespace nmm::reference
