// Where a new crack may start in rock that softens: the rules in cohesive_starts.h.
//
// Rule 2 compares the strength ratio r = max(σ1/σt, (p1 − Nφ·p3)/(2c·√Nφ)) (rock_strength.h) of
// the element's stress at the step's solution with the one at its start: r_end > r_start loads.
// Rule 4's band: with t the tip, d its unit direction and n = (−d_y, d_x), a point p lies at
// a = (p − t)·d ahead and l = (p − t)·n across; the element meets the strip |l| < w where its
// vertices' l do not all lie on one side beyond it.
#include "solver/fracture/cohesive_starts.h"

#include <algorithm>
#include <limits>

#include "solver/contact/cohesive_law.h"
#include "solver/discretisation/stress_field.h"
#include "solver/fracture/element_geometry.h"
#include "solver/fracture/fracture.h"
#include "solver/fracture/rock_strength.h"

namespace nmm::solve {

std::vector<std::uint8_t> cohesive_starts(const Mesh& mesh, const SceneDef& scene, const RunState& start,
                                          const RunState& solved, bool started_this_step, std::size_t first_crack) {
  std::vector<std::uint8_t> soft(scene.bodies.size(), 0);
  bool any = false;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    soft[b] = cohesive_law(scene.materials[static_cast<std::size_t>(scene.bodies[b].material)].strength).on() ? 1 : 0;
    any = any || soft[b];
  }
  if (!any) return {};
  const std::size_t n = mesh.element_count();
  std::vector<std::uint8_t> may(n, kMayStart);
  // The stress the strength check reads (Fracture::find): the element's own at cover order 0,
  // its mean at n ≥ 1.
  const int order = scene.solver.cover_order;
  const std::vector<double> end = order == 0 ? solved.stress : mean_stress(mesh, order, solved);
  const std::vector<double> begin = order == 0 ? start.stress : mean_stress(mesh, order, start);
  const bool known = begin.size() == 3 * n && end.size() == 3 * n;
  for (std::size_t e = 0; e < n; ++e) {
    const std::int32_t body = mesh.element_body[e];
    if (!soft[static_cast<std::size_t>(body)]) continue;
    may[e] = started_this_step ? kMayBeReached : kMayStart | kMayBeReached;  // rule 1
    bool beside = false;  // rule 3: an edge of the element lies on a face of a crack of the run
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1] && !beside; ++v)
      beside = (mesh.loop_edge_origin[static_cast<std::size_t>(v)] & kEdgeJoint) != 0 &&
               mesh.loop_edge_joint[static_cast<std::size_t>(v)] >= static_cast<std::int32_t>(first_crack);
    if (beside) {
      may[e] = 0;
      continue;
    }
    if (element_area(mesh, e) < Fracture::kDebrisArea * mesh.mesh_size * mesh.mesh_size) may[e] &= kMayBeReached;  // rule 5
    if (!known) continue;
    const StrengthDef& st = scene.materials[static_cast<std::size_t>(scene.bodies[static_cast<std::size_t>(body)].material)].strength;
    const double r_end = rock_failure(st, end[3 * e], end[3 * e + 1], end[3 * e + 2]).ratio;
    if (r_end < 1) continue;  // not a candidate anyway
    const double r_start = rock_failure(st, begin[3 * e], begin[3 * e + 1], begin[3 * e + 2]).ratio;
    if (!(r_end > r_start)) may[e] = 0;  // rule 2: unloading
  }
  return may;
}

bool in_crack_band(const Mesh& mesh, std::size_t e, const Vec2& tip, const Vec2& dir, double half_width, double reach,
                   double& along) {
  const Vec2 c = inside_point(mesh, e);  // where a new crack in it would start
  along = (c.x - tip.x) * dir.x + (c.y - tip.y) * dir.y;
  if (!(along > 0 && along <= reach)) return false;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v) {
    const double x = mesh.loop_xy[2 * static_cast<std::size_t>(v)] - tip.x,
                 y = mesh.loop_xy[2 * static_cast<std::size_t>(v) + 1] - tip.y;
    const double l = -dir.y * x + dir.x * y;
    lo = std::min(lo, l), hi = std::max(hi, l);
  }
  return lo < half_width && hi > -half_width;
}

}  // namespace nmm::solve
