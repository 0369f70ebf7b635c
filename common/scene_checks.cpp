// Scene usability checks: see scene_checks.h.
//
// Point in polygon: even–odd ray casting (ring_geometry.h); a point within `tol` of an edge
// counts as inside.
// Segment–body: some part of segment ab lies in the body iff an end lies in it or ab crosses
// one of its boundary edges (outer or hole) — a crossing puts points on both sides, one of
// them inside.
#include "common/scene_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "common/number_format.h"
#include "common/ring_geometry.h"

namespace nmm {
namespace {

double dist_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

bool on_ring(const Ring& r, Vec2 p, double tol) {
  for (std::size_t i = 0; i < r.size(); ++i)
    if (dist_to_segment(p, r[i], r[(i + 1) % r.size()]) <= tol) return true;
  return false;
}

double cross(Vec2 o, Vec2 a, Vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 &&
         d4 != 0;
}

double ring_perimeter(const Ring& r) {
  double s = 0;
  for (std::size_t i = 0; i < r.size(); ++i)
    s += std::hypot(r[(i + 1) % r.size()].x - r[i].x, r[(i + 1) % r.size()].y - r[i].y);
  return s;
}

double scene_size(const SceneDef& scene) { return bodies_box(scene.bodies).longer_side(); }

std::string coords(Vec2 p) { return "(" + format_rough(p.x, 6) + ", " + format_rough(p.y, 6) + ")"; }

}  // namespace

bool point_in_body(const BodyDef& body, Vec2 p, double tol) {
  if (on_ring(body.outer, p, tol)) return true;
  if (!point_in_ring(body.outer, p)) return false;
  for (const Ring& h : body.holes)
    if (!on_ring(h, p, tol) && point_in_ring(h, p)) return false;
  return true;
}

bool polyline_touches_body(const BodyDef& body, const std::vector<Vec2>& line, double tol) {
  for (const Vec2& p : line)
    if (point_in_body(body, p, tol)) return true;
  auto crosses = [&](const Ring& r, Vec2 a, Vec2 b) {
    for (std::size_t i = 0; i < r.size(); ++i)
      if (segments_cross(a, b, r[i], r[(i + 1) % r.size()])) return true;
    return false;
  };
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    if (crosses(body.outer, line[i], line[i + 1])) return true;
    for (const Ring& h : body.holes)
      if (crosses(h, line[i], line[i + 1])) return true;
  }
  return false;
}

double body_inradius_estimate(const BodyDef& body) {
  double area = ring_area(body.outer), perimeter = ring_perimeter(body.outer);
  for (const Ring& h : body.holes) area -= ring_area(h), perimeter += ring_perimeter(h);
  return perimeter > 0 ? 2 * area / perimeter : 0;
}

std::vector<std::string> check_scene_usability(const SceneDef& scene, const std::string& file,
                                               bool allow_stray_joints) {
  std::vector<std::string> warnings;
  const double tol = 1e-9 * scene_size(scene);
  auto in_some_body = [&](Vec2 p) {
    for (const BodyDef& b : scene.bodies)
      if (point_in_body(b, p, tol)) return true;
    return false;
  };
  auto check_point = [&](Vec2 p, const std::string& where, const char* what) {
    if (!in_some_body(p))
      throw InputError(file, where,
                       std::string(what) + " " + coords(p) +
                           " lies outside every body (it must lie in a body or on its boundary)");
  };
  for (std::size_t i = 0; i < scene.fixed_points.size(); ++i)
    check_point(scene.fixed_points[i], "/fixed_points/" + std::to_string(i), "fixed point");
  for (std::size_t i = 0; i < scene.loads.size(); ++i)
    check_point(scene.loads[i].point, "/loads/" + std::to_string(i) + "/point", "load point");
  for (std::size_t i = 0; i < scene.measure_points.size(); ++i)
    check_point(scene.measure_points[i], "/measure_points/" + std::to_string(i), "measure point");
  for (std::size_t i = 0; i < scene.bolts.size(); ++i) {
    const std::string at = "/bolts/" + std::to_string(i) + "/points/";
    check_point(scene.bolts[i].a, at + "0", "bolt end");
    check_point(scene.bolts[i].b, at + "1", "bolt end");
  }

  for (std::size_t j = 0; j < scene.joints.size(); ++j) {
    const JointDef& joint = scene.joints[j];
    bool touches = false;
    for (const BodyDef& b : scene.bodies) touches = touches || polyline_touches_body(b, joint.points, tol);
    if (touches) continue;
    const std::string where = "/joints/" + std::to_string(j);
    const std::string set =
        joint.set >= 0 && joint.set < static_cast<int>(scene.joint_sets.size())
            ? " (set '" + scene.joint_sets[joint.set].name + "')"
            : "";
    const std::string what = "joint " + std::to_string(j) + set + " from " +
                             coords(joint.points.front()) + " to " + coords(joint.points.back()) +
                             " touches no body";
    if (!allow_stray_joints)
      throw InputError(file, where, what + " (a coordinate typo?)");
    warnings.push_back(file + ": " + where + ": warning: " + what + "; it is ignored (a coordinate typo?)");
  }

  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const double r = body_inradius_estimate(scene.bodies[b]);
    if (scene.mesh_size > r) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "warning: mesh size %.4g m is larger than body %zu's inradius (at most %.4g m): "
                    "it gets only a few elements and cannot bend; use mesh.size <= %.3g",
                    scene.mesh_size, b, r, 0.5 * r);
      warnings.push_back(file + ": /mesh/size: " + buf);
    }
  }
  return warnings;
}

}  // namespace nmm
