// Whether an element's stress drives a crack's line on through it: see tip_drive.h for the
// equations.
#include "solver/fracture/tip_drive.h"

#include <algorithm>
#include <cmath>

#include "common/math_constants.h"

namespace nmm::solve {

bool drives_line_ahead(const StrengthDef& strength, double sxx, double syy, double sxy, const Vec2& along,
                       CrackMode mode) {
  const double nx = -along.y, ny = along.x;  // the normal of the line ahead
  const double tx = sxx * nx + sxy * ny, ty = sxy * nx + syy * ny;  // traction on it, σ·n (Pa)
  const double s_nn = tx * nx + ty * ny, tau = tx * along.x + ty * along.y;
  if (mode == CrackMode::tensile) return s_nn > 0;
  const double friction = std::tan(strength.friction_deg * kPi / 180);
  return std::abs(tau) > friction * std::max(-s_nn, 0.0);
}

}  // namespace nmm::solve
