// The strength check of intact rock: see rock_strength.h for the equations.
#include "solver/fracture/rock_strength.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/math_constants.h"

namespace nmm::solve {

RockFailure rock_failure(const StrengthDef& st, double sxx, double syy, double sxy) {
  const double mean = 0.5 * (sxx + syy), radius = std::hypot(0.5 * (sxx - syy), sxy);
  const double s1 = mean + radius, s2 = mean - radius;
  const double theta1 = 0.5 * std::atan2(2 * sxy, sxx - syy);  // σ1's direction
  const Vec2 d1{std::cos(theta1), std::sin(theta1)}, d2{-d1.y, d1.x};  // σ1's and σ2's
  const double r_t = st.tensile > 0 ? s1 / st.tensile : 0.0;
  const double phi = st.friction_deg * kPi / 180, sn = std::sin(phi);
  const double n_phi = (1 + sn) / (1 - sn), ucs = 2 * st.cohesion * std::cos(phi) / (1 - sn);
  const double p1 = -s2, p3 = -s1, drive = p1 - n_phi * p3;
  const double r_s = ucs > 0 ? drive / ucs : drive > 0 ? std::numeric_limits<double>::infinity() : 0.0;
  RockFailure f;
  f.ratio = std::max(r_t, r_s);
  if (r_t >= 1 || r_t >= r_s) {  // the tension cut-off (also where both are reached)
    f.mode = CrackMode::tensile;
    f.direction = f.conjugate = d2;  // across σ1
  } else {
    f.mode = CrackMode::shear;
    // At 45° − φ/2 on either side of the major compression (σ2's direction).
    const double a = 0.25 * kPi - 0.5 * phi, c = std::cos(a), s = std::sin(a);
    f.direction = {c * d2.x - s * d2.y, s * d2.x + c * d2.y};
    f.conjugate = {c * d2.x + s * d2.y, -s * d2.x + c * d2.y};
  }
  return f;
}

StrengthScreen::StrengthScreen(const StrengthDef& st) {
  const double phi = st.friction_deg * kPi / 180, sn = std::sin(phi);
  n_phi_ = (1 + sn) / (1 - sn);
  ucs_ = 2 * st.cohesion * std::cos(phi) / (1 - sn);
  tensile_ = st.tensile;
  usable_ = st.present && tensile_ > 0 && ucs_ > 0 && std::isfinite(n_phi_) && std::isfinite(ucs_);
  if (usable_) slack_ = 1e-13 * (1 + n_phi_) / std::min(tensile_, ucs_);
}

}  // namespace nmm::solve
