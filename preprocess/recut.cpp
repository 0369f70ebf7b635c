// Re-cutting where new joints cross: see recut.h for the method.
#include "preprocess/recut.h"

#include "common/stopwatch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>
#include <utility>

#include "common/lattice.h"
#include "common/ring_geometry.h"
#include "preprocess/cover_cutter.h"

namespace nmm::pre {

namespace {

// The lattice node index of a mesh node (its coordinates are the lattice's, computed alike).
std::int32_t lattice_node(const Lattice& lat, double x, double y) {
  const std::int64_t j = std::llround(y / lat.dy);
  const double shift = ((j % 2) + 2) % 2 == 1 ? 0.5 : 0.0;
  const std::int64_t i = std::llround(x / lat.h - shift);
  return lat.index(i, j);
}

double point_segment_distance(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / l2, 0.0, 1.0) : 0.0;
  return std::hypot(ax + t * dx - px, ay + t * dy - py);
}

double cross(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

// Distance between segments a–b and c–d (0 when they cross).
double segment_distance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(a.x, a.y, b.x, b.y, c.x, c.y), d2 = cross(a.x, a.y, b.x, b.y, d.x, d.y);
  const double d3 = cross(c.x, c.y, d.x, d.y, a.x, a.y), d4 = cross(c.x, c.y, d.x, d.y, b.x, b.y);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0;
  return std::min({point_segment_distance(a.x, a.y, c.x, c.y, d.x, d.y),
                   point_segment_distance(b.x, b.y, c.x, c.y, d.x, d.y),
                   point_segment_distance(c.x, c.y, a.x, a.y, b.x, b.y),
                   point_segment_distance(d.x, d.y, a.x, a.y, b.x, b.y)});
}

// Whether segment a–b comes within tol of triangle t of the mesh (closed region).
bool touches(const Mesh& m, std::size_t t, const Vec2& a, const Vec2& b, double tol) {
  Vec2 q[3];
  for (int k = 0; k < 3; ++k) {
    const std::int32_t n = m.triangle_nodes[3 * t + k];
    q[k] = {m.node_xy[2 * n], m.node_xy[2 * n + 1]};
  }
  for (const Vec2& p : {a, b}) {  // an end inside (the triangles are counter-clockwise)
    bool inside = true;
    for (int k = 0; k < 3; ++k) inside = inside && cross(q[k].x, q[k].y, q[(k + 1) % 3].x, q[(k + 1) % 3].y, p.x, p.y) >= 0;
    if (inside) return true;
  }
  for (int k = 0; k < 3; ++k)
    if (segment_distance(a, b, q[k], q[(k + 1) % 3]) <= tol) return true;
  return false;
}

// A point strictly inside element e's loop: a little inside the middle of its longest edge, by a
// thousandth of the element's mean width (area over that edge's length), so that thin slivers
// get a point inside them too.
Vec2 inner_point(const Mesh& m, std::size_t e) {
  const std::int32_t b = m.element_loop_offset[e], n = m.element_loop_offset[e + 1] - b;
  return point_inside_longest_edge(m.loop_xy.data() + 2 * b, static_cast<std::size_t>(n), element_area(m, e));
}

// A directed loop edge's end points, as a key.
struct EdgeKey {
  double x0, y0, x1, y1;
  bool operator==(const EdgeKey& o) const {
    return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1;
  }
};
struct EdgeHash {
  std::size_t operator()(const EdgeKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (double v : {k.x0, k.y0, k.x1, k.y1}) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
    return static_cast<std::size_t>(h);
  }
};

// Blocks of a mesh whose elements and loops are set, from the loops alone: elements joined across
// mesh-only edges are one block (numbered by their first element). Two elements share a mesh
// edge where one's loop runs the other's edge the other way, to the bit: the cut rounds each
// exact point once, so equal pieces round alike, and two different pieces of a mesh line can
// round alike only where both round to one point — such a piece joins nothing, here and in the
// full cut (cover_cutter.cpp extract), so that the two give the same blocks.
void link_blocks(Mesh& m) {
  const std::size_t ne = m.element_count();
  std::unordered_map<EdgeKey, std::int32_t, EdgeHash> owner;
  owner.reserve(m.loop_vertex_count());
  auto edge = [&](std::int32_t v, std::int32_t e, bool reversed) {
    const std::int32_t b = m.element_loop_offset[e], end = m.element_loop_offset[e + 1];
    const std::int32_t w = v + 1 < end ? v + 1 : b;
    EdgeKey k{m.loop_xy[2 * v], m.loop_xy[2 * v + 1], m.loop_xy[2 * w], m.loop_xy[2 * w + 1]};
    if (reversed) k = {k.x1, k.y1, k.x0, k.y0};
    return k;
  };
  auto joins = [&](std::int32_t v, std::int32_t e) {
    // A gap end's extension (cover_cutter.cpp step 5) joins blocks as a mesh edge does.
    const std::uint8_t o = m.loop_edge_origin[v];
    if (o != kEdgeMesh && o != kEdgeExtension && o != (kEdgeMesh | kEdgeExtension)) return false;
    const EdgeKey k = edge(v, e, false);
    return k.x0 != k.x1 || k.y0 != k.y1;
  };
  for (std::size_t e = 0; e < ne; ++e)
    for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v)
      if (joins(v, static_cast<std::int32_t>(e))) owner.emplace(edge(v, static_cast<std::int32_t>(e), false), static_cast<std::int32_t>(e));
  std::vector<std::int32_t> parent(ne);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (std::size_t e = 0; e < ne; ++e)
    for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v) {
      if (!joins(v, static_cast<std::int32_t>(e))) continue;
      const auto it = owner.find(edge(v, static_cast<std::int32_t>(e), true));
      if (it == owner.end()) continue;
      const std::int32_t a = find(static_cast<std::int32_t>(e)), b = find(it->second);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  m.block_body.clear();
  m.element_block.assign(ne, -1);
  std::vector<std::int32_t> block_of_root(ne, -1);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t r = find(static_cast<std::int32_t>(e));
    if (block_of_root[r] < 0) {
      block_of_root[r] = static_cast<std::int32_t>(m.block_body.size());
      m.block_body.push_back(m.element_body[e]);
    }
    m.element_block[e] = block_of_root[r];
  }
}

// Whether element `re` of `a` has the loop of element `oe` of `b` (vertex for vertex, with the
// same edge origins and joints, from whichever vertex each starts): the rotation r that takes
// a's loop vertex k to b's (k + r) mod n, or -1.
std::int32_t same_loop(const Mesh& a, std::size_t re, const Mesh& b, std::size_t oe) {
  const std::int32_t ab = a.element_loop_offset[re], n = a.element_loop_offset[re + 1] - ab;
  const std::int32_t bb = b.element_loop_offset[oe];
  if (b.element_loop_offset[oe + 1] - bb != n) return -1;
  for (std::int32_t r = 0; r < n; ++r) {
    bool all = true;
    for (std::int32_t k = 0; k < n && all; ++k) {
      const std::int32_t v = ab + k, w = bb + (r + k) % n;
      all = a.loop_xy[2 * v] == b.loop_xy[2 * w] && a.loop_xy[2 * v + 1] == b.loop_xy[2 * w + 1] &&
            a.loop_edge_origin[v] == b.loop_edge_origin[w] && a.loop_edge_joint[v] == b.loop_edge_joint[w];
    }
    if (all) return r;
  }
  return -1;
}

// m's contact edges element by element: `first` [element + 1] CSR into `index` (into the
// contact-edge arrays, in their order).
struct ContactEdgesOf {
  std::vector<std::int32_t> first, index;
  explicit ContactEdgesOf(const Mesh& m) : first(m.element_count() + 1, 0), index(m.contact_edge.size()) {
    for (const std::int32_t e : m.contact_edge_element) ++first[static_cast<std::size_t>(e) + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    std::vector<std::int32_t> at(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < m.contact_edge.size(); ++i)
      index[static_cast<std::size_t>(at[static_cast<std::size_t>(m.contact_edge_element[i])]++)] = static_cast<std::int32_t>(i);
  }
};

}  // namespace

Mesh recut(const Mesh& old, const SceneDef& scene, std::size_t first_new_joint, const std::string& file,
           RecutMap& map) {
  Stopwatch watch;
  const Lattice lat = make_lattice(scene.bodies, scene.mesh_size);
  const std::size_t nt = old.triangle_count();
  // T: the triangles the new joints touch.
  const double tol = 1e-9 * old.mesh_size;
  std::vector<std::uint8_t> in_t(nt, 0);
  for (std::size_t j = first_new_joint; j < scene.joints.size(); ++j) {
    const auto& pts = scene.joints[j].points;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      const Vec2 a = pts[k], b = pts[k + 1];
      const Box sb{std::min(a.x, b.x) - tol, std::min(a.y, b.y) - tol, std::max(a.x, b.x) + tol,
                   std::max(a.y, b.y) + tol};
      for (std::size_t t = 0; t < nt; ++t) {
        if (in_t[t]) continue;
        Box tb{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
               -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
        for (int c = 0; c < 3; ++c) {
          const std::int32_t n = old.triangle_nodes[3 * t + c];
          tb = {std::min(tb.x0, old.node_xy[2 * n]), std::min(tb.y0, old.node_xy[2 * n + 1]),
                std::max(tb.x1, old.node_xy[2 * n]), std::max(tb.y1, old.node_xy[2 * n + 1])};
        }
        if (tb.overlaps(sb) && touches(old, t, a, b, tol)) in_t[t] = 1;
      }
    }
  }
  // T's nodes, and R: every triangle with one of them.
  std::vector<std::uint8_t> t_node(old.node_count(), 0), in_r(nt, 0);
  map.cut_triangles.clear();
  for (std::size_t t = 0; t < nt; ++t)
    if (in_t[t]) {
      map.cut_triangles.push_back(static_cast<std::int32_t>(t));
      for (int c = 0; c < 3; ++c) t_node[old.triangle_nodes[3 * t + c]] = 1;
    }
  // R, and the ring of triangles around it (sharing a node with it) that is cut too but not
  // taken: an element of R \ T is cut as its neighbours outside R see it — a face that holds a
  // crack ending inside it is bridged to its boundary (cover_cutter.cpp step 4), and the bridge's
  // end is a vertex of the element across that boundary too.
  std::vector<std::uint8_t> r_node(old.node_count(), 0);
  for (std::size_t t = 0; t < nt; ++t) {
    bool near = false;
    for (int c = 0; c < 3; ++c) near = near || t_node[old.triangle_nodes[3 * t + c]];
    if (!near) continue;
    in_r[t] = 1;
    for (int c = 0; c < 3; ++c) r_node[old.triangle_nodes[3 * t + c]] = 1;
  }
  std::vector<std::array<std::int32_t, 3>> region;
  std::map<std::array<std::int32_t, 3>, std::int32_t> triangle_of_key;  // lattice key → old triangle
  for (std::size_t t = 0; t < nt; ++t) {
    bool ring = false;
    for (int c = 0; c < 3; ++c) ring = ring || r_node[old.triangle_nodes[3 * t + c]];
    if (!ring) continue;
    std::array<std::int32_t, 3> key;
    for (int c = 0; c < 3; ++c) {
      const std::int32_t n = old.triangle_nodes[3 * t + c];
      key[c] = lattice_node(lat, old.node_xy[2 * n], old.node_xy[2 * n + 1]);
    }
    std::sort(key.begin(), key.end());
    region.push_back(key);
    triangle_of_key[key] = static_cast<std::int32_t>(t);
  }
  map.region_triangles = region.size();
  map.seconds_find = watch.seconds();
  watch.restart();
  RegionCut cut = cut_region(scene, region, file);
  map.seconds_cut = watch.seconds();
  watch.restart();
  const Mesh& rc = cut.mesh;
  std::vector<std::int32_t> rc_triangle(rc.triangle_count());  // cut's triangle → old triangle
  for (std::size_t t = 0; t < rc.triangle_count(); ++t) {
    std::array<std::int32_t, 3> key = cut.lattice_triangles[t];
    std::sort(key.begin(), key.end());
    rc_triangle[t] = triangle_of_key.at(key);
  }
  // The cut's nodes → old nodes (by the triangle corners they are).
  std::vector<std::int32_t> rc_node(rc.node_count(), -1);
  for (std::size_t t = 0; t < rc.triangle_count(); ++t) {
    const std::size_t ot = static_cast<std::size_t>(rc_triangle[t]);
    for (int c = 0; c < 3; ++c) {
      const std::int32_t rn = rc.triangle_nodes[3 * t + c];
      for (int d = 0; d < 3; ++d) {
        const std::int32_t on = old.triangle_nodes[3 * ot + d];
        if (old.node_xy[2 * on] == rc.node_xy[2 * rn] && old.node_xy[2 * on + 1] == rc.node_xy[2 * rn + 1])
          rc_node[rn] = on;
      }
    }
  }
  // Old elements by triangle.
  std::vector<std::int32_t> first_old(nt + 1, 0);
  for (std::size_t e = 0; e < old.element_count(); ++e) ++first_old[old.element_triangle[e] + 1];
  std::partial_sum(first_old.begin(), first_old.end(), first_old.begin());
  std::vector<std::int32_t> first_rc(nt + 1, 0);
  for (std::size_t e = 0; e < rc.element_count(); ++e) ++first_rc[rc_triangle[rc.element_triangle[e]] + 1];
  std::partial_sum(first_rc.begin(), first_rc.end(), first_rc.begin());
  std::vector<std::int32_t> rc_by_triangle(rc.element_count());
  {
    std::vector<std::int32_t> at(first_rc.begin(), first_rc.end() - 1);
    for (std::size_t e = 0; e < rc.element_count(); ++e)
      rc_by_triangle[at[rc_triangle[rc.element_triangle[e]]]++] = static_cast<std::int32_t>(e);
  }

  // The parent of a cut element: the old element of its triangle that holds it.
  auto parent_of = [&](std::size_t re) {
    const std::int32_t t = rc_triangle[rc.element_triangle[re]];
    const Vec2 p = inner_point(rc, re);
    std::int32_t best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::int32_t oe = first_old[t]; oe < first_old[t + 1]; ++oe) {
      const std::int32_t b = old.element_loop_offset[oe], n = old.element_loop_offset[oe + 1] - b;
      if (point_in_loop(old.loop_xy.data() + 2 * b, static_cast<std::size_t>(n), p.x, p.y)) return oe;
      const double d = distance_to_loop(old.loop_xy.data() + 2 * b, static_cast<std::size_t>(n), p.x, p.y);
      if (d < best_d) best_d = d, best = oe;
    }
    return best;
  };

  // The new mesh: triangles and nodes as before; elements triangle by triangle, R's from the cut.
  Mesh m;
  m.mesh_size = old.mesh_size;
  m.dofs_per_cover = old.dofs_per_cover;
  m.node_xy = old.node_xy;
  m.triangle_nodes = old.triangle_nodes;
  m.tool = old.tool;
  m.tool_version = old.tool_version;
  m.scene_file = old.scene_file;
  m.scene_text = old.scene_text;
  m.scene_sha256 = old.scene_sha256;
  map.element_parent.clear();
  map.vertex_parent.clear();
  std::vector<std::int32_t> source_rc;  // [new me] the cut's element, or -1 (an old one kept)
  std::vector<std::int32_t> old_new(old.element_count(), -1);  // [old me] the new element it is, or -1
  std::vector<std::uint8_t> matched;    // [new me] 1: an old element, kept or matched loop for loop
  std::vector<std::int32_t> match_rotation;  // [new me] its loop vertex k is the old one's k + this
  m.element_loop_offset.push_back(0);
  // Appends element e of `from` (the old mesh: kept as it is; the cut: a piece of `parent`).
  auto add_loop = [&](const Mesh& from, std::size_t e, std::int32_t parent) {
    const bool kept = &from == &old;
    const std::int32_t b = from.element_loop_offset[e], end = from.element_loop_offset[e + 1];
    const std::int32_t pb = old.element_loop_offset[parent], pend = old.element_loop_offset[parent + 1];
    for (std::int32_t v = b; v < end; ++v) {
      m.loop_xy.push_back(from.loop_xy[2 * v]);
      m.loop_xy.push_back(from.loop_xy[2 * v + 1]);
      m.loop_edge_origin.push_back(from.loop_edge_origin[v]);
      m.loop_edge_joint.push_back(from.loop_edge_joint[v]);
      std::int32_t same = kept ? v : -1;
      for (std::int32_t w = pb; w < pend && same < 0; ++w)
        if (old.loop_xy[2 * w] == from.loop_xy[2 * v] && old.loop_xy[2 * w + 1] == from.loop_xy[2 * v + 1]) same = w;
      map.vertex_parent.push_back(same);
    }
    m.element_loop_offset.push_back(static_cast<std::int32_t>(m.loop_edge_origin.size()));
  };
  for (std::size_t t = 0; t < nt; ++t) {
    if (!in_r[t]) {
      for (std::int32_t oe = first_old[t]; oe < first_old[t + 1]; ++oe) {
        old_new[oe] = static_cast<std::int32_t>(m.element_count());
        matched.push_back(1);
        match_rotation.push_back(0);
        m.element_triangle.push_back(static_cast<std::int32_t>(t));
        m.element_body.push_back(old.element_body[oe]);
        map.element_parent.push_back(oe);
        source_rc.push_back(-1);
        add_loop(old, static_cast<std::size_t>(oe), oe);
      }
      continue;
    }
    for (std::int32_t k = first_rc[t]; k < first_rc[t + 1]; ++k) {
      const std::size_t re = static_cast<std::size_t>(rc_by_triangle[k]);
      // An element the new joints left as it was is that old element (in a triangle of R \ T
      // every one is): matched loop for loop, not by a point inside it, which for a sliver a
      // round-off wide can land on the edge it shares with its neighbour and take the
      // neighbour's covers.
      std::int32_t parent = -1, rotation = -1;
      for (std::int32_t oe = first_old[t]; oe < first_old[t + 1] && parent < 0; ++oe)
        if (old_new[oe] < 0 && (rotation = same_loop(rc, re, old, static_cast<std::size_t>(oe))) >= 0) parent = oe;
      if (parent >= 0) old_new[parent] = static_cast<std::int32_t>(m.element_count());
      else parent = parent_of(re);
      matched.push_back(old_new[parent] == static_cast<std::int32_t>(m.element_count()) ? 1 : 0);
      match_rotation.push_back(matched.back() ? rotation : -1);
      m.element_triangle.push_back(static_cast<std::int32_t>(t));
      m.element_body.push_back(rc.element_body[re]);
      map.element_parent.push_back(parent);
      source_rc.push_back(static_cast<std::int32_t>(re));
      add_loop(rc, re, parent);
    }
  }
  const std::size_t ne = m.element_count();
  std::vector<std::int32_t> from_cut;  // the new elements that came from the cut
  for (std::size_t e = 0; e < ne; ++e)
    if (source_rc[e] >= 0) from_cut.push_back(static_cast<std::int32_t>(e));

  // Covers: node by node; T's nodes take the cut's covers (ordered by their first new element),
  // the others keep theirs.
  std::vector<std::vector<std::int32_t>> rc_covers_of(old.node_count());  // T-node → cut covers
  {
    std::vector<std::int32_t> first_at(rc.cover_count(), -1);
    for (const std::int32_t e : from_cut) {
      for (int c = 0; c < 3; ++c) {
        const std::int32_t rcov = rc.element_covers[3 * static_cast<std::size_t>(source_rc[e]) + c];
        if (first_at[rcov] < 0) first_at[rcov] = static_cast<std::int32_t>(e);
      }
    }
    std::vector<std::int32_t> order(rc.cover_count());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) { return first_at[a] < first_at[b]; });
    for (std::int32_t rcov : order) {
      const std::int32_t n = rc_node[rc.cover_node[rcov]];
      if (n >= 0 && t_node[n]) rc_covers_of[n].push_back(rcov);
    }
  }
  std::vector<std::int32_t> old_cover_new(old.cover_count(), -1), rc_cover_new(rc.cover_count(), -1);
  map.cover_parent.clear();
  std::vector<std::int32_t> old_first_cover(old.node_count() + 1, 0);
  for (std::size_t c = 0; c < old.cover_count(); ++c) ++old_first_cover[old.cover_node[c] + 1];
  std::partial_sum(old_first_cover.begin(), old_first_cover.end(), old_first_cover.begin());
  // A cut cover's parent: the old cover of its node that its first element's parent had.
  std::vector<std::int32_t> rc_cover_parent(rc.cover_count(), -1);
  for (const std::int32_t e : from_cut)
    for (int c = 0; c < 3; ++c) {
      const std::int32_t rcov = rc.element_covers[3 * static_cast<std::size_t>(source_rc[e]) + c];
      if (rc_cover_parent[rcov] < 0)
        rc_cover_parent[rcov] = old.element_covers[3 * static_cast<std::size_t>(map.element_parent[e]) + c];
    }
  for (std::size_t n = 0; n < old.node_count(); ++n) {
    if (!t_node[n]) {
      for (std::int32_t c = old_first_cover[n]; c < old_first_cover[n + 1]; ++c) {
        old_cover_new[c] = static_cast<std::int32_t>(m.cover_node.size());
        m.cover_node.push_back(static_cast<std::int32_t>(n));
        m.cover_body.push_back(old.cover_body[c]);
        map.cover_parent.push_back(c);
      }
      continue;
    }
    for (std::int32_t rcov : rc_covers_of[n]) {
      rc_cover_new[rcov] = static_cast<std::int32_t>(m.cover_node.size());
      m.cover_node.push_back(static_cast<std::int32_t>(n));
      m.cover_body.push_back(rc.cover_body[rcov]);
      map.cover_parent.push_back(rc_cover_parent[rcov]);
    }
  }
  m.element_covers.resize(3 * ne);
  for (std::size_t e = 0; e < ne; ++e)
    for (int c = 0; c < 3; ++c) {
      const std::int32_t node = m.triangle_nodes[3 * static_cast<std::size_t>(m.element_triangle[e]) + c];
      m.element_covers[3 * e + c] =
          source_rc[e] >= 0 && t_node[node]
              ? rc_cover_new[rc.element_covers[3 * static_cast<std::size_t>(source_rc[e]) + c]]
              : old_cover_new[old.element_covers[3 * static_cast<std::size_t>(map.element_parent[e]) + c]];
    }
  // Contact edges from the cuts' own topology, not from rounded coordinates (an edge that rounds
  // to a point would run "the other way" in its own element): a kept element's from the old mesh,
  // a cut element's from the cut.
  {
    const ContactEdgesOf old_ce(old), rc_ce(rc);
    std::vector<std::int32_t> rc_new(rc.element_count(), -1);
    for (std::size_t e = 0; e < ne; ++e)
      if (source_rc[e] >= 0) rc_new[static_cast<std::size_t>(source_rc[e])] = static_cast<std::int32_t>(e);
    m.contact_edge.clear();
    m.contact_edge_element.clear();
    m.contact_edge_opposite.clear();
    auto add = [&](std::size_t e, std::int32_t v, std::int32_t across) {
      m.contact_edge.push_back(v);
      m.contact_edge_element.push_back(static_cast<std::int32_t>(e));
      m.contact_edge_opposite.push_back(across);
    };
    // The old contact edge of old element oe that starts at its loop vertex `local`, or -1 (by
    // position in the loop, not by coordinates: an edge that rounds to a point has company).
    auto old_edge = [&](std::int32_t oe, std::int32_t local) {
      const std::int32_t v = old.element_loop_offset[oe] + local;
      for (std::int32_t k = old_ce.first[oe]; k < old_ce.first[oe + 1]; ++k) {
        const std::int32_t i = old_ce.index[static_cast<std::size_t>(k)];
        if (old.contact_edge[i] == v) return i;
      }
      return -1;
    };
    auto across_old = [&](std::int32_t i) {
      const std::int32_t o = old.contact_edge_opposite[i];
      return o < 0 ? -1 : old_new[o];
    };
    for (std::size_t e = 0; e < ne; ++e) {
      const std::int32_t nb = m.element_loop_offset[e], nend = m.element_loop_offset[e + 1];
      if (source_rc[e] < 0) {
        const std::int32_t oe = map.element_parent[e], ob = old.element_loop_offset[oe];
        for (std::int32_t k = old_ce.first[oe]; k < old_ce.first[oe + 1]; ++k) {
          const std::int32_t i = old_ce.index[static_cast<std::size_t>(k)];
          add(e, nb + (old.contact_edge[i] - ob), across_old(i));
        }
        continue;
      }
      const std::size_t re = static_cast<std::size_t>(source_rc[e]);
      const std::int32_t rb = rc.element_loop_offset[re];
      for (std::int32_t k = rc_ce.first[re]; k < rc_ce.first[re + 1]; ++k) {
        const std::int32_t i = rc_ce.index[static_cast<std::size_t>(k)];
        const std::int32_t local = rc.contact_edge[i] - rb, n = nend - nb;
        // The cut saw R and the ring around it, so it knows whether anything lies across (an
        // edge's other side is in the next triangle); an element across in the ring is an old
        // one, named by the old mesh (this element is then an old one too: only R \ T borders
        // the ring).
        const std::int32_t rc_across = rc.contact_edge_opposite[i];
        std::int32_t across = rc_across >= 0 ? rc_new[static_cast<std::size_t>(rc_across)] : -1;
        if (rc_across >= 0 && across < 0 && matched[e]) {
          const std::int32_t oi = old_edge(map.element_parent[e], (local + match_rotation[e]) % n);
          if (oi >= 0) across = across_old(oi);
        }
        const std::int32_t v = nb + local;
        add(e, v, across);
      }
    }
  }
  link_blocks(m);
  map.seconds_splice = watch.seconds();
  return m;
}

}  // namespace nmm::pre
