// Boundary edges under polylines, interface faces, and the exact edge integrals of supports
// (boundary_conditions.h).
#include "solver/discretisation/boundary_conditions.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.h"

namespace nmm::solve {

namespace {

/// Distance from p to the segment a–b, and the parameter of its projection.
double dist_to_segment(double px, double py, const Vec2& a, const Vec2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((px - a.x) * dx + (py - a.y) * dy) / l2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(a.x + t * dx - px, a.y + t * dy - py);
}

/// Calls visit(element, v, next) for every boundary loop edge of the mesh.
template <class Visit>
void for_boundary_edges(const Mesh& mesh, Visit visit) {
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::int32_t b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
    for (std::int32_t v = b; v < end; ++v) {
      const std::uint8_t o = mesh.loop_edge_origin[v];
      if (!(o & kEdgeBoundary) || (o & kEdgeBridge)) continue;
      visit(static_cast<std::int32_t>(e), v, v + 1 < end ? v + 1 : b);
    }
  }
}

}  // namespace

std::vector<BoundaryEdge> edges_under(const Mesh& mesh, const std::vector<Vec2>& poly,
                                      const std::string& scene_name, const std::string& path) {
  const double tol = 1e-6 * mesh.mesh_size;
  std::vector<BoundaryEdge> out;
  for_boundary_edges(mesh, [&](std::int32_t e, std::int32_t v, std::int32_t n) {
    const double ax = mesh.loop_xy[2 * v], ay = mesh.loop_xy[2 * v + 1];
    const double bx = mesh.loop_xy[2 * n], by = mesh.loop_xy[2 * n + 1];
    for (std::size_t i = 0; i + 1 < poly.size(); ++i) {
      if (dist_to_segment(ax, ay, poly[i], poly[i + 1]) > tol ||
          dist_to_segment(bx, by, poly[i], poly[i + 1]) > tol)
        continue;
      const double dx = poly[i + 1].x - poly[i].x, dy = poly[i + 1].y - poly[i].y;
      const double l = std::hypot(dx, dy);
      out.push_back(BoundaryEdge{e, v, n, dx / l, dy / l});
      break;
    }
  });
  if (out.empty())
    throw InputError(scene_name, path,
                     "the polyline lies on no body boundary (outer or hole face) of the mesh");
  return out;
}

std::vector<InterfaceEdge> interface_edges(const Mesh& mesh, const SceneDef& scene) {
  const double tol = 1e-6 * mesh.mesh_size;
  std::vector<InterfaceEdge> out;
  auto on_ring = [&](double x, double y, const Ring& r) {
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
      if (dist_to_segment(x, y, r[j], r[i]) <= tol) return true;
    return false;
  };
  for_boundary_edges(mesh, [&](std::int32_t e, std::int32_t v, std::int32_t n) {
    const double mx = 0.5 * (mesh.loop_xy[2 * v] + mesh.loop_xy[2 * n]);
    const double my = 0.5 * (mesh.loop_xy[2 * v + 1] + mesh.loop_xy[2 * n + 1]);
    const std::int32_t body = mesh.element_body[e];
    for (std::size_t o = 0; o < scene.bodies.size(); ++o) {
      if (static_cast<std::int32_t>(o) == body) continue;
      bool on = on_ring(mx, my, scene.bodies[o].outer);
      for (const Ring& h : scene.bodies[o].holes) on = on || on_ring(mx, my, h);
      if (on) {
        out.push_back(InterfaceEdge{BoundaryEdge{e, v, n, 0, 0}, static_cast<std::int32_t>(o)});
        break;
      }
    }
  });
  return out;
}

const double* gauss_points(int n) {
  static constexpr double k2[2] = {0.21132486540518711775, 0.78867513459481288225};
  static constexpr double k3[3] = {0.11270166537925831148, 0.5, 0.88729833462074168852};
  static constexpr double k4[4] = {0.06943184420297371239, 0.33000947820757186760,
                                   0.66999052179242813240, 0.93056815579702628761};
  return n <= 2 ? k2 : n == 3 ? k3 : k4;
}

const double* gauss_weights(int n) {
  static constexpr double k2[2] = {0.5, 0.5};
  static constexpr double k3[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  static constexpr double k4[4] = {0.17392742256872692869, 0.32607257743127307131,
                                   0.32607257743127307131, 0.17392742256872692869};
  return n <= 2 ? k2 : n == 3 ? k3 : k4;
}

void edge_support(const EdgeFrame& f, const double a[2], const double b[2], const double ua[2],
                  const double ub[2], bool fix_x, bool fix_y, double k_s, double* k, double* f_out) {
  const int nf = f.basis->functions(), nd = 2 * nf;
  std::vector<double> w(static_cast<std::size_t>(nf));
  const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
  const double* gp = gauss_points(f.points);
  const double* gw = gauss_weights(f.points);
  for (int q = 0; q < f.points; ++q) {
    const double xi = gp[q];
    const double x = a[0] + xi * dx, y = a[1] + xi * dy;
    const double u[2] = {(1 - xi) * ua[0] + xi * ub[0], (1 - xi) * ua[1] + xi * ub[1]};
    f.basis->values(x, y, w.data());
    const double c = k_s * gw[q] * len;
    for (int d = 0; d < 2; ++d) {
      if ((d == 0 && !fix_x) || (d == 1 && !fix_y)) continue;
      for (int i = 0; i < nf; ++i) {
        for (int j = 0; j < nf; ++j) k[(2 * j + d) * nd + (2 * i + d)] += c * w[i] * w[j];
        f_out[2 * i + d] -= c * w[i] * u[d];
      }
    }
  }
}

}  // namespace nmm::solve
