// The flow network of a run: see flow_network.h (equations there).
//
// Nodes are the loop vertices of the joint faces merged by position (within 1e-6·h, as the
// boundary polylines are matched: boundary_conditions.h): the two faces of a joint are cut at the
// same points, so each division point becomes one node. A segment is a pair of nodes on one joint
// (both faces' edges between them give the same segment). Numbering follows the elements' loops,
// so the same mesh always gives the same network.
#include "solver/flow/flow_network.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

#include "common/error.h"
#include "common/number_format.h"
#include "solver/discretisation/boundary_conditions.h"

namespace nmm::solve {

namespace {

// Points merged within `tol` through a grid of cells of that size (the 3 × 3 cells around).
class PointIndex {
 public:
  explicit PointIndex(double tol) : tol_(tol) {}
  std::int32_t find(double x, double y, const std::vector<double>& xy) const {
    const long long cx = std::llround(x / tol_), cy = std::llround(y / tol_);
    for (long long i = cx - 1; i <= cx + 1; ++i)
      for (long long j = cy - 1; j <= cy + 1; ++j) {
        const auto it = cells_.find({i, j});
        if (it == cells_.end()) continue;
        for (std::int32_t n : it->second)
          if (std::hypot(xy[2 * static_cast<std::size_t>(n)] - x, xy[2 * static_cast<std::size_t>(n) + 1] - y) <= tol_)
            return n;
      }
    return -1;
  }
  void add(double x, double y, std::int32_t n) { cells_[{std::llround(x / tol_), std::llround(y / tol_)}].push_back(n); }

 private:
  double tol_;
  std::map<std::pair<long long, long long>, std::vector<std::int32_t>> cells_;
};

double distance_to_segment(double px, double py, double ax, double ay, double bx, double by, double& t) {
  const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
  t = l2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / l2, 0.0, 1.0) : 0.0;
  return std::hypot(ax + t * dx - px, ay + t * dy - py);
}

}  // namespace

FlowNetwork::FlowNetwork(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name) {
  const double tol = 1e-6 * mesh.mesh_size;
  PointIndex index(tol);
  auto node_at = [&](std::int32_t v) {
    const double x = mesh.loop_xy[2 * static_cast<std::size_t>(v)], y = mesh.loop_xy[2 * static_cast<std::size_t>(v) + 1];
    std::int32_t n = index.find(x, y, node_xy_);
    if (n >= 0) return n;
    n = static_cast<std::int32_t>(node_boundary_.size());
    node_xy_.push_back(x);
    node_xy_.push_back(y);
    node_boundary_.push_back(-1);
    index.add(x, y, n);
    return n;
  };
  std::map<std::tuple<std::int32_t, std::int32_t, std::int32_t>, std::int32_t> segment_of;
  std::vector<std::vector<FlowFaceVertex>> at_end;  // [2·segment + end]
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::int32_t first = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
    for (std::int32_t v = first; v < end; ++v) {
      const std::uint8_t o = mesh.loop_edge_origin[static_cast<std::size_t>(v)];
      if ((o & kEdgeJoint) == 0 || (o & kEdgeBridge) != 0) continue;
      const std::int32_t next = v + 1 < end ? v + 1 : first;
      const std::int32_t na = node_at(v), nb = node_at(next);
      if (na == nb) continue;  // an edge of no length
      const std::int32_t joint = mesh.loop_edge_joint[static_cast<std::size_t>(v)];
      const auto key = std::make_tuple(std::min(na, nb), std::max(na, nb), joint);
      auto it = segment_of.find(key);
      if (it == segment_of.end()) {
        FlowSegment sg;
        sg.a = std::min(na, nb);
        sg.b = std::max(na, nb);
        sg.joint = joint;
        const double dx = node_xy_[2 * static_cast<std::size_t>(sg.b)] - node_xy_[2 * static_cast<std::size_t>(sg.a)];
        const double dy = node_xy_[2 * static_cast<std::size_t>(sg.b) + 1] - node_xy_[2 * static_cast<std::size_t>(sg.a) + 1];
        sg.length = std::hypot(dx, dy);
        sg.nx = -dy / sg.length;
        sg.ny = dx / sg.length;
        it = segment_of.emplace(key, static_cast<std::int32_t>(segments_.size())).first;
        segments_.push_back(sg);
        at_end.resize(2 * segments_.size());
      }
      const std::int32_t s = it->second;
      const bool reversed = na != segments_[static_cast<std::size_t>(s)].a;
      // The element lies left of its CCW edge vertex → next: on the +n side when the edge runs a → b.
      const std::int8_t side = reversed ? -1 : 1;
      faces_.push_back({static_cast<std::int32_t>(e), v, next, s, reversed});
      at_end[2 * static_cast<std::size_t>(s)].push_back({reversed ? next : v, side});
      at_end[2 * static_cast<std::size_t>(s) + 1].push_back({reversed ? v : next, side});
    }
  }
  end_offset_.push_back(0);
  for (const auto& list : at_end) {
    end_vertices_.insert(end_vertices_.end(), list.begin(), list.end());
    end_offset_.push_back(static_cast<std::int32_t>(end_vertices_.size()));
  }

  const FlowDef& flow = scene.flow;
  for (std::size_t i = 0; i < flow.boundaries.size(); ++i) {
    const std::string path = "/flow/boundaries/" + std::to_string(i) + "/points";
    bool reached = false;
    for (const BoundaryEdge& be : edges_under(mesh, flow.boundaries[i].points, scene_name, path))
      for (std::int32_t v : {be.vertex, be.next}) {
        const std::int32_t n = index.find(mesh.loop_xy[2 * static_cast<std::size_t>(v)],
                                          mesh.loop_xy[2 * static_cast<std::size_t>(v) + 1], node_xy_);
        if (n < 0) continue;
        reached = true;
        if (node_boundary_[static_cast<std::size_t>(n)] < 0) node_boundary_[static_cast<std::size_t>(n)] = static_cast<std::int32_t>(i);
      }
    // In a run that can crack, a crack may reach it later (docs/flow.md "Hydraulic fracturing").
    if (!reached && !scene.fracture.present)
      throw InputError(scene_name, path, "no joint reaches the body boundary under the polyline");
  }
  for (std::size_t i = 0; i < flow.injections.size(); ++i) {
    const Vec2 p = flow.injections[i].point;
    double best = std::numeric_limits<double>::infinity(), best_t = 0;
    std::size_t best_s = 0;
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      const FlowSegment& sg = segments_[s];
      double t = 0;
      const double d = distance_to_segment(p.x, p.y, node_xy_[2 * static_cast<std::size_t>(sg.a)],
                                           node_xy_[2 * static_cast<std::size_t>(sg.a) + 1],
                                           node_xy_[2 * static_cast<std::size_t>(sg.b)],
                                           node_xy_[2 * static_cast<std::size_t>(sg.b) + 1], t);
      if (d < best) {
        best = d;
        best_t = t;
        best_s = s;
      }
    }
    if (!(best <= mesh.mesh_size))
      throw InputError(scene_name, "/flow/injections/" + std::to_string(i) + "/point",
                       "no joint within the mesh size (" + format_number(mesh.mesh_size) + " m) of the point");
    injection_shares_.push_back({segments_[best_s].a, segments_[best_s].b, 1 - best_t, best_t});
  }
}

std::vector<double> FlowNetwork::separations(const std::vector<double>& loop_u) const {
  std::vector<double> w(2 * segments_.size(), 0.0);
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const FlowSegment& sg = segments_[s];
    for (std::size_t end = 0; end < 2; ++end) {
      double up[2] = {0, 0}, um[2] = {0, 0};
      int np = 0, nm = 0;
      for (std::int32_t k = end_offset_[2 * s + end]; k < end_offset_[2 * s + end + 1]; ++k) {
        const FlowFaceVertex& fv = end_vertices_[static_cast<std::size_t>(k)];
        double* u = fv.side > 0 ? up : um;
        u[0] += loop_u[2 * static_cast<std::size_t>(fv.vertex)];
        u[1] += loop_u[2 * static_cast<std::size_t>(fv.vertex) + 1];
        ++(fv.side > 0 ? np : nm);
      }
      if (np == 0 || nm == 0) continue;  // one face only: no separation to measure
      w[2 * s + end] = (up[0] / np - um[0] / nm) * sg.nx + (up[1] / np - um[1] / nm) * sg.ny;
    }
  }
  return w;
}

std::vector<double> FlowNetwork::apertures(const std::vector<double>& loop_u, double residual, double max) const {
  std::vector<double> ap = separations(loop_u);
  for (double& a : ap) a = std::min(max, residual + std::max(0.0, a));
  return ap;
}

std::vector<double> FlowNetwork::volumes(const std::vector<double>& ap) const {
  std::vector<double> v(nodes(), 0.0);
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const FlowSegment& sg = segments_[s];
    const double a1 = ap[2 * s], a2 = ap[2 * s + 1];
    v[static_cast<std::size_t>(sg.a)] += 0.5 * sg.length * (3 * a1 + a2) / 4;
    v[static_cast<std::size_t>(sg.b)] += 0.5 * sg.length * (a1 + 3 * a2) / 4;
  }
  return v;
}

std::vector<double> FlowNetwork::conductances(const std::vector<double>& ap, double viscosity) const {
  std::vector<double> c(segments_.size());
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const double a1 = ap[2 * s], a2 = ap[2 * s + 1];
    c[s] = a1 * a1 * a2 * a2 / (6 * viscosity * segments_[s].length * (a1 + a2));
  }
  return c;
}

std::vector<double> FlowNetwork::face_pressures(const std::vector<double>& p, std::size_t loop_vertices) const {
  std::vector<double> out(2 * loop_vertices, 0.0);
  if (p.size() != nodes()) return out;
  for (const FlowFace& f : faces_) {
    const FlowSegment& sg = segments_[static_cast<std::size_t>(f.segment)];
    const auto v = static_cast<std::size_t>(f.vertex);
    out[2 * v] = p[static_cast<std::size_t>(f.reversed ? sg.b : sg.a)];
    out[2 * v + 1] = p[static_cast<std::size_t>(f.reversed ? sg.a : sg.b)];
  }
  return out;
}

std::vector<double> FlowNetwork::node_apertures(const std::vector<double>& ap) const {
  std::vector<double> sum(nodes(), 0.0), count(nodes(), 0.0);
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    for (std::size_t end = 0; end < 2; ++end) {
      const auto n = static_cast<std::size_t>(end == 0 ? segments_[s].a : segments_[s].b);
      sum[n] += ap[2 * s + end];
      count[n] += 1;
    }
  }
  for (std::size_t n = 0; n < sum.size(); ++n) sum[n] = count[n] > 0 ? sum[n] / count[n] : 0.0;
  return sum;
}

std::vector<double> FlowNetwork::node_displacements(const std::vector<double>& loop_u) const {
  std::vector<double> sum(2 * nodes(), 0.0), count(nodes(), 0.0);
  for (std::size_t s = 0; s < segments_.size(); ++s)
    for (std::size_t end = 0; end < 2; ++end) {
      const auto n = static_cast<std::size_t>(end == 0 ? segments_[s].a : segments_[s].b);
      for (std::int32_t k = end_offset_[2 * s + end]; k < end_offset_[2 * s + end + 1]; ++k) {
        const auto v = static_cast<std::size_t>(end_vertices_[static_cast<std::size_t>(k)].vertex);
        sum[2 * n] += loop_u[2 * v];
        sum[2 * n + 1] += loop_u[2 * v + 1];
        count[n] += 1;
      }
    }
  for (std::size_t n = 0; n < count.size(); ++n)
    if (count[n] > 0) {
      sum[2 * n] /= count[n];
      sum[2 * n + 1] /= count[n];
    }
  return sum;
}

}  // namespace nmm::solve
