// Where the bolts are: see bolt_layout.h.
#include "solver/reinforcement/bolt_layout.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.h"
#include "solver/discretisation/excavation.h"
#include "solver/discretisation/point_location.h"

namespace nmm::solve {

namespace {

/// The scene's bolt is the one this state was installed for.
bool same_bolt(const BoltDef& d, const BoltState& b) {
  return b.type == static_cast<std::uint8_t>(d.type) && b.ax == d.a.x && b.ay == d.a.y && b.bx == d.b.x &&
         b.by == d.b.y;
}

/// Moves a material point given where it was in the mesh as cut (p.x0, p.y0, in element
/// p.element) to where that point of the rock is in state s. At cover order 0 every step moves an
/// element affinely, so the point keeps its barycentric coordinates λ_k in the triangle of its
/// element's cover nodes: x = x0 + Σ λ_k·(x_k − x_k,0), exact (and x = x0 at step 0); at higher
/// orders the same is the nodes' share of the motion, within the element's curvature of it.
void carried_to_now(const Mesh& mesh, const RunState& s, TrackedPoint& p) {
  const std::int32_t* ec = &mesh.element_covers[3 * static_cast<std::size_t>(p.element)];
  double x[3], y[3], dx[3], dy[3];
  for (int k = 0; k < 3; ++k) {
    const std::size_t node = static_cast<std::size_t>(mesh.cover_node[static_cast<std::size_t>(ec[k])]);
    x[k] = mesh.node_xy[2 * node];
    y[k] = mesh.node_xy[2 * node + 1];
    dx[k] = s.cover_xy[2 * static_cast<std::size_t>(ec[k])] - x[k];
    dy[k] = s.cover_xy[2 * static_cast<std::size_t>(ec[k]) + 1] - y[k];
  }
  const double twice = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  if (!(std::abs(twice) > 0)) return;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double lambda = ((x[i] - p.x0) * (y[j] - p.y0) - (x[j] - p.x0) * (y[i] - p.y0)) / twice;
    p.x += lambda * dx[k];
    p.y += lambda * dy[k];
  }
}

/// Bolt i of the scene installed at state s: each point tied to the element that held it in the
/// mesh as cut, at that point of the rock's position now.
BoltState install(const SceneDef& scene, std::size_t i, const Mesh& mesh, const RunState& s,
                  const std::vector<std::uint8_t>& removed, const std::string& scene_name) {
  const BoltDef& d = scene.bolts[i];
  BoltState b;
  b.type = static_cast<std::uint8_t>(d.type);
  b.ax = d.a.x;
  b.ay = d.a.y;
  b.bx = d.b.x;
  b.by = d.b.y;
  b.installed_step = s.step;
  const int n = bolt_segments(d, mesh.mesh_size);
  for (int k = 0; k <= n; ++k) {
    const double f = static_cast<double>(k) / n;
    const Vec2 p{d.a.x + f * (d.b.x - d.a.x), d.a.y + f * (d.b.y - d.a.y)};
    const PointLocation at = locate_point(mesh, mesh.loop_xy, p, &removed);
    if (at.element < 0 || at.distance > 1e-6 * mesh.mesh_size) {
      std::ostringstream os;
      os << (k == 0 || k == n ? "its end " : "its segment point ") << "(" << p.x << ", " << p.y
         << ") lies outside the rock" << (std::any_of(removed.begin(), removed.end(), [](std::uint8_t r) { return r != 0; })
                                             ? " (outside every body, or in an excavated one)"
                                             : " (outside every body)")
         << "; a bolt is tied to the rock along its whole length";
      throw InputError(scene_name, "/bolts/" + std::to_string(i) + "/points", os.str());
    }
    b.nodes.push_back(TrackedPoint{at.element, p.x, p.y, p.x, p.y});
    carried_to_now(mesh, s, b.nodes.back());
  }
  b.axial.assign(static_cast<std::size_t>(n), d.type == BoltType::anchored ? d.pretension : 0.0);
  if (d.type == BoltType::grouted) {
    b.slip.assign(b.nodes.size(), 0.0);
    b.bond.assign(b.nodes.size(), 0.0);
  }
  b.max_axial = std::abs(b.axial[0]);
  return b;
}

}  // namespace

double installed_length(const TrackedPoint& a, const TrackedPoint& b) { return std::hypot(b.x0 - a.x0, b.y0 - a.y0); }

double tributary_length(const std::vector<TrackedPoint>& points, std::size_t i) {
  return 0.5 * ((i > 0 ? installed_length(points[i - 1], points[i]) : 0.0) +
                (i + 1 < points.size() ? installed_length(points[i], points[i + 1]) : 0.0));
}

int bolt_segments(const BoltDef& bolt, double mesh_size) {
  if (bolt.type == BoltType::anchored) return 1;
  if (bolt.segments > 0) return bolt.segments;
  const double length = std::hypot(bolt.b.x - bolt.a.x, bolt.b.y - bolt.a.y);
  const double lambda = std::sqrt(bolt.bond_stiffness / bolt.ea);  // 1/m
  const double n = std::max(2.0 * length / mesh_size, 2.0 * lambda * length);
  return static_cast<int>(std::clamp(std::ceil(n), 2.0, 1000.0));
}

std::vector<BoltState> bolts_for_run(const SceneDef& scene, const Mesh& mesh, const RunState& s,
                                     const std::vector<BoltState>& previous, const std::string& scene_name) {
  const std::vector<std::uint8_t> removed = removed_elements(mesh, s);
  std::vector<BoltState> out;
  for (std::size_t i = 0; i < scene.bolts.size(); ++i) {
    if (i < previous.size() && same_bolt(scene.bolts[i], previous[i]))
      out.push_back(previous[i]);
    else
      out.push_back(install(scene, i, mesh, s, removed, scene_name));
  }
  return out;
}

}  // namespace nmm::solve
