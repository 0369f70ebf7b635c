// Whether a crack parted anything in an element, and the crack through a triangle: see
// crack_parting.h.
#include "solver/fracture/crack_parting.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace nmm::solve {

TriangleElements::TriangleElements(const Mesh& mesh) : mesh_(&mesh), elements_(mesh.element_count()) {
  offset_.assign(mesh.triangle_count() + 1, 0);
  for (const std::int32_t t : mesh.element_triangle) ++offset_[static_cast<std::size_t>(t) + 1];
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) offset_[t + 1] += offset_[t];
  element_.resize(elements_);
  std::vector<std::size_t> next(offset_.begin(), offset_.end() - 1);
  for (std::size_t e = 0; e < elements_; ++e)
    element_[next[static_cast<std::size_t>(mesh.element_triangle[e])]++] = static_cast<std::int32_t>(e);
}

bool TriangleElements::shares_a_cover(const Mesh& mesh, std::size_t e, std::int32_t first_crack) const {
  return shared_nodes(mesh, e, first_crack) != 0;
}

unsigned TriangleElements::shared_nodes(const Mesh& mesh, std::size_t e, std::int32_t first_crack) const {
  // Across each of e's edges on a crack, the piece of the same triangle with that edge reversed
  // (its ends within 1e-9·h): e itself where the crack ends inside it (a slit, both faces e's,
  // every cover shared). An edge with no such piece (a crack along the triangle's own edge, the
  // piece across in the next triangle) is not compared.
  const std::size_t t = static_cast<std::size_t>(mesh.element_triangle[e]);
  const double tol = 1e-9 * mesh.mesh_size;
  auto vertex = [&](std::int32_t k) { return Vec2{mesh.loop_xy[2 * static_cast<std::size_t>(k)], mesh.loop_xy[2 * static_cast<std::size_t>(k) + 1]}; };
  auto near = [&](const Vec2& a, const Vec2& b) { return std::abs(a.x - b.x) <= tol && std::abs(a.y - b.y) <= tol; };
  auto next = [&](std::size_t el, std::int32_t v) {
    return v + 1 < mesh.element_loop_offset[el + 1] ? v + 1 : mesh.element_loop_offset[el];
  };
  unsigned shared = 0;
  for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v) {
    if (mesh.loop_edge_joint[static_cast<std::size_t>(v)] < first_crack) continue;  // -1 (none) or a scene joint
    const Vec2 p = vertex(v), q = vertex(next(e, v));
    for (std::size_t i = offset_[t]; i < offset_[t + 1]; ++i) {
      const std::size_t o = static_cast<std::size_t>(element_[i]);
      bool across = false;
      for (std::int32_t w = mesh.element_loop_offset[o]; w < mesh.element_loop_offset[o + 1] && !across; ++w)
        across = near(vertex(w), q) && near(vertex(next(o, w)), p);
      if (!across) continue;
      unsigned here = 0;
      for (int k = 0; k < 3; ++k)
        if (mesh.element_covers[3 * o + static_cast<std::size_t>(k)] == mesh.element_covers[3 * e + static_cast<std::size_t>(k)])
          here |= 1u << k;
      shared |= here;
    }
  }
  return shared;
}

bool inside_star(const Mesh& mesh, std::size_t e, unsigned nodes, const Vec2& p) {
  const std::size_t t = static_cast<std::size_t>(mesh.element_triangle[e]);
  const double tol = 1e-9 * mesh.mesh_size * mesh.mesh_size;  // ×(edge length) ≈ 1e-9·h of distance
  auto node = [&](std::int32_t n) { return Vec2{mesh.node_xy[2 * static_cast<std::size_t>(n)], mesh.node_xy[2 * static_cast<std::size_t>(n) + 1]}; };
  for (int k = 0; k < 3; ++k) {
    if (!(nodes & (1u << k))) continue;
    const std::int32_t centre = mesh.triangle_nodes[3 * t + static_cast<std::size_t>(k)];
    for (std::size_t u = 0; u < mesh.triangle_count(); ++u) {
      const std::int32_t* q = &mesh.triangle_nodes[3 * u];
      if (q[0] != centre && q[1] != centre && q[2] != centre) continue;
      // p inside the star's triangle u, off the edge opposite the centre (the star's outer edge)
      // by more than the tolerance; on the edges that meet at the centre counts as inside.
      const Vec2 a = node(q[0]), b = node(q[1]), c = node(q[2]);
      const double area2 = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      const Vec2 v[3] = {a, b, c};
      bool in = true;
      for (int i = 0; i < 3 && in; ++i) {
        const Vec2& m = v[(i + 1) % 3];
        const Vec2& n = v[(i + 2) % 3];
        const double side = ((n.x - m.x) * (p.y - m.y) - (p.x - m.x) * (n.y - m.y)) * (area2 > 0 ? 1 : -1);
        const bool outer = q[i] == centre;  // the edge opposite node i: opposite the centre
        in = outer ? side > tol : side >= -tol;
      }
      if (in) return true;
    }
  }
  return false;
}

CrackEnds::CrackEnds(const std::vector<Vec2>& ends_a, const std::vector<Vec2>& ends_b) : a_(&ends_a), b_(&ends_b) {
  sorted_.reserve(2 * ends_a.size());
  for (std::size_t i = 0; i < ends_a.size(); ++i) {
    sorted_.push_back({ends_a[i].x, ends_a[i].y, i});
    sorted_.push_back({ends_b[i].x, ends_b[i].y, i});
  }
  std::sort(sorted_.begin(), sorted_.end(), [](const End& p, const End& q) {
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    return p.index < q.index;
  });
}

std::vector<std::size_t> cracks_through_triangle(const Mesh& mesh, std::size_t t, const std::vector<Vec2>& ends_a,
                                                 const std::vector<Vec2>& ends_b) {
  return cracks_through_triangle(mesh, t, CrackEnds(ends_a, ends_b));
}

std::vector<std::size_t> cracks_through_triangle(const Mesh& mesh, std::size_t t, const CrackEnds& ends) {
  // Barycentric coordinates of the segment's mid-point in the triangle, each ≥ −tol / (its
  // height): inside or on it within 1e-9·h. A segment is cut from edge to edge of one element,
  // so its mid-point lies in that element's triangle.
  const std::vector<Vec2>& ends_a = ends.a();
  const std::vector<Vec2>& ends_b = ends.b();
  Vec2 n[3];
  for (int k = 0; k < 3; ++k) {
    const std::size_t node = static_cast<std::size_t>(mesh.triangle_nodes[3 * t + static_cast<std::size_t>(k)]);
    n[k] = {mesh.node_xy[2 * node], mesh.node_xy[2 * node + 1]};
  }
  const double area2 = (n[1].x - n[0].x) * (n[2].y - n[0].y) - (n[2].x - n[0].x) * (n[1].y - n[0].y);
  const double tol = 1e-9 * mesh.mesh_size * mesh.mesh_size;  // ×(edge length) ≈ 1e-9·h of distance
  auto inside = [&](const Vec2& p) {
    for (int k = 0; k < 3; ++k) {
      const Vec2& a = n[(k + 1) % 3];
      const Vec2& b = n[(k + 2) % 3];
      const double s = (b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y);  // 2·area of (a, b, p)
      if ((area2 > 0 ? s : -s) < -tol) return false;
    }
    return true;
  };
  const std::size_t count = ends_a.size();
  std::vector<std::uint8_t> in(count, 0);
  std::vector<std::size_t> queue;
  for (std::size_t i = 0; i < count; ++i)
    if (inside({(ends_a[i].x + ends_b[i].x) / 2, (ends_a[i].y + ends_b[i].y) / 2})) in[i] = 1, queue.push_back(i);
  if (queue.empty()) return queue;
  // The chains through those found, by end point (exact). The closure does not depend on the
  // order the joined segments are visited in, and the result is sorted.
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const std::size_t i = queue[q];
    for (const Vec2& p : {ends_a[i], ends_b[i]})
      ends.at(p, [&](std::size_t k) {
        if (!in[k]) in[k] = 1, queue.push_back(k);
      });
  }
  std::sort(queue.begin(), queue.end());
  return queue;
}

}  // namespace nmm::solve
