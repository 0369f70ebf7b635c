// Whether an element's stress pulls a crack's line open through it: see tip_drive.h for the
// equation.
#include "solver/fracture/tip_drive.h"

#include <algorithm>
#include <cmath>

namespace nmm::solve {

bool pulls_line_open(double sxx, double syy, double sxy, const Vec2& along) {
  const double nx = -along.y, ny = along.x;  // the normal of the line ahead
  const double s_nn = sxx * nx * nx + syy * ny * ny + 2 * sxy * nx * ny;  // Pa, nᵀσn
  return s_nn > 0;
}

namespace {

// m, the distance from p to the segment (a, b).
double to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / l2, 0.0, 1.0) : 0.0;
  return std::hypot(a.x + t * dx - p.x, a.y + t * dy - p.y);
}

}  // namespace

std::vector<std::uint8_t> jointed_cracks(const std::vector<JointDef>& joints, std::size_t scene_joints,
                                         const std::vector<Vec2>& a, const std::vector<Vec2>& b,
                                         const std::vector<std::int32_t>& crack, int cracks, double tol) {
  std::vector<std::uint8_t> tied(static_cast<std::size_t>(std::max(cracks, 0)), 0);
  const std::size_t count = a.size();
  auto id_tied = [&](std::int32_t c) { return c < 0 || tied[static_cast<std::size_t>(c)] != 0; };
  auto on_joint = [&](const Vec2& p) {
    for (std::size_t j = 0; j < scene_joints && j < joints.size(); ++j)
      for (std::size_t k = 0; k + 1 < joints[j].points.size(); ++k)
        if (to_segment(p, joints[j].points[k], joints[j].points[k + 1]) <= tol) return true;
    return false;
  };
  for (std::size_t i = 0; i < count; ++i)
    if (crack[i] >= 0 && (on_joint(a[i]) || on_joint(b[i]))) tied[static_cast<std::size_t>(crack[i])] = 1;
  // Through cracks tied already, until nothing changes (each pass ties at least one more crack).
  for (bool more = true; more;) {
    more = false;
    for (std::size_t i = 0; i < count; ++i) {
      if (id_tied(crack[i])) continue;
      for (std::size_t k = 0; k < count && !id_tied(crack[i]); ++k)
        if (id_tied(crack[k]) && (to_segment(a[i], a[k], b[k]) <= tol || to_segment(b[i], a[k], b[k]) <= tol))
          tied[static_cast<std::size_t>(crack[i])] = 1, more = true;
    }
  }
  return tied;
}

}  // namespace nmm::solve
