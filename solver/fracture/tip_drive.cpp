// Whether an element's stress pulls a crack's line open through it: see tip_drive.h for the
// equation.
#include "solver/fracture/tip_drive.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

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
  // Through cracks tied already, to the fixed point: the least set of cracks that holds the
  // ones tied above and every crack with an end within tol of a segment of a tied one, whatever
  // order the segments are visited in. From each segment of a tied crack (a worklist: a crack's
  // segments join it when the crack is tied), the untied segments with an end near it are found
  // in a grid of the segments' ends, cells as wide as the widest segment: each segment's
  // neighbourhood lies within 2 × 2 cells. (Each pass over all pairs until nothing changed cost
  // S² distances a pass, S the segments: in a shattering wedge of a thousand segments it outgrew
  // the rest of Fracture::find.)
  if (count == 0) return tied;
  double cell = tol, x0 = a[0].x, y0 = a[0].y;
  for (std::size_t i = 0; i < count; ++i) {
    cell = std::max({cell, std::abs(b[i].x - a[i].x) + 2 * tol, std::abs(b[i].y - a[i].y) + 2 * tol});
    x0 = std::min({x0, a[i].x, b[i].x});
    y0 = std::min({y0, a[i].y, b[i].y});
  }
  if (!(cell > 0)) cell = 1;  // tol 0 and points only
  auto cell_of = [&](double x, double y) {
    return std::make_pair(static_cast<std::int64_t>(std::floor((x - x0) / cell)),
                          static_cast<std::int64_t>(std::floor((y - y0) / cell)));
  };
  struct End {
    std::pair<std::int64_t, std::int64_t> cell;
    std::size_t segment;
    bool operator<(const End& o) const { return cell < o.cell || (cell == o.cell && segment < o.segment); }
  };
  std::vector<End> ends;
  ends.reserve(2 * count);
  for (std::size_t i = 0; i < count; ++i) {
    ends.push_back({cell_of(a[i].x, a[i].y), i});
    ends.push_back({cell_of(b[i].x, b[i].y), i});
  }
  std::sort(ends.begin(), ends.end());
  std::vector<std::vector<std::size_t>> of_crack(tied.size());
  std::vector<std::size_t> work;
  for (std::size_t i = 0; i < count; ++i) {
    if (id_tied(crack[i]))
      work.push_back(i);
    else
      of_crack[static_cast<std::size_t>(crack[i])].push_back(i);
  }
  while (!work.empty()) {
    const std::size_t k = work.back();
    work.pop_back();
    const auto lo = cell_of(std::min(a[k].x, b[k].x) - tol, std::min(a[k].y, b[k].y) - tol);
    const auto hi = cell_of(std::max(a[k].x, b[k].x) + tol, std::max(a[k].y, b[k].y) + tol);
    for (std::int64_t cx = lo.first; cx <= hi.first; ++cx)
      for (auto it = std::lower_bound(ends.begin(), ends.end(), End{{cx, lo.second}, 0});
           it != ends.end() && it->cell.first == cx && it->cell.second <= hi.second; ++it) {
        const std::size_t i = it->segment;
        if (id_tied(crack[i])) continue;
        if (to_segment(a[i], a[k], b[k]) <= tol || to_segment(b[i], a[k], b[k]) <= tol) {
          tied[static_cast<std::size_t>(crack[i])] = 1;
          for (const std::size_t j : of_crack[static_cast<std::size_t>(crack[i])]) work.push_back(j);
        }
      }
  }
  return tied;
}

}  // namespace nmm::solve
