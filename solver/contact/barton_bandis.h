// Barton–Bandis shear strength of a rough rock joint: peak strength, mobilised roughness along
// the shear travel, and dilation (Barton & Choubey 1977; Barton 1982; Barton, Bandis & Bakhtar
// 1985), with shear reversal (sliding back toward the start position down the asperities).
// Equations in barton_bandis.cpp and docs/physics.md §4.
#pragma once

namespace nmm::solve {

/// One joint set's Barton–Bandis parameters (field scale).
struct BartonBandis {
  double jrc = 0;        ///< –, JRC_n
  double jcs = 0;        ///< Pa, JCS_n
  double phi_r_deg = 0;  ///< degrees, residual friction angle φr
  double peak_slip = 0;  ///< m, δp: shear travel at the peak strength
  double strength_factor = 1;  ///< –, the strength is divided by it (strength reduction); dilation is not
};

/// δp = (L/500)·(JRC/L)^0.33 (L in m, δp in m; Barton & Bandis 1982): the peak shear displacement
/// of a joint of length L.
double peak_shear_displacement(double jrc, double length);

/// Barton's dimensionless table JRC_mob/JRC_p against δ/δp (Barton 1982), interpolated linearly:
/// (0, −φr/i) (0.3, 0) (0.6, 0.75) (1, 1) (2, 0.85) (4, 0.7) (10, 0.5) (25, 0.4) (100, 0), held at
/// 0 beyond; i = JRC_p·log10(JCS/σn) (degrees) is the peak roughness angle. With i ≤ 0 (no
/// roughness, or σn ≥ JCS) the ratio is 1: the strength is σn·tan φr whatever the travel.
double mobilised_jrc_ratio(double travel_ratio, double phi_r_deg, double i_deg);

/// The state of the joint at normal stress σn (Pa, effective, > 0) after a shear travel δ (m).
struct BartonBandisState {
  double jrc_mob = 0;       ///< –, mobilised JRC (negative before δ/δp = 0.3)
  double friction_deg = 0;  ///< degrees, φr + JRC_mob·log10(JCS/σn), in [0, 70]
  double dilation_deg = 0;  ///< degrees, d_n,mob = ½·JRC_mob·log10(JCS/σn), ≥ 0
};
BartonBandisState barton_bandis_state(const BartonBandis& law, double sigma_n, double travel);

/// Shear strength (Pa) at normal stress σn (Pa) and travel δ (m): σn·tan(friction_deg)/F (F the
/// strength factor, 1 but in strength reduction); 0 for σn ≤ 0.
double barton_bandis_strength(const BartonBandis& law, double sigma_n, double travel);

/// What a Barton–Bandis joint remembers of its shear history (the contact's JointMemory).
struct JointTravel {
  double travel = 0;    ///< m, δ: total shear travel (either direction): Barton's table reads it
  double dilation = 0;  ///< m, v: normal opening from shearing over the asperities, ≥ 0
  double position = 0;  ///< m, u: signed shear displacement from the joint's start position
};

/// Travel, position and dilation after a step that sheared the joint by Δu (m, signed along the
/// contact's edge) at normal stress σn (Pa). Away from the start position (u·Δu ≥ 0, or from
/// u = 0) the faces climb the asperities; toward it (u·Δu < 0) they ride back down the secant
/// to the start, v ∝ |u|, and reach it with no dilation; a step through u = 0 goes on forward
/// with what is left:
///   forward:   δ' = δ + |Δu|,  u' = u + Δu,  v' = v + tan(d_n,mob(δ + |Δu|/2))·|Δu|
///   backward:  δ' = δ + |Δu|,  u' = u + Δu,  v' = v·|u'|/|u|
JointTravel advance_barton_bandis(const BartonBandis& law, JointTravel now, double sigma_n, double step_shear);

/// The strength state of a joint sliding by Δu (m, signed) from `start` (the memory at the start
/// of the step), at the end of that step: Barton's forward state at the travel δ + |Δu|, or,
/// sliding back toward the start position (u·Δu < 0 and |Δu| < |u|), the asperities' roughness
/// turned against it:
///   φ_back = φr + JRC_mob·log10(JCS/σn) − d_n,mob − ψ,   ψ = atan(v/|u|) (the descent angle)
/// in [0, 70°]; dilation_deg is then −ψ.
BartonBandisState barton_bandis_sliding_state(const BartonBandis& law, double sigma_n, const JointTravel& start,
                                              double step_shear);

/// Shear strength (Pa) of the joint sliding by Δu from `start`: σn·tan(barton_bandis_sliding_state's
/// friction)/F; 0 for σn ≤ 0.
double barton_bandis_strength(const BartonBandis& law, double sigma_n, const JointTravel& start,
                              double step_shear);

}  // namespace nmm::solve
