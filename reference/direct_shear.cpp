// Displacement-controlled direct shear of a Barton–Bandis joint: scene and closed form
// (direct_shear.h has the equations).
#include "reference/direct_shear.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "reference/joint_specimen.h"
#include "common/math_constants.h"

namespace nmm::reference {

namespace {
constexpr double kMaxFrictionDeg = 70;  // Barton (1976)
constexpr double kTableX[] = {0, 0.3, 0.6, 1, 2, 4, 10, 25, 100};
constexpr double kTableR[] = {0, 0, 0.75, 1, 0.85, 0.7, 0.5, 0.4, 0};  // first row: −φr/i at use
double tan_deg(double d) { return std::tan(d * kPi / 180); }
double log_term(const BartonJoint& j, double sigma_n) {
  return sigma_n > 0 ? std::max(std::log10(j.jcs / sigma_n), 0.0) : 0.0;
}
// degrees: JRC·r·log10(JCS/σn), capped at 70° − φr.
double roughness(const BartonJoint& j, double sigma_n, double travel) {
  const double lt = log_term(j, sigma_n);
  const double r = barton_jrc_ratio(travel / j.peak_slip, j.phi_r_deg, j.jrc * lt);
  return std::min(j.jrc * r * lt, kMaxFrictionDeg - j.phi_r_deg);
}
}  // namespace

double barton_jrc_ratio(double travel_ratio, double phi_r_deg, double i_deg) {
  if (!(i_deg > 0)) return 1;
  const double x = std::max(travel_ratio, 0.0);
  const std::size_t n = std::size(kTableX);
  if (x >= kTableX[n - 1]) return 0;
  std::size_t k = 1;
  while (x > kTableX[k]) ++k;
  const double r0 = k == 1 ? -phi_r_deg / i_deg : kTableR[k - 1];
  return r0 + (x - kTableX[k - 1]) / (kTableX[k] - kTableX[k - 1]) * (kTableR[k] - r0);
}

double barton_shear_stress(const BartonJoint& j, double sigma_n, double travel) {
  if (!(sigma_n > 0)) return 0;
  return sigma_n * tan_deg(std::max(j.phi_r_deg + roughness(j, sigma_n, travel), 0.0));
}

double barton_dilation_angle(const BartonJoint& j, double sigma_n, double travel) {
  return std::max(0.5 * roughness(j, sigma_n, travel), 0.0);
}

double barton_opening(const BartonJoint& j, double sigma_n, double travel) {
  // Simpson's rule between consecutive table rows (the integrand is smooth inside each).
  double v = 0, a = 0;
  for (std::size_t k = 1; k < std::size(kTableX) && a < travel; ++k) {
    const double b = std::min(travel, kTableX[k] * j.peak_slip);
    const int m = 200;
    double s = 0;
    for (int q = 0; q <= m; ++q) {
      const double w = (q == 0 || q == m) ? 1 : (q % 2 ? 4 : 2);
      s += w * tan_deg(barton_dilation_angle(j, sigma_n, a + (b - a) * q / m));
    }
    v += s * (b - a) / (3.0 * m);
    a = b;
  }
  if (travel > a) v += (travel - a) * tan_deg(barton_dilation_angle(j, sigma_n, travel));
  return v;
}

ReversedShearPoint barton_reversed_shear(const BartonJoint& j, double sigma_n, double amplitude,
                                         double travel) {
  ReversedShearPoint p;
  const double a = amplitude;
  p.position = travel <= a ? travel : 2 * a - travel;
  if (travel <= a || travel >= 2 * a) {  // forward (at the start itself too)
    p.shear_stress = barton_shear_stress(j, sigma_n, travel);
    p.opening = travel <= a ? barton_opening(j, sigma_n, travel)
                            : barton_opening(j, sigma_n, travel) - barton_opening(j, sigma_n, 2 * a);
    return p;
  }
  const double v_a = barton_opening(j, sigma_n, a);
  const double psi = std::atan(v_a / a) * 180 / kPi;
  const double phi = j.phi_r_deg + roughness(j, sigma_n, travel) - barton_dilation_angle(j, sigma_n, travel) - psi;
  p.shear_stress = sigma_n * tan_deg(std::clamp(phi, 0.0, kMaxFrictionDeg));
  p.opening = v_a * p.position / a;
  return p;
}

SceneDef direct_shear_scene(const JointSetDef& joint, double sigma_n, double velocity) {
  SceneDef s = joint_specimen_scene(joint, 5e11, 0.25);
  load_joint_specimen(s, sigma_n, 0);
  SupportDef push;
  push.points = {{0, 1}, {0, 2}};
  push.fix_x = true;
  push.velocity = {velocity, 0};
  s.supports.push_back(push);
  s.solver.support_stiffness = 1e14;
  return s;
}

}  // namespace nmm::reference
