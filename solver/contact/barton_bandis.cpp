// Barton–Bandis shear (docs/physics.md §4, "Shear: Barton–Bandis").
//
// Peak strength (Barton & Choubey 1977), effective normal stress σn, residual friction angle φr:
//     τp = σn·tan(φr + JRC·log10(JCS/σn))
// Mobilised roughness (Barton 1982, the dimensionless "JRC_mob" model): along the shear travel δ
// the roughness term JRC·log10(JCS/σn) is scaled by JRC_mob/JRC_p from a table of δ/δp:
//     δ/δp          0        0.3   0.6   1    2     4    10   25   100
//     JRC_mob/JRC_p −φr/i    0     0.75  1    0.85  0.7  0.5  0.4  0
//     τ(δ) = σn·tan(φr + JRC_mob·log10(JCS/σn))
// so τ starts at 0 (the first row cancels φr), reaches τp at δp, and falls to the residual
// σn·tan φr at 100·δp. Linear interpolation between rows; 0 beyond 100·δp (residual).
// Peak displacement (Barton & Bandis 1982; Barton, Bandis & Bakhtar 1985), L and δp in m:
//     δp = (L/500)·(JRC/L)^0.33
// Dilation (Barton & Choubey 1977; Barton 1982): the mobilised dilation angle
//     d_n,mob = ½·JRC_mob·log10(JCS/σn)
// opens the joint by dv = tan(d_n,mob)·dδ. Before δ/δp = 0.3 JRC_mob < 0: no dilation (held at 0,
// not contraction; Barton's model starts dilating at 0.3·δp).
// Guards (ours): σn ≥ JCS gives log10(JCS/σn) ≤ 0, taken as 0 (no roughness: τ = σn·tan φr); at
// very low σn the log grows without bound, and Barton (1976) limits φr + JRC·log10(JCS/σn) to
// 70°: the friction angle and so the dilation angle (its half roughness term) are capped there.
// Strength reduction (nmm-fos) divides τ by F at every σn and travel (the SRM of a nonlinear
// criterion: τ_F(σn) = τ(σn)/F); the dilation, a kinematic property of the asperities, is kept.
// Shear reversal (cyclic shear). Barton's table describes shearing one way from the start; for
// the way back we follow the position-and-direction form of Plesha (1987) that Fei & Choo (2022,
// "Extended Barton–Bandis model for rock joints under cyclic loading", Int. J. Numer. Anal.
// Methods Geomech.; arXiv 2207.06026) bring to the Barton–Bandis model: the joint remembers its
// signed position u (shear displacement from its start), and the roughness degrades with the
// cumulative travel δ = ∫|du| (Barton's table is read at δ whichever way the joint moves, so a
// second cycle meets the softened, post-peak roughness). Their equations were not at hand; what
// is built here is the standard form they extend, stated in full:
//   forward (moving away from the start, u·du ≥ 0): Barton's model as above, at travel δ:
//       τ = σn·tan(φr + JRC_mob(δ)·log10(JCS/σn)),   dv = tan(d_n,mob(δ))·|du|
//   backward (toward the start, u·du < 0): the faces ride down the asperities they climbed, on
//   the secant from where they are to the start (Fei & Choo's zero net dilation at the initial
//   position, taken with the state at the start of the step so it cannot over-contract):
//       dv = −(v/|u|)·|du|   ⇒   v = v_rev·|u|/|u_rev|,   0 at u = 0
//   and the dilation's share of the strength turns against the motion (Patton's φ + i forward,
//   φ − i backward; the asperity-shearing share ½·JRC_mob·log10(JCS/σn) stays):
//       τ = σn·tan(φr + JRC_mob(δ)·log10(JCS/σn) − d_n,mob(δ) − ψ),   ψ = atan(v/|u|)
//   so on reversal at u_rev the strength falls from σn·tan(φr + 2·d_n) to σn·tan(φr + d_n − ψ).
//   Through u = 0 the joint moves forward again on the other side, dilating from zero with the
//   degraded d_n,mob(δ). Before 0.3·δp (no dilation yet) both ways are Barton's pre-peak curve.
// δ, u and v advance at the end of each accepted step from the step's signed shear Δu
// (advance_barton_bandis); within a step the contact's strength uses the state at the end of
// the step: δ + |Δu| and the direction of Δu of the solution so far (solver/contact/contact_problem.cpp, the
// friction fixed point).
#include "solver/contact/barton_bandis.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "common/math_constants.h"

namespace nmm::solve {

namespace {
constexpr double kMaxFrictionDeg = 70;  // Barton (1976): φr + JRC·log10(JCS/σn) ≤ 70°
double rad(double deg) { return deg * kPi / 180; }
// Barton (1982), δ/δp → JRC_mob/JRC_p; the first row's value is −φr/i (filled in at use).
constexpr double kRatio[] = {0, 0.3, 0.6, 1, 2, 4, 10, 25, 100};
constexpr double kJrc[] = {0, 0, 0.75, 1, 0.85, 0.7, 0.5, 0.4, 0};
}  // namespace

double peak_shear_displacement(double jrc, double length) {
  return length / 500.0 * std::pow(jrc / length, 0.33);
}

double mobilised_jrc_ratio(double travel_ratio, double phi_r_deg, double i_deg) {
  if (!(i_deg > 0)) return 1.0;
  const double r = std::max(travel_ratio, 0.0);
  constexpr std::size_t n = std::size(kRatio);
  if (r >= kRatio[n - 1]) return 0.0;
  std::size_t k = 1;
  while (r > kRatio[k]) ++k;
  const double y0 = k == 1 ? -phi_r_deg / i_deg : kJrc[k - 1];
  const double t = (r - kRatio[k - 1]) / (kRatio[k] - kRatio[k - 1]);
  return y0 + t * (kJrc[k] - y0);
}

BartonBandisState barton_bandis_state(const BartonBandis& law, double sigma_n, double travel) {
  BartonBandisState s;
  const double log_term = sigma_n > 0 ? std::max(std::log10(law.jcs / sigma_n), 0.0) : 0.0;
  const double i_peak = law.jrc * log_term;  // degrees
  const double ratio = law.peak_slip > 0 ? travel / law.peak_slip : 0.0;
  s.jrc_mob = law.jrc * mobilised_jrc_ratio(ratio, law.phi_r_deg, i_peak);
  const double roughness = std::min(s.jrc_mob * log_term, kMaxFrictionDeg - law.phi_r_deg);
  s.friction_deg = std::clamp(law.phi_r_deg + roughness, 0.0, kMaxFrictionDeg);
  s.dilation_deg = std::max(0.5 * roughness, 0.0);
  return s;
}

double barton_bandis_strength(const BartonBandis& law, double sigma_n, double travel) {
  if (!(sigma_n > 0)) return 0.0;
  return sigma_n * std::tan(rad(barton_bandis_state(law, sigma_n, travel).friction_deg)) / law.strength_factor;
}

JointTravel advance_barton_bandis(const BartonBandis& law, JointTravel now, double sigma_n,
                                  double step_shear) {
  double du = std::abs(step_shear);
  if (now.position * step_shear < 0) {  // back toward the start, down the secant
    const double from = std::abs(now.position), back = std::min(du, from);
    now.travel += back;
    if (back < from) {
      now.dilation *= (from - back) / from;
      now.position += step_shear;
      return now;
    }
    now.dilation = 0;  // at the start position: the asperities are back in their seats
    now.position = 0;
    du -= back;
    if (!(du > 0)) return now;
  }
  const BartonBandisState mid = barton_bandis_state(law, sigma_n, now.travel + 0.5 * du);
  now.dilation += std::tan(rad(mid.dilation_deg)) * du;
  now.travel += du;
  now.position += step_shear < 0 ? -du : du;
  return now;
}

BartonBandisState barton_bandis_sliding_state(const BartonBandis& law, double sigma_n, const JointTravel& start,
                                              double step_shear) {
  BartonBandisState s = barton_bandis_state(law, sigma_n, start.travel + std::abs(step_shear));
  const double from = std::abs(start.position);
  if (!(start.position * step_shear < 0) || !(std::abs(step_shear) < from)) return s;
  const double descent = std::atan(start.dilation / from) * 180 / kPi;  // ψ, degrees
  s.friction_deg = std::clamp(s.friction_deg - s.dilation_deg - descent, 0.0, kMaxFrictionDeg);
  s.dilation_deg = -descent;
  return s;
}

double barton_bandis_strength(const BartonBandis& law, double sigma_n, const JointTravel& start,
                              double step_shear) {
  if (!(sigma_n > 0)) return 0.0;
  return sigma_n * std::tan(rad(barton_bandis_sliding_state(law, sigma_n, start, step_shear).friction_deg)) /
         law.strength_factor;
}

}  // namespace nmm::solve
