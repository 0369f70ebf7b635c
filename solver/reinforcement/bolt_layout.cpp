// Where the bolts are: see bolt_layout.h.
#include "solver/reinforcement/bolt_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/ring_geometry.h"
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

/// m, how deep p lies in element e's loop as cut: its distance to the loop, negative outside.
double depth_in(const Mesh& mesh, std::int32_t e, const Vec2& p) {
  const std::size_t b = static_cast<std::size_t>(mesh.element_loop_offset[static_cast<std::size_t>(e)]);
  const std::size_t n = static_cast<std::size_t>(mesh.element_loop_offset[static_cast<std::size_t>(e) + 1]) - b;
  const double* xy = mesh.loop_xy.data() + 2 * b;
  const double d = distance_to_loop(xy, n, p.x, p.y);
  return point_in_loop(xy, n, p.x, p.y) ? d : -d;
}

/// A face of element e of `now` that the re-cut made a joint face (a crack's: not one of `old`,
/// whose vertex it came from is vertex_parent's) passes within tol of p (as cut).
bool crack_face_near(const Mesh& old, const Mesh& mesh, const std::vector<std::int32_t>& vertex_parent, std::int32_t e,
                     const Vec2& p, double tol) {
  const auto b = static_cast<std::size_t>(mesh.element_loop_offset[static_cast<std::size_t>(e)]);
  const auto end = static_cast<std::size_t>(mesh.element_loop_offset[static_cast<std::size_t>(e) + 1]);
  for (std::size_t v = b; v < end; ++v) {
    const std::int32_t was = vertex_parent[v];
    if (mesh.loop_edge_joint[v] < 0 || (was >= 0 && old.loop_edge_joint[static_cast<std::size_t>(was)] >= 0)) continue;
    const std::size_t u = v + 1 < end ? v + 1 : b;
    const double edge[4] = {mesh.loop_xy[2 * v], mesh.loop_xy[2 * v + 1], mesh.loop_xy[2 * u], mesh.loop_xy[2 * u + 1]};
    if (distance_to_loop(edge, 2, p.x, p.y) <= tol) return true;
  }
  return false;
}

/// The element of `now` a bolt point p as cut is tied to: p was in element `was` of `old`, whose
/// pieces are `pieces`; `toward`: as cut, the point the bolt runs to from it (retie_bolts).
std::int32_t piece_for(const Mesh& old, std::int32_t was, const Mesh& now, const std::vector<std::int32_t>& vertex_parent,
                       const std::vector<std::int32_t>& pieces, const Vec2& p, const Vec2& toward) {
  const double tol = 1e-9 * now.mesh_size;
  std::vector<std::int32_t> near = pieces;
  // A point on its element's edge may lie on a crack cut along that edge: the elements across it
  // are candidates too (found by a scan: only for such points).
  if (depth_in(old, was, p) <= tol)
    for (std::size_t e = 0; e < now.element_count(); ++e) {
      const auto ei = static_cast<std::int32_t>(e);
      if (std::find(near.begin(), near.end(), ei) == near.end() && depth_in(now, ei, p) >= -tol) near.push_back(ei);
    }
  std::int32_t best = -1;
  double deepest = -std::numeric_limits<double>::infinity();
  for (const std::int32_t e : pieces)
    if (const double d = depth_in(now, e, p); d > deepest) deepest = d, best = e;
  // A crack through p: a face the re-cut made a joint face, of an element within tol of p, passes
  // within tol of it. The rock the bolt runs into decides; elsewhere (p on a mesh edge or an
  // earlier joint) the piece of its own element that holds it, as before the re-cut.
  if (deepest > tol) return best;
  near.erase(std::remove_if(near.begin(), near.end(), [&](std::int32_t e) { return depth_in(now, e, p) < -tol; }),
             near.end());
  if (near.size() < 2 ||
      std::none_of(near.begin(), near.end(), [&](std::int32_t e) { return crack_face_near(old, now, vertex_parent, e, p, tol); }))
    return best;
  const double dx = toward.x - p.x, dy = toward.y - p.y, l = std::hypot(dx, dy);
  if (!(l > 0)) return best;
  const double step = 1e-6 * now.mesh_size;
  const Vec2 probe{p.x + step * dx / l, p.y + step * dy / l};
  deepest = -std::numeric_limits<double>::infinity();
  for (const std::int32_t e : near)
    if (const double d = depth_in(now, e, probe); d > deepest) deepest = d, best = e;
  return best;
}

}  // namespace

void retie_bolts(const Mesh& old, const Mesh& now, const std::vector<std::int32_t>& element_parent,
                 const std::vector<std::int32_t>& vertex_parent, std::vector<BoltState>& bolts) {
  std::vector<std::vector<std::int32_t>> pieces(old.element_count());
  for (std::size_t e = 0; e < element_parent.size(); ++e)
    pieces[static_cast<std::size_t>(element_parent[e])].push_back(static_cast<std::int32_t>(e));
  for (BoltState& b : bolts) {
    // Decided on the points as they were before any is moved to its piece.
    std::vector<std::int32_t> tied(b.nodes.size());
    for (std::size_t k = 0; k < b.nodes.size(); ++k) {
      const TrackedPoint& p = b.nodes[k];
      const TrackedPoint& q = b.nodes[k + 1 < b.nodes.size() ? k + 1 : k - 1];
      const std::vector<std::int32_t>& of = pieces[static_cast<std::size_t>(p.element)];
      tied[k] = of.empty() ? locate_point(now, now.loop_xy, {p.x0, p.y0}).element
                           : piece_for(old, p.element, now, vertex_parent, of, {p.x0, p.y0}, {q.x0, q.y0});
    }
    for (std::size_t k = 0; k < b.nodes.size(); ++k) b.nodes[k].element = tied[k];
  }
}

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
