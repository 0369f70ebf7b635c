// Where a new crack may start in rock that softens: the rules in cohesive_starts.h.
//
// Rule 2 compares the strength ratio r = max(σ1/σt, (p1 − Nφ·p3)/(2c·√Nφ)) (rock_strength.h) of
// the element's stress at the step's solution with the one at its start: r_end > r_start loads.
// Rule 4's band: with t the tip, d its unit direction and n = (−d_y, d_x), a point p lies at
// a = (p − t)·d ahead and l = (p − t)·n across; the element meets the strip |l| < w where its
// vertices' l do not all lie on one side beyond it.
#include "solver/fracture/cohesive_starts.h"

#include <algorithm>
#include <utility>
#include <cmath>
#include <limits>

#include "common/ring_geometry.h"
#include "solver/contact/cohesive_law.h"
#include "solver/discretisation/stress_field.h"
#include "solver/fracture/element_geometry.h"
#include "solver/fracture/fracture.h"
#include "solver/fracture/rock_strength.h"

namespace nmm::solve {

namespace {
// m, the distance from p to the segment a–b.
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / l2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// The reflex corners of the bodies' outlines (interior angle above 180°: a notch's or slot's end),
// where the body's rock wraps round a gap, each with the unit bisector of its angle into the body.
std::vector<std::pair<Vec2, Vec2>> reflex_corners(const SceneDef& scene) {
  std::vector<std::pair<Vec2, Vec2>> out;
  auto unit = [](double x, double y) {
    const double l = std::hypot(x, y);
    return Vec2{x / l, y / l};
  };
  auto add = [&](const Ring& r, double body_side) {  // body_side: +1 the body inside r, −1 outside
    const double turn = ring_area(r) > 0 ? body_side : -body_side;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Vec2& p = r[(i + r.size() - 1) % r.size()];
      const Vec2& q = r[i];
      const Vec2& u = r[(i + 1) % r.size()];
      if (!(turn * ((q.x - p.x) * (u.y - q.y) - (q.y - p.y) * (u.x - q.x)) < 0)) continue;
      // The two edges' directions away from q sum to a vector into the gap; the body's side is
      // the other way.
      const Vec2 a = unit(p.x - q.x, p.y - q.y), b = unit(u.x - q.x, u.y - q.y);
      out.push_back({q, unit(-(a.x + b.x), -(a.y + b.y))});
    }
  };
  for (const BodyDef& b : scene.bodies) {
    add(b.outer, 1);
    for (const Ring& h : b.holes) add(h, -1);
  }
  return out;
}

// Segments p–q and a–b cross at a point inside both (not at an end, not collinear).
bool cross(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  auto side = [](const Vec2& o, const Vec2& d, const Vec2& r) {
    return (d.x - o.x) * (r.y - o.y) - (d.y - o.y) * (r.x - o.x);
  };
  const double s1 = side(p, q, a), s2 = side(p, q, b), s3 = side(a, b, p), s4 = side(a, b, q);
  return ((s1 > 0 && s2 < 0) || (s1 < 0 && s2 > 0)) && ((s3 > 0 && s4 < 0) || (s3 < 0 && s4 > 0));
}

// Rule 7: [me] 1 for an element that holds a physical cover reaching round a gap of the body
// (two of the cover's elements see each other only across a body boundary edge of one of its
// elements) and has no reflex corner of the outline on its loop, 2 for one that has.
std::vector<std::uint8_t> covers_round_a_gap(const Mesh& mesh, const SceneDef& scene) {
  const std::size_t n = mesh.element_count(), covers = mesh.cover_count();
  std::vector<std::size_t> first(covers + 1, 0);
  for (std::size_t e = 0; e < n; ++e)
    for (std::size_t k = 0; k < 3; ++k)
      if (mesh.element_covers[3 * e + k] >= 0) ++first[static_cast<std::size_t>(mesh.element_covers[3 * e + k]) + 1];
  for (std::size_t c = 0; c < covers; ++c) first[c + 1] += first[c];
  std::vector<std::size_t> held(first.back()), fill(first.begin(), first.end() - 1);
  for (std::size_t e = 0; e < n; ++e)
    for (std::size_t k = 0; k < 3; ++k)
      if (mesh.element_covers[3 * e + k] >= 0) held[fill[static_cast<std::size_t>(mesh.element_covers[3 * e + k])]++] = e;
  auto vertex = [&](std::int32_t v) {
    return Vec2{mesh.loop_xy[2 * static_cast<std::size_t>(v)], mesh.loop_xy[2 * static_cast<std::size_t>(v) + 1]};
  };
  auto next = [&](std::size_t el, std::int32_t v) { return v + 1 < mesh.element_loop_offset[el + 1] ? v + 1 : mesh.element_loop_offset[el]; };
  std::vector<std::uint8_t> tied(n, 0);
  std::vector<Vec2> ea, eb, at;
  for (std::size_t c = 0; c < covers; ++c) {
    ea.clear(), eb.clear(), at.clear();
    for (std::size_t i = first[c]; i < first[c + 1]; ++i) {
      const std::size_t e = held[i];
      at.push_back(inside_point(mesh, e));
      for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v)
        if (mesh.loop_edge_origin[static_cast<std::size_t>(v)] & kEdgeBoundary) ea.push_back(vertex(v)), eb.push_back(vertex(next(e, v)));
    }
    if (ea.empty()) continue;
    bool wraps = false;
    for (std::size_t i = 0; i < at.size() && !wraps; ++i)
      for (std::size_t j = i + 1; j < at.size() && !wraps; ++j)
        for (std::size_t k = 0; k < ea.size() && !wraps; ++k) wraps = cross(at[i], at[j], ea[k], eb[k]);
    if (wraps)
      for (std::size_t i = first[c]; i < first[c + 1]; ++i) tied[held[i]] = 1;
  }
  const auto corners = reflex_corners(scene);
  const double tol = 1e-9 * mesh.mesh_size;
  for (std::size_t e = 0; e < n; ++e) {
    if (!tied[e]) continue;
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1] && tied[e]; ++v)
      for (const auto& [q, bisector] : corners)
        if (std::abs(vertex(v).x - q.x) <= tol && std::abs(vertex(v).y - q.y) <= tol) {
          tied[e] = 2;  // the gap's end: where its concentration breaks the rock
          break;
        }
  }
  return tied;
}
}  // namespace

std::vector<std::uint8_t> cohesive_starts(const Mesh& mesh, const SceneDef& scene, const RunState& start,
                                          const RunState& solved, bool started_this_step, std::size_t first_crack,
                                          const std::vector<CrackSegment>& cracks) {
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
  const std::vector<std::uint8_t> tied = covers_round_a_gap(mesh, scene);  // rule 7
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
    Vec2 gap_at, gap_dir;
    if (tied[e] == 1) {  // rule 7: its stress is the gap's end's, smeared: a start there or none
      if (gap_end(mesh, scene, e, gap_at, gap_dir))
        may[e] |= kGapEnd | kGapOnly;
      else
        may[e] &= kMayBeReached;
    }
    if (tied[e] == 2) may[e] |= kGapEnd;
    if (!known) continue;
    const StrengthDef& st = scene.materials[static_cast<std::size_t>(scene.bodies[static_cast<std::size_t>(body)].material)].strength;
    const double r_end = rock_failure(st, end[3 * e], end[3 * e + 1], end[3 * e + 2]).ratio;
    if (r_end < 1) continue;  // not a candidate anyway
    const double r_start = rock_failure(st, begin[3 * e], begin[3 * e + 1], begin[3 * e + 2]).ratio;
    if (!(r_end > r_start)) {
      may[e] = 0;  // rule 2: unloading
      continue;
    }
    // Rule 6: within l_ch of a growing crack the element is that crack's to reach (rule 4)
    // or shielded by it, never the start of another.
    if (may[e] & kMayStart) {
      const MaterialDef& mat = scene.materials[static_cast<std::size_t>(scene.bodies[static_cast<std::size_t>(body)].material)];
      const double reach = characteristic_length(mat.young, mat.strength);
      const Vec2 c = inside_point(mesh, e);
      for (const CrackSegment& seg : cracks)
        if (distance_to_segment(c, seg.a, seg.b) < reach) {
          may[e] &= kMayBeReached;
          break;
        }
    }
  }
  return may;
}

bool gap_end(const Mesh& mesh, const SceneDef& scene, std::size_t e, Vec2& at, Vec2& dir) {
  const double tol = 1e-9 * mesh.mesh_size;
  const auto corners = reflex_corners(scene);
  std::vector<std::uint8_t> in(corners.size(), 0);
  for (std::size_t i = 0; i < corners.size(); ++i)
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1] && !in[i]; ++v)
      in[i] = std::hypot(mesh.loop_xy[2 * static_cast<std::size_t>(v)] - corners[i].first.x,
                         mesh.loop_xy[2 * static_cast<std::size_t>(v) + 1] - corners[i].first.y) <= mesh.mesh_size + tol;
  // The gap's end: e's corners and every reflex corner within an element's size of one of them
  // (both corners of a slot narrower than h, which the covers reach round together).
  double x = 0, y = 0, dx = 0, dy = 0;
  int k = 0;
  for (std::size_t j = 0; j < corners.size(); ++j) {
    bool near = false;
    for (std::size_t i = 0; i < corners.size() && !near; ++i)
      near = in[i] && std::hypot(corners[j].first.x - corners[i].first.x, corners[j].first.y - corners[i].first.y) <=
                          mesh.mesh_size;
    if (!near) continue;
    x += corners[j].first.x, y += corners[j].first.y, dx += corners[j].second.x, dy += corners[j].second.y, ++k;
  }
  const double l = std::hypot(dx, dy);
  if (k == 0 || !(l > 0)) return false;
  at = {x / k, y / k};
  dir = {dx / l, dy / l};
  return true;
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
