// The KGD hydraulic fracture (plane strain, a straight crack of half-length ℓ fed at its middle by
// Q0, m³/s per m of thickness into both wings, no leak-off, no confining stress): the scene of
// tests/test_kgd.cpp and docs/kgd_curves.py, and the closed forms of its two limiting regimes
// (docs/flow.md "Hydraulic fracturing"). E′ = E/(1 − ν²), μ′ = 12μ, K′ = 4·√(2/π)·K_Ic; the
// regime is set by the dimensionless toughness K_m = K′/(E′³·μ′·Q0)^(1/4), constant in time for
// this geometry (Detournay 2004, "Propagation regimes of fluid-driven fractures in impermeable
// rocks", Int. J. Geomech. 4(1) 35–45): viscosity-dominated (the M-vertex) for K_m ≲ 1,
// toughness-dominated (the K-vertex) for K_m ≳ 4.
//
// Toughness-dominated (μ → 0): the pressure p is uniform, Griffith's crack under p holds
// V = 2π·p·ℓ²/E′ and grows at p·√(πℓ) = K_Ic; with V = Q0·t (derived here):
//   ℓ(t) = (E′Q0t/(2√π·K_Ic))^(2/3) = 0.9324·(E′Q0t/K′)^(2/3),   0.9324 = (π/(2√2))^(−2/3)
//   p(t) = K_Ic/√(πℓ(t)),   w(0, t) = 4·p·ℓ/E′   (the faces' separation at the middle).
//
// Viscosity-dominated (K_Ic → 0, no fluid lag): Adachi & Detournay 2002 ("Self-similar solution
// of a plane-strain fracture driven by a power-law fluid", Int. J. Numer. Anal. Meth. Geomech.
// 26, 579–604), in the scaling of Detournay 2004: with ε = (μ′/(E′t))^(1/3),
// L = (E′Q0³t⁴/μ′)^(1/6), ξ = x/ℓ,
//   ℓ(t) = γ·L,   w(x, t) = ε·L·γ·Ω̄(ξ),   p(x, t) = ε·E′·Π(ξ),
// where, with α = 2/3 and C_n^(α−1/2) the Gegenbauer polynomials,
//   Ω̄(ξ) = Σ_{j=1..7} A_j·(1 − ξ²)^α·C_{2j−2}^(1/6)(ξ) + B·[4√(1 − ξ²) + 2ξ²·ln|(1 − √(1 − ξ²))/(1 + √(1 − ξ²))|]
//   Π(ξ)  = A_1·(α/2π)·B(½, α)·₂F₁(½ − α, 1; ½; ξ²)
//         + Σ_{j=2..7} A_j·(2α − 1)(2j − 1)/(4π(j − 1 + α))·B(½ − j, α + j)
//                      ·[α·ξ²·₂F₁(5/2 − j − α, j; 3/2; ξ²) − ½·₂F₁(3/2 − j − α, j − 1; ½; ξ²)]
//         + B·(2 − π|ξ|)
// (B(·,·) the beta function), A = 1.61750, 0.39650, 1.00297e-2, 1.06179e-2, −2.97947e-3,
// −0.74268e-3, −1.34675e-3, B = 0.06858, γ = 0.61524 (Adachi & Detournay 2002's series; GEOS's
// validation case quotes ℓ = 0.6152·(E′Q0³/μ′)^(1/6)·t^(2/3) and w0·p0 = 0.62·(μ′Q0E′)^(1/2)).
// What we checked of it here (tests/test_kgd.cpp, Kgd.ClosedForms): the scaling, derived: with
// w ∝ t^(1/3), ℓ ∝ t^(2/3), the fluid's balance ∂w/∂t + ∂q/∂x = 0 and Poiseuille's
// q = −w³/μ′·∂p/∂x give −Ω̄³·Π′ = ∫_ξ^1 Ω̄ dξ′ + (2/3)·ξ·Ω̄(ξ), which the series meets within
// 0.4 % on 0.1 ≤ ξ ≤ 0.9; the volume ∫_{−ℓ}^{ℓ} w dx = Q0·t, i.e. γ²·∫_{−1}^{1} Ω̄ dξ = 1, gives γ = 0.6162
// from the seven terms (0.16 % above the published 0.61524, the series' truncation). At the
// wellbore: Ω̄(0) = 1.8258, so w(0, t) = 1.1233·(μ′Q0³t²/E′)^(1/6); Π(0) = 0.5443, so
// p(0, t) = 0.5443·(E′²μ′/t)^(1/3). Near the tip Π → −∞ as −(1 − ξ)^(−1/3) (the zero-lag
// solution's suction): Π(ξ) < 0 for ξ > 0.95.
#pragma once

#include "common/scene.h"

namespace nmm::reference {

/// The KGD scene: a square plate of half-width W with a crack along y = 0 from −ℓ0 to ℓ0, an
/// injection at its middle, tips that grow by toughness in steps of h, static equilibrium steps.
struct KgdSetup {
  double half_width = 2;      ///< m, W: the plate spans [−W, W]²
  double h = 0.05;            ///< m, mesh size and tip step
  double l0 = 0.2;            ///< m, initial half-length
  double q0 = 1e-5;           ///< m²/s, injection (m³/s per m, both wings)
  double dt = 0.25;           ///< s, time step
  double young = 1e10;        ///< Pa
  double poisson = 0.25;      ///< –
  double k_ic = 1e6;          ///< Pa·√m, toughness
  double viscosity = 1e-6;    ///< Pa·s, μ
  double bulk_modulus = 2.2e9; ///< Pa, the fluid's K_f
  double residual = 1e-6;     ///< m, hydraulic aperture of closed faces
  bool viscous_tip = false;   ///< fracture.viscous_tip: tips grow against the fluid's apparent toughness
  bool lag = false;           ///< a fluid lag: flow.fluid.cavitation_pressure given
  double cavitation_pressure = 0;  ///< Pa, its floor (net of the confining stress: none here)
};

/// The scene of `k` (plane strain; the plate held at one point and one roller on its base).
SceneDef kgd_scene(const KgdSetup& k);

/// The constants of the closed forms for `k`: E′ (Pa), μ′ (Pa·s), K′ (Pa·√m).
struct KgdScales {
  double e_prime = 0, mu_prime = 0, k_prime = 0, q0 = 0;
  explicit KgdScales(const KgdSetup& k);
  /// –, K_m = K′/(E′³μ′Q0)^(1/4).
  double toughness_number() const;
};

/// Toughness-dominated (K-vertex): half-length (m), pressure (Pa), opening at the middle (m) at t (s).
double kgd_k_length(const KgdScales& s, double k_ic, double t);
double kgd_k_pressure(const KgdScales& s, double k_ic, double t);
double kgd_k_opening(const KgdScales& s, double k_ic, double t);

/// Viscosity-dominated (M-vertex, zero lag): half-length (m) at t (s); opening (m) and net
/// pressure (Pa) at x = ξ·ℓ(t), 0 ≤ |ξ| < 1.
double kgd_m_length(const KgdScales& s, double t);
double kgd_m_opening(const KgdScales& s, double xi, double t);
double kgd_m_pressure(const KgdScales& s, double xi, double t);
/// The M-vertex's dimensionless profiles Ω̄(ξ) and Π(ξ) (header comment).
double kgd_m_omega_bar(double xi);
double kgd_m_pi(double xi);
/// γ of the M-vertex: 0.61524.
constexpr double kKgdMGamma = 0.61524;

}  // namespace nmm::reference
