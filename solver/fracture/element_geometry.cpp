// An element's geometry for cracks: see element_geometry.h for the map.
#include "solver/fracture/element_geometry.h"

#include <cmath>
#include <limits>

#include "common/ring_geometry.h"

namespace nmm::solve {

namespace {
struct Triangle {
  Vec2 n[3];  // nodes as cut
  Vec2 c[3];  // the element's covers' current nodes
};

Triangle triangle_of(const Mesh& mesh, const std::vector<double>& cover_xy, std::size_t e) {
  Triangle t;
  const std::size_t tri = static_cast<std::size_t>(mesh.element_triangle[e]);
  for (int k = 0; k < 3; ++k) {
    const std::int32_t node = mesh.triangle_nodes[3 * tri + k], cover = mesh.element_covers[3 * e + k];
    t.n[k] = {mesh.node_xy[2 * node], mesh.node_xy[2 * node + 1]};
    t.c[k] = {cover_xy[2 * cover], cover_xy[2 * cover + 1]};
  }
  return t;
}

// The affine map fitted to element e's loop as cut (mesh.loop_xy) and now (loop_xy), see the header:
// x(X) = xc + A·(X − Xc).
struct LoopMap {
  Vec2 Xc, xc;
  double a[2][2] = {{1, 0}, {0, 1}};
};

LoopMap loop_map(const Mesh& mesh, const std::vector<double>& loop_xy, std::size_t e) {
  const std::int32_t b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
  const double n = end - b;
  LoopMap m;
  for (std::int32_t v = b; v < end; ++v) {
    m.Xc.x += mesh.loop_xy[2 * v] / n, m.Xc.y += mesh.loop_xy[2 * v + 1] / n;
    m.xc.x += loop_xy[2 * v] / n, m.xc.y += loop_xy[2 * v + 1] / n;
  }
  double p[2][2] = {{0, 0}, {0, 0}}, q[2][2] = {{0, 0}, {0, 0}};  // Σ (x − x̄)(X − X̄)ᵀ, Σ (X − X̄)(X − X̄)ᵀ
  for (std::int32_t v = b; v < end; ++v) {
    const double X[2] = {mesh.loop_xy[2 * v] - m.Xc.x, mesh.loop_xy[2 * v + 1] - m.Xc.y};
    const double x[2] = {loop_xy[2 * v] - m.xc.x, loop_xy[2 * v + 1] - m.xc.y};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) p[i][j] += x[i] * X[j], q[i][j] += X[i] * X[j];
  }
  const double det = q[0][0] * q[1][1] - q[0][1] * q[1][0];
  if (!(std::abs(det) > 0)) return m;  // a degenerate loop: a translation
  const double qi[2][2] = {{q[1][1] / det, -q[0][1] / det}, {-q[1][0] / det, q[0][0] / det}};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) m.a[i][j] = p[i][0] * qi[0][j] + p[i][1] * qi[1][j];
  return m;
}

Vec2 loop_point(const Mesh& mesh, const std::vector<double>& loop_xy, std::size_t e, const Vec2& X) {
  // On an edge of the loop as cut (within round-off of the cut's coordinates): that edge's fraction.
  const std::int32_t b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
  const double tol = 1e-9 * (mesh.mesh_size > 0 ? mesh.mesh_size : 1.0);
  for (std::int32_t v = b; v < end; ++v) {
    const std::int32_t w = v + 1 < end ? v + 1 : b;
    const double ax = mesh.loop_xy[2 * v], ay = mesh.loop_xy[2 * v + 1];
    const double ex = mesh.loop_xy[2 * w] - ax, ey = mesh.loop_xy[2 * w + 1] - ay, l2 = ex * ex + ey * ey;
    if (!(l2 > 0)) continue;
    const double t = ((X.x - ax) * ex + (X.y - ay) * ey) / l2;
    if (t < 0 || t > 1 || std::hypot(ax + t * ex - X.x, ay + t * ey - X.y) > tol) continue;
    return {loop_xy[2 * v] + t * (loop_xy[2 * w] - loop_xy[2 * v]),
            loop_xy[2 * v + 1] + t * (loop_xy[2 * w + 1] - loop_xy[2 * v + 1])};
  }
  const LoopMap m = loop_map(mesh, loop_xy, e);
  const double dx = X.x - m.Xc.x, dy = X.y - m.Xc.y;
  return {m.xc.x + m.a[0][0] * dx + m.a[0][1] * dy, m.xc.y + m.a[1][0] * dx + m.a[1][1] * dy};
}

Vec2 loop_direction_as_cut(const Mesh& mesh, const std::vector<double>& loop_xy, std::size_t e, const Vec2& d) {
  const LoopMap m = loop_map(mesh, loop_xy, e);
  const double det = m.a[0][0] * m.a[1][1] - m.a[0][1] * m.a[1][0];
  const Vec2 r{(m.a[1][1] * d.x - m.a[0][1] * d.y) / det, (m.a[0][0] * d.y - m.a[1][0] * d.x) / det};
  const double l = std::hypot(r.x, r.y);
  return {r.x / l, r.y / l};
}

Vec2 triangle_point(const Mesh& mesh, const std::vector<double>& cover_xy, std::size_t e, const Vec2& X) {
  const Triangle t = triangle_of(mesh, cover_xy, e);
  const double ax = t.n[1].x - t.n[0].x, ay = t.n[1].y - t.n[0].y, bx = t.n[2].x - t.n[0].x, by = t.n[2].y - t.n[0].y;
  const double det = ax * by - ay * bx, px = X.x - t.n[0].x, py = X.y - t.n[0].y;
  const double l1 = (px * by - py * bx) / det, l2 = (ax * py - ay * px) / det, l0 = 1 - l1 - l2;
  return {l0 * t.c[0].x + l1 * t.c[1].x + l2 * t.c[2].x, l0 * t.c[0].y + l1 * t.c[1].y + l2 * t.c[2].y};
}

Vec2 triangle_direction_as_cut(const Mesh& mesh, const std::vector<double>& cover_xy, std::size_t e, const Vec2& d) {
  const Triangle t = triangle_of(mesh, cover_xy, e);
  // A = C·N⁻¹ with C = [c1 − c0, c2 − c0], N = [N1 − N0, N2 − N0]: A⁻¹d = N·C⁻¹d.
  const double cax = t.c[1].x - t.c[0].x, cay = t.c[1].y - t.c[0].y, cbx = t.c[2].x - t.c[0].x, cby = t.c[2].y - t.c[0].y;
  const double det = cax * cby - cay * cbx;
  const double u = (d.x * cby - d.y * cbx) / det, w = (cax * d.y - cay * d.x) / det;  // C⁻¹d
  const Vec2 r{u * (t.n[1].x - t.n[0].x) + w * (t.n[2].x - t.n[0].x), u * (t.n[1].y - t.n[0].y) + w * (t.n[2].y - t.n[0].y)};
  const double l = std::hypot(r.x, r.y);
  return {r.x / l, r.y / l};
}

}  // namespace

Vec2 current_point(const Mesh& mesh, const RunState& s, int order, std::size_t e, const Vec2& X) {
  return order == 0 ? triangle_point(mesh, s.cover_xy, e, X) : loop_point(mesh, s.loop_xy, e, X);
}

Vec2 direction_as_cut(const Mesh& mesh, const RunState& s, int order, std::size_t e, const Vec2& d) {
  return order == 0 ? triangle_direction_as_cut(mesh, s.cover_xy, e, d) : loop_direction_as_cut(mesh, s.loop_xy, e, d);
}

bool ray_exit(const Mesh& mesh, std::size_t e, const Vec2& p, const Vec2& d, double t_min, RayExit& out) {
  const std::int32_t b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
  bool found = false;
  for (std::int32_t v = b; v < end; ++v) {
    const std::int32_t w = v + 1 < end ? v + 1 : b;
    const double ax = mesh.loop_xy[2 * v], ay = mesh.loop_xy[2 * v + 1];
    const double ex = mesh.loop_xy[2 * w] - ax, ey = mesh.loop_xy[2 * w + 1] - ay;
    // p + t·d = a + s·e:  t·d − s·e = a − p.
    const double den = d.x * (-ey) - d.y * (-ex);
    if (den == 0) continue;  // parallel: a ray along an edge leaves through the edges it meets
    const double rx = ax - p.x, ry = ay - p.y;
    const double t = (rx * (-ey) - ry * (-ex)) / den, s = (d.x * ry - d.y * rx) / den;
    if (s < 0 || s > 1 || !(t > t_min)) continue;
    if (!found || t < out.t) {
      found = true;
      out.t = t;
      out.at = {p.x + t * d.x, p.y + t * d.y};
      out.edge = v;
    }
  }
  return found;
}

Vec2 inside_point(const Mesh& mesh, std::size_t e) {
  const std::int32_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
  const double* xy = mesh.loop_xy.data() + 2 * b;
  // Centroid of the polygon (shoelace).
  double a2 = 0, cx = 0, cy = 0;
  for (std::int32_t i = 0; i < n; ++i) {
    const std::int32_t j = (i + 1) % n;
    const double c = xy[2 * i] * xy[2 * j + 1] - xy[2 * j] * xy[2 * i + 1];
    a2 += c;
    cx += (xy[2 * i] + xy[2 * j]) * c;
    cy += (xy[2 * i + 1] + xy[2 * j + 1]) * c;
  }
  const Vec2 centroid{cx / (3 * a2), cy / (3 * a2)};
  if (point_in_loop(xy, static_cast<std::size_t>(n), centroid.x, centroid.y)) return centroid;
  return point_inside_longest_edge(xy, static_cast<std::size_t>(n), 0.5 * a2);
}

std::int32_t element_holding(const Mesh& mesh, const std::vector<std::int32_t>& candidates, const Vec2& p) {
  for (std::int32_t e : candidates) {
    const std::int32_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
    if (point_in_loop(mesh.loop_xy.data() + 2 * b, static_cast<std::size_t>(n), p.x, p.y)) return e;
  }
  return -1;
}

}  // namespace nmm::solve
