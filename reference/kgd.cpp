// The KGD hydraulic fracture: scene and closed forms (kgd.h has the equations and their sources).
#include "reference/kgd.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "common/math_constants.h"

namespace nmm::reference {

namespace {

constexpr double kAlpha = 2.0 / 3.0;  // the opening's tip exponent, w ∝ (1 − ξ)^(2/3)
// Adachi & Detournay 2002's coefficients of the M-vertex series (kgd.h).
constexpr double kA[7] = {1.61750, 0.39650, 1.00297e-2, 1.06179e-2, -2.97947e-3, -0.74268e-3, -1.34675e-3};
constexpr double kB = 0.06858;

double beta(double a, double b) { return std::tgamma(a) * std::tgamma(b) / std::tgamma(a + b); }

// ₂F₁(a, b; c; z) by its series, 0 ≤ z < 1 (near z = 1 the terms fall as k^(a+b−c−1)·z^k: up
// to 200 000 of them at ξ = 0.9999).
double hyp2f1(double a, double b, double c, double z) {
  double sum = 1, term = 1;
  for (int k = 0; k < 200000; ++k) {
    term *= (a + k) * (b + k) / ((c + k) * (k + 1)) * z;
    sum += term;
    if (std::abs(term) < 1e-16 * std::abs(sum)) break;
  }
  return sum;
}

// Gegenbauer C_n^(λ)(x) by the three-term recurrence.
double gegenbauer(int n, double lambda, double x) {
  if (n == 0) return 1;
  double c0 = 1, c1 = 2 * lambda * x;
  for (int k = 1; k < n; ++k) {
    const double c2 = (2 * x * (k + lambda) * c1 - (k + 2 * lambda - 1) * c0) / (k + 1);
    c0 = c1;
    c1 = c2;
  }
  return c1;
}

}  // namespace

SceneDef kgd_scene(const KgdSetup& k) {
  using nlohmann::json;
  const double W = k.half_width, h = k.h;
  json d;
  d["plane"] = "strain";
  // The intact rock never breaks by strength (1 GPa): the tips grow by toughness alone.
  d["materials"]["rock"] = {{"density", 2500}, {"young", k.young}, {"poisson", k.poisson},
                            {"strength", {{"tensile", 1e9}, {"cohesion", 1e9}, {"friction_deg", 30},
                                          {"toughness", k.k_ic}}}};
  d["joint_sets"]["crack"] = {{"friction_deg", 30},
                              {"normal", {{"model", "constant"}, {"kn", 1e12}}},
                              {"shear", {{"model", "constant"}, {"ks", 4e11}}}};
  d["bodies"] = {{{"material", "rock"}, {"outer", {{-W, -W}, {W, -W}, {W, W}, {-W, W}}}}};
  d["joints"] = {{{"set", "crack"}, {"points", {{-k.l0, 0}, {k.l0, 0}}}}};
  d["mesh"]["size"] = h;
  // Statically determinate: a point near the base's middle and a roller at its right end.
  d["fixed_points"] = {{0, -W + 0.01 * h}};
  d["supports"] = {{{"points", {{W - 0.5 * h, -W}, {W, -W}}}, {"fix", "y"}}};
  d["solver"] = {{"time_step", k.dt}, {"dynamic", false}, {"static_mode", "equilibrium"}};
  d["fracture"] = {{"crack_set", "crack"}, {"tip_step", h}};
  if (k.viscous_tip) d["fracture"]["viscous_tip"] = true;
  d["flow"] = {{"fluid", {{"viscosity", k.viscosity}, {"bulk_modulus", k.bulk_modulus}}},
               {"aperture", {{"residual", k.residual}, {"max", 0.1}}},
               {"injections", {{{"point", {0, 0}}, {"rate", k.q0}}}}};
  if (k.lag) d["flow"]["fluid"]["cavitation_pressure"] = k.cavitation_pressure;
  return scene_from_json(d, "kgd");
}

KgdScales::KgdScales(const KgdSetup& k)
    : e_prime(k.young / (1 - k.poisson * k.poisson)),
      mu_prime(12 * k.viscosity),
      k_prime(4 * std::sqrt(2 / kPi) * k.k_ic),
      q0(k.q0) {}

double KgdScales::toughness_number() const {
  return k_prime / std::pow(e_prime * e_prime * e_prime * mu_prime * q0, 0.25);
}

double kgd_k_length(const KgdScales& s, double k_ic, double t) {
  return std::pow(s.e_prime * s.q0 * t / (2 * std::sqrt(kPi) * k_ic), 2.0 / 3.0);
}

double kgd_k_pressure(const KgdScales& s, double k_ic, double t) {
  return k_ic / std::sqrt(kPi * kgd_k_length(s, k_ic, t));
}

double kgd_k_opening(const KgdScales& s, double k_ic, double t) {
  return 4 * kgd_k_pressure(s, k_ic, t) * kgd_k_length(s, k_ic, t) / s.e_prime;
}

double kgd_m_omega_bar(double xi) {
  const double z = xi * xi, r = std::sqrt(std::max(0.0, 1 - z));
  double w = 4 * r;
  if (xi != 0 && r > 0) w += 2 * z * std::log(std::abs((1 - r) / (1 + r)));
  w *= kB;
  for (int j = 1; j <= 7; ++j) w += kA[j - 1] * std::pow(1 - z, kAlpha) * gegenbauer(2 * j - 2, kAlpha - 0.5, xi);
  return w;
}

double kgd_m_pi(double xi) {
  const double z = xi * xi, a = kAlpha;
  double p = kA[0] * a / (2 * kPi) * beta(0.5, a) * hyp2f1(0.5 - a, 1, 0.5, z);
  for (int j = 2; j <= 7; ++j)
    p += kA[j - 1] * (2 * a - 1) * (2 * j - 1) / (4 * kPi * (j - 1 + a)) * beta(0.5 - j, a + j) *
         (a * z * hyp2f1(2.5 - j - a, j, 1.5, z) - 0.5 * hyp2f1(1.5 - j - a, j - 1, 0.5, z));
  return p + kB * (2 - kPi * std::abs(xi));
}

double kgd_m_length(const KgdScales& s, double t) {
  return kKgdMGamma * std::pow(s.e_prime * s.q0 * s.q0 * s.q0 * t * t * t * t / s.mu_prime, 1.0 / 6.0);
}

double kgd_m_opening(const KgdScales& s, double xi, double t) {
  // ε·L = (μ′Q0³t²/E′)^(1/6)
  const double eps_l = std::pow(s.mu_prime * s.q0 * s.q0 * s.q0 * t * t / s.e_prime, 1.0 / 6.0);
  return eps_l * kKgdMGamma * kgd_m_omega_bar(xi);
}

double kgd_m_pressure(const KgdScales& s, double xi, double t) {
  // ε·E′ = (E′²μ′/t)^(1/3)
  return std::cbrt(s.e_prime * s.e_prime * s.mu_prime / t) * kgd_m_pi(xi);
}

}  // namespace nmm::reference
