// Whether an element's stress pulls a crack's line open through it: see tip_drive.h for the
// equation.
#include "solver/fracture/tip_drive.h"

namespace nmm::solve {

bool pulls_line_open(double sxx, double syy, double sxy, const Vec2& along) {
  const double nx = -along.y, ny = along.x;  // the normal of the line ahead
  const double s_nn = sxx * nx * nx + syy * ny * ny + 2 * sxy * nx * ny;  // Pa, nᵀσn
  return s_nn > 0;
}

}  // namespace nmm::solve
