// A run's state carried onto a re-cut mesh: see state_transfer.h.
#include "solver/fracture/state_transfer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/ring_geometry.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/polynomial.h"
#include "solver/fracture/element_geometry.h"

namespace nmm::solve {

namespace {

// The element of `now` that holds a tracked point's start (as cut), among the pieces of the old
// element it was in; the first piece when none holds it (a point on a crack face).
std::int32_t piece_holding(const Mesh& now, const std::vector<std::vector<std::int32_t>>& pieces,
                           const TrackedPoint& p) {
  const std::vector<std::int32_t>& of = pieces[static_cast<std::size_t>(p.element)];
  const std::int32_t e = element_holding(now, of, {p.x0, p.y0});
  return e >= 0 ? e : of.front();
}

}  // namespace

void transfer_state(const Mesh& old, const Mesh& now, const pre::RecutMap& map, int dofs_per_cover, RunState& s) {
  const std::size_t nc = now.cover_count(), ne = now.element_count(), nv = now.loop_vertex_count();
  const std::size_t m = static_cast<std::size_t>(dofs_per_cover);
  int order = 0;  // the cover order of dofs_per_cover = 2·(n + 1)(n + 2)/2
  while (2 * monomial_count(order) < dofs_per_cover) ++order;
  RunState t = s;  // scalars and per-body data unchanged
  t.cover_xy.resize(2 * nc);
  for (auto* v : {&t.cover_u, &t.velocity, &t.accel}) v->resize(m * nc);
  for (std::size_t c = 0; c < nc; ++c) {
    const std::size_t p = static_cast<std::size_t>(map.cover_parent[c]);
    for (int k = 0; k < 2; ++k) t.cover_xy[2 * c + k] = s.cover_xy[2 * p + k];
    for (std::size_t k = 0; k < m; ++k) {
      t.cover_u[m * c + k] = s.cover_u[m * p + k];
      t.velocity[m * c + k] = s.velocity[m * p + k];
      t.accel[m * c + k] = s.accel[m * p + k];
    }
  }
  // Each piece's stress polynomial (T terms of σxx σyy τxy about its first cover's node): its
  // parent's, re-expanded about the piece's origin where that is another node (stress_field.h).
  const std::size_t T = static_cast<std::size_t>(monomial_count(order));
  const double h = basis_scale(old);
  t.stress.assign(3 * T * ne, 0.0);
  std::vector<std::vector<std::int32_t>> pieces(old.element_count());
  for (std::size_t e = 0; e < ne; ++e) {
    const std::size_t p = static_cast<std::size_t>(map.element_parent[e]);
    pieces[p].push_back(static_cast<std::int32_t>(e));
    const double* from = s.stress.data() + 3 * T * p;
    double* to = t.stress.data() + 3 * T * e;
    const std::size_t o_old = static_cast<std::size_t>(old.element_covers[3 * p]);
    const std::size_t o_now = static_cast<std::size_t>(now.element_covers[3 * e]);
    const double sx = (s.cover_xy[2 * o_old] - t.cover_xy[2 * o_now]) / h;
    const double sy = (s.cover_xy[2 * o_old + 1] - t.cover_xy[2 * o_now + 1]) / h;
    if (T == 1 || (sx == 0 && sy == 0)) {
      std::copy(from, from + 3 * T, to);
      continue;
    }
    // ξ_old = ξ_now − (o_old − o_now)/h: each monomial of the old variables expanded in the new.
    for (std::size_t k = 0; k < T; ++k) {
      const Poly shifted = shifted_monomial(kMonomials.p[k], kMonomials.q[k], sx, sy);
      for (std::size_t j = 0; j < T; ++j)
        for (int r = 0; r < 3; ++r) to[3 * j + r] += from[3 * k + r] * shifted.c[j];
    }
  }
  t.loop_xy.resize(2 * nv);
  t.loop_u.resize(2 * nv);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::size_t p = static_cast<std::size_t>(map.element_parent[e]);
    for (std::int32_t v = now.element_loop_offset[e]; v < now.element_loop_offset[e + 1]; ++v) {
      const std::int32_t was = map.vertex_parent[v];
      const std::size_t i = static_cast<std::size_t>(v);
      if (was >= 0) {
        for (int k = 0; k < 2; ++k) {
          t.loop_xy[2 * i + k] = s.loop_xy[2 * static_cast<std::size_t>(was) + k];
          t.loop_u[2 * i + k] = s.loop_u[2 * static_cast<std::size_t>(was) + k];
        }
        continue;
      }
      const Vec2 X{now.loop_xy[2 * i], now.loop_xy[2 * i + 1]};
      const Vec2 x = current_point(old, s, order, p, X);
      t.loop_xy[2 * i] = x.x;
      t.loop_xy[2 * i + 1] = x.y;
      t.loop_u[2 * i] = x.x - X.x;
      t.loop_u[2 * i + 1] = x.y - X.y;
    }
  }
  for (auto* points : {&t.fixed, &t.loads, &t.measure})
    for (TrackedPoint& p : *points) p.element = piece_holding(now, pieces, p);
  t.pattern_pairs.clear();
  t.block_force.clear();
  s = std::move(t);
}

pre::RecutMap compose(const pre::RecutMap& later, const pre::RecutMap& earlier) {
  // An index of the middle mesh outside `earlier`'s range is a bug of the caller (maps of two
  // unrelated re-cuts): std::vector::at throws rather than reading another piece's parent.
  pre::RecutMap m;
  m.element_parent.reserve(later.element_parent.size());
  for (const std::int32_t p : later.element_parent)
    m.element_parent.push_back(earlier.element_parent.at(static_cast<std::size_t>(p)));
  m.cover_parent.reserve(later.cover_parent.size());
  for (const std::int32_t p : later.cover_parent) m.cover_parent.push_back(earlier.cover_parent.at(static_cast<std::size_t>(p)));
  m.vertex_parent.reserve(later.vertex_parent.size());
  for (const std::int32_t p : later.vertex_parent)
    m.vertex_parent.push_back(p < 0 ? -1 : earlier.vertex_parent.at(static_cast<std::size_t>(p)));
  m.cut_triangles = earlier.cut_triangles;
  m.cut_triangles.insert(m.cut_triangles.end(), later.cut_triangles.begin(), later.cut_triangles.end());
  std::sort(m.cut_triangles.begin(), m.cut_triangles.end());
  m.cut_triangles.erase(std::unique(m.cut_triangles.begin(), m.cut_triangles.end()), m.cut_triangles.end());
  m.region_triangles = earlier.region_triangles + later.region_triangles;
  m.seconds_find = earlier.seconds_find + later.seconds_find;
  m.seconds_cut = earlier.seconds_cut + later.seconds_cut;
  m.seconds_splice = earlier.seconds_splice + later.seconds_splice;
  return m;
}

std::vector<ContactHistory> transfer_history(const std::vector<ContactHistory>& history, const Mesh& old,
                                             const Mesh& now, const pre::RecutMap& map,
                                             std::size_t first_new_joint, bool cohesive) {
  std::vector<std::int32_t> vertex_now(old.loop_vertex_count(), -1);
  for (std::size_t v = 0; v < now.loop_vertex_count(); ++v) {
    const std::int32_t was = map.vertex_parent[v];
    if (was >= 0 && vertex_now[static_cast<std::size_t>(was)] < 0) vertex_now[static_cast<std::size_t>(was)] = static_cast<std::int32_t>(v);
  }
  // A block of the old mesh → its pieces in the new one. An entry against a block a crack split
  // follows the piece that holds the contact edge nearest its vertex (as cut): the face it was
  // closed against. (Taken by the first piece instead, an entry against the other piece let the
  // vertex count as closed against every edge of the wrong one, up to closed_depth deep.)
  std::vector<std::vector<std::int32_t>> pieces(old.block_count());
  for (std::size_t e = 0; e < now.element_count(); ++e) {
    auto& p = pieces[static_cast<std::size_t>(old.element_block[static_cast<std::size_t>(map.element_parent[e])])];
    if (std::find(p.begin(), p.end(), now.element_block[e]) == p.end()) p.push_back(now.element_block[e]);
  }
  // `own` ≥ 0: a piece the entry may not follow (its vertex's own, below).
  auto piece_near = [&](std::int32_t old_block, std::int32_t v, std::int32_t own) {
    const auto& p = pieces[static_cast<std::size_t>(old_block)];
    if (p.size() == 1) return p.front();
    if (p.empty()) return std::int32_t{-1};
    const double x = now.loop_xy[2 * static_cast<std::size_t>(v)], y = now.loop_xy[2 * static_cast<std::size_t>(v) + 1];
    std::int32_t best = p.front() == own ? p[1] : p.front();
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < now.contact_edge.size(); ++i) {
      const auto e = static_cast<std::size_t>(now.contact_edge_element[i]);
      if (now.element_block[e] == own) continue;
      if (std::find(p.begin(), p.end(), now.element_block[e]) == p.end()) continue;
      const std::int32_t a = now.contact_edge[i], first = now.element_loop_offset[e], end = now.element_loop_offset[e + 1];
      const std::int32_t b = a + 1 < end ? a + 1 : first;
      const double ax = now.loop_xy[2 * a], ay = now.loop_xy[2 * a + 1];
      const double dx = now.loop_xy[2 * b] - ax, dy = now.loop_xy[2 * b + 1] - ay, l2 = dx * dx + dy * dy;
      const double t = l2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / l2, 0.0, 1.0) : 0.0;
      const double d = std::hypot(ax + t * dx - x, ay + t * dy - y);
      if (d < best_d) best_d = d, best = now.element_block[e];
    }
    return best;
  };
  // A cohesive face's entry against its own block — a crack that had not split it, its faces
  // holding across it — follows the piece across the crack once a cut splits the block: its own
  // face edges lie at no distance from the vertex, level with the other face's, and where the
  // nearest edge was its own the entry stayed against its own piece, the contact across started
  // without its cohesion and nothing held that point of the crack (the bar of
  // reference/cohesive_bar.h at h 0.05 m: the top end of its first crack, 0.011 m of the 0.19 m
  // section, carried nothing once the crack ran through, and the section's traction, eccentric
  // by that, opened the crack 19.4 µm at its top and 0.09 µm at its bottom in one step).
  auto block_of_vertex = [](const Mesh& mesh) {
    std::vector<std::int32_t> b(mesh.loop_vertex_count(), -1);
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
      for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v)
        b[static_cast<std::size_t>(v)] = mesh.element_block[e];
    return b;
  };
  std::vector<std::int32_t> old_block_of, now_block_of;
  if (cohesive) old_block_of = block_of_vertex(old), now_block_of = block_of_vertex(now);
  std::vector<ContactHistory> out;
  out.reserve(history.size());
  for (ContactHistory h : history) {
    const std::int32_t v = vertex_now[static_cast<std::size_t>(h.vertex)];
    if (v < 0) continue;
    const bool across_own =
        cohesive && h.cohesive.on && old_block_of[static_cast<std::size_t>(h.vertex)] == h.block;
    h.vertex = v;
    h.block = piece_near(h.block, v, across_own ? now_block_of[static_cast<std::size_t>(v)] : -1);
    if (h.block < 0) continue;
    out.push_back(h);
  }
  for (std::size_t i = 0; i < now.contact_edge.size(); ++i) {
    const std::int32_t v = now.contact_edge[i], across = now.contact_edge_opposite[i];
    if (across < 0 || now.loop_edge_joint[static_cast<std::size_t>(v)] < static_cast<std::int32_t>(first_new_joint))
      continue;
    const std::int32_t block = now.element_block[static_cast<std::size_t>(across)];
    // The edge's start, and — where the rock softens (cohesive_law.h) — its end too: contact
    // detection keeps one vertex per point of a crack, either face's, and the end of a face's
    // last edge (at a boundary or a tip) is the start of none, so without an entry of its own a
    // contact kept there would start open, without its cohesion.
    const auto e = static_cast<std::size_t>(now.contact_edge_element[i]);
    const std::int32_t end = v + 1 < now.element_loop_offset[e + 1] ? v + 1 : now.element_loop_offset[e];
    for (const std::int32_t p : {v, end}) {
      if (p == end && !cohesive) continue;
      const bool has = std::any_of(out.begin(), out.end(), [&](const ContactHistory& h) { return h.vertex == p && h.block == block; });
      if (has) continue;
      ContactHistory h;
      h.vertex = p;
      h.block = block;
      h.state = ContactState::locked;
      h.fresh = true;
      h.cohesive.on = cohesive;
      out.push_back(h);
    }
  }

  return out;
}

}  // namespace nmm::solve
