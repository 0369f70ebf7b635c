// A compressional wave crossing one joint: the displacement-discontinuity model (Schoenberg
// 1980, J. Acoust. Soc. Am. 68(5); Pyrak-Nolte, Myer & Cook 1990, J. Geophys. Res. 95(B6)) in
// closed form and the bar that reproduces it (what is read off a run: studies/joint_wave.h). Built
// here once and used by tests/test_joint_wave.cpp, nmm-study (case joint_wave;
// docs/joint-studies.md) and data/joint_wave.json (the same scene as a file); docs/physics.md §5.
//
// The bar (uniaxial strain: rollers hold y on the top and bottom faces), compression positive:
//
//     σ_i(t)      x_a            x_j            x_b
//   → |------------o--------------|--------------o------------| L
//   traction       measure        joint kn       measure       free end, far enough
//
//   P-wave modulus M = E(1 − ν)/((1 + ν)(1 − 2ν)), speed c = √(M/ρ), impedance Z = ρc.
//   Incident stress at the loaded end, a half-sine of peak p and duration T (ω = π/T):
//     σ_i(s) = p·sin ωs for 0 ≤ s ≤ T, 0 otherwise.
//   A joint of normal stiffness kn (Pa/m) carries σ_t = kn·(u⁻ − u⁺); with stress continuity
//   σ_i + σ_r = σ_t and v = ±σ/Z for waves running ±x, the transmitted stress is the incident
//   one through a first-order low-pass filter of time constant τ = Z/(2kn):
//     τ·dσ_t/ds + σ_t = σ_i,  σ_t(0) = 0,   σ_r = σ_t − σ_i.
//   Integrated exactly for the half-sine (a = ωτ, A = p/(1 + a²)):
//     σ_t(s) = A·(sin ωs − a·cos ωs + a·e^(−s/τ))                         0 ≤ s ≤ T
//     σ_t(s) = σ_t(T)·e^(−(s−T)/τ),  σ_t(T) = A·a·(1 + e^(−T/τ))          s > T
//   and their time integrals (the displacement is ∫v dt = ∫σ dt / Z):
//     I_i(s) = p(1 − cos ωs)/ω (s ≤ T),  2p/ω after
//     I_t(s) = A·((1 − cos ωs)/ω − τ·sin ωs + aτ(1 − e^(−s/τ)))          0 ≤ s ≤ T
//     I_t(s) = I_t(T) + σ_t(T)·τ·(1 − e^(−(s−T)/τ))                      s > T
//   (I_t(∞) = 2p/ω: the joint delays the pulse, it does not keep any of it).
//   At a point x before the joint the incident wave passes at s = t − x/c, the reflected one at
//   s = t − (2x_j − x)/c; after the joint the transmitted wave at s = t − x/c:
//     x < x_j:  v = (σ_i(s_i) − σ_r(s_r))/Z,  u = (I_i(s_i) − I_t(s_r) + I_i(s_r))/Z
//               with s_i = t − x/c, s_r = t − (2x_j − x)/c
//     x > x_j:  v = σ_t(t − x/c)/Z,           u = I_t(t − x/c)/Z.
//   The closed form holds until a wave it leaves out arrives: the reflection off the joint
//   reflected again at the loaded end (free once the pulse is over), at (2x_j + x)/c, and the
//   transmitted wave reflected at the far end, at (2L − x)/c.
#pragma once

#include "common/scene.h"

namespace nmm::reference {

/// The physical problem: rock, pulse, joint and bar (defaults: the scene of data/joint_wave.json).
struct JointWaveSetup {
  double density = 2700;   ///< kg/m³
  double young = 1e10;     ///< Pa
  double poisson = 0.2;    ///< –
  double pressure = 1e6;   ///< Pa, peak of the incident half-sine (compression)
  double duration = 5e-3;  ///< s, T, length of the half-sine
  double kn = 1.37e9;      ///< Pa/m, the joint's normal stiffness (τ = Z/(2kn) = 2.0 ms here)
  double length = 26;      ///< m, L, the bar
  double height = 2;       ///< m, the bar (held in y on both faces)
  double joint_x = 12;     ///< m, x_j
  double before_x = 6;     ///< m, x_a, measure point 0, before the joint
  double after_x = 14;     ///< m, x_b, measure point 1, after the joint
  // The run:
  double h = 0.5;         ///< m, mesh size
  double dt = 2.5e-5;     ///< s, time step
  int table_rows = 41;    ///< rows of the traction's time table over the half-sine (chords within 0.08 % of p)
};

/// The displacement-discontinuity model's closed form for a setup (equations above).
class JointWaveClosedForm {
 public:
  explicit JointWaveClosedForm(const JointWaveSetup& s);
  double modulus() const { return m_; }      ///< Pa, M (uniaxial strain)
  double speed() const { return c_; }        ///< m/s, c
  double impedance() const { return z_; }    ///< Pa·s/m, Z = ρc
  double tau() const { return tau_; }        ///< s, Z/(2kn)
  double incident(double s) const;           ///< Pa, σ_i at source time s
  double transmitted(double s) const;        ///< Pa, σ_t at source time s
  double incident_integral(double s) const;  ///< Pa·s, ∫σ_i
  double transmitted_integral(double s) const;  ///< Pa·s, ∫σ_t
  /// m/s and m along +x at point x (m from the loaded end) and time t (s).
  double velocity(double x, double t) const;
  double displacement(double x, double t) const;
  /// s, when a wave the closed form leaves out first reaches x.
  double valid_until(double x) const;
  /// m, the displacement once the whole pulse has passed, 2p/(ωZ).
  double final_displacement() const;
  /// s, source time of the transmitted stress's peak (σ_t = σ_i there), and that peak, Pa.
  double transmitted_peak_time() const;
  double transmitted_peak() const { return transmitted(transmitted_peak_time()); }
  /// s, when u(x, t) first reaches u(x, ∞)/2 (after the joint; bisection on the closed form).
  double half_rise_time(double x) const;

 private:
  JointWaveSetup s_;
  double m_, c_, z_, tau_, w_;
};

/// kn (Pa/m) that gives time constant τ (s) for the setup's rock.
double joint_wave_kn_for_tau(const JointWaveSetup& s, double tau);

/// The scene: the bar as one body cut across by one joint at x_j, reaching 0.5 m beyond both
/// faces (constant springs kn in Pa/m, ks = kn/2.5; friction 45°: loaded in compression only,
/// it stays closed and elastic), supports holding y along both long faces, the traction −p·table on x = 0,
/// measure points 0 at (x_a, H/2) and 1 at (x_b, H/2); dynamic, β = ½ (Shi's scheme), steps to
/// the latest valid_until of the two points.
SceneDef joint_wave_scene(const JointWaveSetup& s);

}  // namespace nmm::reference
