// Contact detection (classic NMM / DDA, docs/physics.md §3).
//
// Broad phase: a Verlet list. Each candidate vertex keeps the candidate edges of other elements
// within reach R = 2·(d + β·h) of it (β = beside_edge: the narrow phase looks that far past an
// edge's ends; d = max(g_max, p_deep): the widest gap a contact is found at — d0, or the
// stepper's smaller reach — and the deepest a contact is followed to, below), found by a uniform
// grid of cell size max(mean candidate edge length, 2·R): every edge entered in the cells its box
// grown by R overlaps, every vertex meeting the edges of its own cell. Element edges are at most
// one mesh size long however large the blocks are, so each cell holds a bounded number of edges
// and the build grows about linearly with their number.
// The list is reused while no loop vertex has moved more than (R − d − β·h)/2 since the build:
// a vertex and a segment whose ends each moved at most m/2 have come at most m nearer, so every
// edge the narrow phase can accept (−p_deep ≤ g ≤ g_max, ω in [−β, 1 + β]: within d + β·h of
// the segment) is still in the list. Each vertex's edges ascend, as the grid gives them, so the
// narrow phase meets its candidates in the same order from a new list or an old one, and finds
// the same contacts: the list is a cache (no state of the run). A settling wall moves far less
// than R/4 per step, so most steps reuse the list.
//
// Narrow phase, for vertex P of element A and edge Q2 → Q3 of element B (loops are CCW, so the
// edge's outward normal is n = (t_y, −t_x) with t = (Q3 − Q2)/l):
//   - A ≠ B, and (P, B) not continuous (P coincides with a vertex of B seeing the same covers
//     with the same weights: the two can never separate, e.g. along a free surface inside one
//     block, or next to a crack tip whose covers are not split);
//   - ω = (P − Q2)·t / l in [0, 1] (within 1e-3): P lies beside the edge;
//   - gap g = (P − Q2)·n ≤ g_max (d0, or the stepper's smaller reach: time_stepper.cpp), and g ≥ −shallow (1e-3·h: a vertex missed for a step) unless
//     P was in closed contact with B's block after the last step, then g ≥ −min(p_max, d_last
//     + shallow), d_last how deep P was against that block at the end of the last step (a
//     contact sinks step by step; it does not jump onto another face of the block deeper down),
//     p_max = min(0.3·h, d0) (an accepted step leaves no contact deeper than g2·w0 < d0, and the
//     list holds no edge farther than that; a vertex deep inside another element without having
//     come in through a contact is near that edge from the wrong side, e.g. a corner of a block
//     near the far side of the same block), and never deeper than 0.35 of how far B and the
//     elements of its block around it reach behind the edge (a mesh coarser than the blocks:
//     0.3·h can exceed a block); a negative gap must also mean that P lies inside element B — or,
//     near an end of the edge and at most 0.05·h deep, inside an element of B's block sharing a
//     mesh node with it (a vertex sinking through an edge at a mesh node enters the triangle below
//     the node, which does not own the edge): past a corner of the block, P can be behind the line
//     of an edge without being inside it at all;
//   - the edge faces P: n · n_P < −0.2, n_P the mean outward normal of P's candidate edges.
//   - single pass along flat stretches: a vertex that is not a corner of its block's boundary
//     (a 180° vertex: where mesh lines cut a straight boundary or joint) touches only if its
//     outward normal points down (n_y < 0, or n_y = 0 and n_x < 0) — against the other face of
//     its own joint, its normal as cut (the two faces' are exactly opposite there, whatever
//     round-off tilts them by as they deform; a vertical joint is the case), against anything
//     else its normal now — or if it pokes into the
//     other side between that side's vertices deeper than max(1e-4·h, 2·Vm) (beyond what a
//     contact spring or a joint's closure lets a face sink, so faces pressed together still
//     carry one set of contacts, whose tributary lengths add up to the joint's length). Two faces
//     pressed together then carry one set of contacts, not two that fight each other (with
//     deformable blocks some of a doubled set always end up in tension and the states chatter); the
//     faces of a joint have exactly opposite normals as cut, so exactly one of them is that side
//     everywhere. Corners always touch.
// Each vertex keeps one edge per other block (the angle rule of DDA, here for angle–edge and
// angle–angle alike): the smallest |g|, then the edge most opposite to P's own normal (the
// entrance edge), then the lower index. Edge–edge contact is the two vertex–edge contacts of its
// end points. Per block, as DDA detects contacts block pair by block pair: a corner at a concave
// junction of two other blocks (the bottom corner of a block standing on a base beside another
// block) touches both. With one edge per vertex in all, such a corner held only one of them and
// swapped every step — on the base, it sank and the other face's gap became the smaller; against
// the face, the base let it rise — a period-2 motion that no solver tolerance removes
// (tests/test_hard_cases.cpp, BlocksSideBySideBesideMeshNodesAreStill).
// Where two vertices meet, within 0.01·h, and each picks an edge of the other's element ending
// at the other (angle–angle: matching vertices on the two faces of a joint, a block corner
// passing over a vertex of the surface it slides on), one point is one contact: the one that
// was closed is kept, else the one of the lower vertex index.
#include "solver/contact/contact_detection.h"

#include "solver/contact/contact_tolerances.h"
#include "common/vec2.h"
#include "common/math_constants.h"
#include "common/ring_geometry.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace nmm::solve {

bool ContactTopology::is_continuous(std::int32_t vertex, std::int32_t element) const {
  if (continuous_offset.empty())
    return std::binary_search(continuous.begin(), continuous.end(), std::make_pair(vertex, element));
  for (std::int32_t i = continuous_offset[vertex]; i < continuous_offset[vertex + 1]; ++i)
    if (continuous[i].second == element) return true;
  return false;
}

void ClosedContacts::index(std::size_t vertices) {
  first.assign(vertices + 1, 0);
  for (const auto& [v, block] : pairs) ++first[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
}

std::pair<std::size_t, std::size_t> ClosedContacts::range(std::int32_t v) const {
  if (!first.empty())
    return {static_cast<std::size_t>(first[static_cast<std::size_t>(v)]),
            static_cast<std::size_t>(first[static_cast<std::size_t>(v) + 1])};
  const auto lo = std::lower_bound(pairs.begin(), pairs.end(), std::make_pair(v, std::int32_t{-1}));
  auto hi = lo;
  while (hi != pairs.end() && hi->first == v) ++hi;
  return {static_cast<std::size_t>(lo - pairs.begin()), static_cast<std::size_t>(hi - pairs.begin())};
}

bool ClosedContacts::with(std::int32_t v, std::int32_t block) const {
  const auto [lo, hi] = range(v);
  for (std::size_t i = lo; i < hi; ++i)
    if (pairs[i].second == block) return true;
  return false;
}

bool ClosedContacts::holds_with(std::int32_t v, std::int32_t block) const {
  if (holds.empty()) return false;
  const auto [lo, hi] = range(v);
  for (std::size_t i = lo; i < hi; ++i)
    if (pairs[i].second == block) return holds[i] != 0;
  return false;
}

double ClosedContacts::depth_with(std::int32_t v, std::int32_t block, double unknown) const {
  const auto [lo, hi] = range(v);
  for (std::size_t i = lo; i < hi; ++i)
    if (pairs[i].second == block) return depth.empty() ? unknown : depth[i];
  return -1;
}

namespace {

// Crossing-number test of (x, y) in element e's loop (slits and bridges cancel).
bool inside_element(const ContactTopology& t, const std::vector<double>& xy, std::int32_t first,
                    double x, double y) {
  bool in = false;
  std::int32_t j = t.prev[first], i = first;
  do {
    const double xi = xy[2 * i], yi = xy[2 * i + 1], xj = xy[2 * j], yj = xy[2 * j + 1];
    if (ray_crosses(xi, yi, xj, yj, x, y)) in = !in;
    j = i;
    i = t.next[i];
  } while (i != first);
  return in;
}

// Whether (x, y) lies within eps of the loop starting at `first`: on its boundary, as far as
// round-off can tell. A point there is no deeper in the element than on its rim — the corner of a
// hairline element a crack cut a round-off from a mesh edge — and makes no deep contact.
bool on_loop(const ContactTopology& t, const std::vector<double>& xy, std::int32_t first, double x, double y,
             double eps) {
  std::int32_t i = first;
  do {
    const std::int32_t j = t.next[i];
    const double ax = xy[2 * i], ay = xy[2 * i + 1], dx = xy[2 * j] - ax, dy = xy[2 * j + 1] - ay;
    const double l2 = dx * dx + dy * dy;
    const double s = l2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / l2, 0.0, 1.0) : 0.0;
    const double ox = ax + s * dx - x, oy = ay + s * dy - y;
    if (ox * ox + oy * oy <= eps * eps) return true;
    i = j;
  } while (i != first);
  return false;
}

// Whether a vertex `depth` (m) below the line through (qx, qy) with outward normal (ex, ey) lies
// deeper than `extent` times how far the elements of element e's block around it (those sharing
// a mesh node with it: a sliver's full neighbours too) reach behind that line — the largest depth
// of their loop vertices below it. The reach only grows vertex by vertex, and extent·r with it,
// so the answer is known (no) at the first vertex deep enough: element e's own far vertex, for
// nearly every contact, instead of every vertex of the 3–12 elements around it (the same answer
// as the full maximum, bit for bit: a product by a positive constant is monotone).
bool deeper_than_reach(const ContactTopology& t, const std::vector<double>& xy, std::int32_t e,
                       double qx, double qy, double ex, double ey, double depth, double extent) {
  double r = 0;
  for (std::int32_t k = t.near_offset[e]; k < t.near_offset[e + 1]; ++k) {
    const std::int32_t first = t.first_vertex[t.near_elements[k]];
    std::int32_t i = first;
    do {
      r = std::max(r, -((xy[2 * i] - qx) * ex + (xy[2 * i + 1] - qy) * ey));
      if (!(depth > extent * r)) return false;
      i = t.next[i];
    } while (i != first);
  }
  return true;
}

// P inside element e or an element of its block sharing a mesh node with it.
bool inside_near(const ContactTopology& t, const std::vector<double>& xy, std::int32_t e, double x,
                 double y) {
  for (std::int32_t k = t.near_offset[e]; k < t.near_offset[e + 1]; ++k)
    if (inside_element(t, xy, t.first_vertex[t.near_elements[k]], x, y)) return true;
  return false;
}

// Weights of the element's three covers at (x, y), from the mesh's node positions.
void cover_weights(const Mesh& m, std::size_t e, double x, double y, double w[3]) {
  const std::int32_t t = m.element_triangle[e];
  double p[6];
  for (int k = 0; k < 3; ++k) {
    const std::int32_t n = m.triangle_nodes[3 * t + k];
    p[2 * k] = m.node_xy[2 * n];
    p[2 * k + 1] = m.node_xy[2 * n + 1];
  }
  const double det = (p[2] - p[0]) * (p[5] - p[1]) - (p[4] - p[0]) * (p[3] - p[1]);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    w[k] = ((p[2 * i] - x) * (p[2 * j + 1] - y) - (p[2 * j] - x) * (p[2 * i + 1] - y)) / det;
  }
}

}  // namespace

ContactTopology build_contact_topology(const Mesh& mesh) {
  ContactTopology t;
  t.mesh_size = mesh.mesh_size;
  t.master_depth = kContactTolerances.master_depth * mesh.mesh_size;
  const std::size_t nv = mesh.loop_vertex_count();
  t.next.resize(nv);
  t.prev.resize(nv);
  t.element_of.resize(nv);
  t.edge_candidate.assign(nv, 0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::int32_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
    for (std::int32_t i = 0; i < n; ++i) {
      t.next[b + i] = b + (i + 1) % n;
      t.prev[b + i] = b + (i + n - 1) % n;
      t.element_of[b + i] = static_cast<std::int32_t>(e);
    }
  }
  for (std::int32_t v : mesh.contact_edge) t.edge_candidate[v] = 1;
  t.edges = mesh.contact_edge;
  t.block_of = mesh.element_block;
  {
    const std::size_t ne = mesh.element_count();
    t.first_vertex.assign(mesh.element_loop_offset.begin(), mesh.element_loop_offset.end() - 1);
    std::vector<std::vector<std::int32_t>> at_node(mesh.node_count());
    for (std::size_t e = 0; e < ne; ++e)
      for (int k = 0; k < 3; ++k)
        at_node[mesh.triangle_nodes[3 * mesh.element_triangle[e] + k]].push_back(static_cast<std::int32_t>(e));
    t.near_offset.assign(1, 0);
    for (std::size_t e = 0; e < ne; ++e) {
      std::vector<std::int32_t> near;
      for (int k = 0; k < 3; ++k)
        for (std::int32_t f : at_node[mesh.triangle_nodes[3 * mesh.element_triangle[e] + k]])
          if (mesh.element_block[f] == mesh.element_block[e]) near.push_back(f);
      std::sort(near.begin(), near.end());
      near.erase(std::unique(near.begin(), near.end()), near.end());
      t.near_elements.insert(t.near_elements.end(), near.begin(), near.end());
      t.near_offset.push_back(static_cast<std::int32_t>(t.near_elements.size()));
    }
  }
  // Corners: at each point of a block's boundary, the candidate edges of that block meeting
  // there; a point with exactly two, turning by less than 10°, is flat, all others are corners.
  t.corner.assign(nv, 1);
  {
    std::map<std::tuple<double, double, std::int32_t>, std::vector<std::int32_t>> at_point;
    for (std::size_t v = 0; v < nv; ++v)
      if (t.edge_candidate[v] || t.edge_candidate[t.prev[v]])
        at_point[{mesh.loop_xy[2 * v], mesh.loop_xy[2 * v + 1], t.block_of[t.element_of[v]]}]
            .push_back(static_cast<std::int32_t>(v));
    for (const auto& [key, vs] : at_point) {
      std::vector<std::pair<double, double>> out_dirs;  // unit directions of edges leaving the point
      for (std::int32_t v : vs) {
        const double x = mesh.loop_xy[2 * v], y = mesh.loop_xy[2 * v + 1];
        for (std::int32_t w : {t.next[v], t.prev[v]}) {
          const std::int32_t s0 = w == t.next[v] ? v : w;  // first vertex of the edge v–w
          if (!t.edge_candidate[s0]) continue;
          const double dx = mesh.loop_xy[2 * w] - x, dy = mesh.loop_xy[2 * w + 1] - y;
          const double l = std::hypot(dx, dy);
          if (l > 0) out_dirs.emplace_back(dx / l, dy / l);
        }
      }
      // The same boundary edge seen from both ends' elements is one direction: dedupe.
      std::vector<std::pair<double, double>> dirs;
      for (const auto& d : out_dirs) {
        bool seen = false;
        for (const auto& e : dirs) seen |= d.first * e.first + d.second * e.second > 1 - kContactTolerances.same_direction;
        if (!seen) dirs.push_back(d);
      }
      const bool flat = dirs.size() == 2 &&
                        dirs[0].first * dirs[1].first + dirs[0].second * dirs[1].second <
                            -std::cos(kContactTolerances.flat_turn_deg * kPi / 180.0);
      if (flat)
        for (std::int32_t v : vs) t.corner[v] = 0;
    }
  }
  for (std::size_t v = 0; v < nv; ++v)
    if (t.edge_candidate[v] || t.edge_candidate[t.prev[v]])
      t.vertices.push_back(static_cast<std::int32_t>(v));

  // The side of a joint's faces in the single pass, decided as cut: the two faces of a joint lie
  // on the same loop edges run in opposite directions, so their normals are exactly opposite
  // here and exactly one face is the side that does not touch. Decided from the normals as they
  // deform, a vertical joint (n_y = 0 as cut) had both faces on that side wherever its faces
  // tilted a round-off apart in opposite senses, and nothing held them: data/tunnel_inflow.json
  // with J1 along x = 20, through a column of mesh nodes, passed 1.2 mm through itself.
  t.edge_joint = mesh.loop_edge_joint;
  if (t.edge_joint.size() != nv) t.edge_joint.assign(nv, -1);
  t.face_joint.assign(nv, -1);
  t.face_master.assign(nv, 0);
  for (std::int32_t v : t.vertices) {
    if (t.corner[v]) continue;
    std::int32_t joint = -1;
    bool one_joint = true;
    double nx = 0, ny = 0;
    for (std::int32_t s : {t.prev[v], v}) {
      if (!t.edge_candidate[s]) continue;
      const std::int32_t j = t.edge_joint[s];
      if (j < 0 || (joint >= 0 && j != joint)) one_joint = false;
      joint = j;
      const std::int32_t f = t.next[s];
      const double dx = mesh.loop_xy[2 * f] - mesh.loop_xy[2 * s],
                   dy = mesh.loop_xy[2 * f + 1] - mesh.loop_xy[2 * s + 1];
      const double l = length(dx, dy);
      if (l > kContactTolerances.degenerate_edge * mesh.mesh_size) {
        nx += dy / l;
        ny -= dx / l;
      }
    }
    if (!one_joint || joint < 0 || (nx == 0 && ny == 0)) continue;
    t.face_joint[v] = joint;
    t.face_master[v] = ny > 0 || (ny == 0 && nx > 0);
  }

  // Continuity: candidate vertices at the same place (the mesh file rounds each exact point to
  // the same double) whose elements see the same covers with the same weights there.
  std::map<std::pair<double, double>, std::vector<std::int32_t>> at;
  for (std::int32_t v : t.vertices) at[{mesh.loop_xy[2 * v], mesh.loop_xy[2 * v + 1]}].push_back(v);
  for (const auto& [xy, vs] : at) {
    if (vs.size() < 2) continue;
    for (std::int32_t p : vs)
      for (std::int32_t q : vs) {
        const std::int32_t ea = t.element_of[p], eb = t.element_of[q];
        if (ea == eb) continue;
        double wa[3], wb[3];
        cover_weights(mesh, ea, xy.first, xy.second, wa);
        cover_weights(mesh, eb, xy.first, xy.second, wb);
        // Cover → weight, dropping covers with no weight at this point.
        std::map<std::int32_t, double> ca, cb;
        for (int k = 0; k < 3; ++k) {
          if (std::abs(wa[k]) > kContactTolerances.same_weight) ca[mesh.element_covers[3 * ea + k]] += wa[k];
          if (std::abs(wb[k]) > kContactTolerances.same_weight) cb[mesh.element_covers[3 * eb + k]] += wb[k];
        }
        bool same = ca.size() == cb.size();
        for (auto ia = ca.begin(), ib = cb.begin(); same && ia != ca.end(); ++ia, ++ib)
          same = ia->first == ib->first && std::abs(ia->second - ib->second) < kContactTolerances.same_weight;
        if (same) t.continuous.emplace_back(p, eb);
      }
  }
  {
    std::vector<std::vector<std::int32_t>> mirror(nv);
    for (const auto& [xy, vs] : at)
      for (std::int32_t p : vs)
        for (std::int32_t q : vs)
          if (t.block_of[t.element_of[p]] != t.block_of[t.element_of[q]]) mirror[p].push_back(q);
    t.mirror_offset.assign(1, 0);
    for (const auto& m : mirror) {
      t.mirrors.insert(t.mirrors.end(), m.begin(), m.end());
      t.mirror_offset.push_back(static_cast<std::int32_t>(t.mirrors.size()));
    }
  }
  std::sort(t.continuous.begin(), t.continuous.end());
  t.continuous.erase(std::unique(t.continuous.begin(), t.continuous.end()), t.continuous.end());
  t.continuous_offset.assign(nv + 1, 0);
  for (const auto& [v, e] : t.continuous) ++t.continuous_offset[v + 1];
  for (std::size_t v = 0; v < nv; ++v) t.continuous_offset[v + 1] += t.continuous_offset[v];
  return t;
}

namespace {

void edge_geometry(const ContactTopology& topo, const std::vector<double>& xy,
                   std::vector<CandidateEdgeFrame>& geometry) {
  geometry.resize(topo.edges.size());
  for (std::size_t k = 0; k < topo.edges.size(); ++k) {
    const std::int32_t q2 = topo.edges[k], q3 = topo.next[q2];
    const double dx = xy[2 * q3] - xy[2 * q2], dy = xy[2 * q3 + 1] - xy[2 * q2 + 1];
    const double l = length(dx, dy);
    geometry[k] = {xy[2 * q2], xy[2 * q2 + 1], dx / l, dy / l, l, q2, topo.element_of[q2],
                   l > kContactTolerances.degenerate_edge * topo.mesh_size};
  }
}

// The list holds for a search within `need` of the edges while no loop vertex has moved more
// than half its margin (reach − need) since it was built: a vertex and a segment whose end
// points each moved at most m/2 have come at most m nearer.
bool list_holds(const CandidateList& list, const std::vector<double>& xy, double need) {
  if (list.builds == 0 || list.xy.size() != xy.size() || !(list.reach > need)) return false;
  const double half = 0.5 * (list.reach - need), half2 = half * half;
  for (std::size_t i = 0; i < xy.size(); i += 2) {
    const double dx = xy[i] - list.xy[i], dy = xy[i + 1] - list.xy[i + 1];
    if (dx * dx + dy * dy > half2) return false;
  }
  return true;
}

// For every candidate vertex, the candidate edges of other elements, not continuous with it,
// within reach = 2·need of it (need: the search distance and how far past its ends an edge
// reaches), by a uniform grid: cell the edges' mean length (at least 2·reach; not the mesh
// size: with a mesh coarser than the blocks a cell of h held the edges of several blocks), every
// edge entered in the cells its box grown by reach overlaps, a vertex meeting the edges of its
// own cell. Each vertex's edges ascend, as the grid's cells held them, so the narrow phase meets
// candidates in the same order whichever list it reads.
// The vertices and edges of blocks all of whose elements are removed (detect_contacts'
// `removed`) get no candidates and go into no cell.
void build_candidate_list(const ContactTopology& topo, const std::vector<double>& xy,
                          const std::vector<CandidateEdgeFrame>& geometry, double need, CandidateList& list,
                          const std::vector<std::uint8_t>* removed) {
  const double reach = kContactTolerances.list_reach * need;
  list.reach = reach;
  list.xy = xy;
  ++list.builds;
  double x0 = xy[0], y0 = xy[1], mean_length = 0;
  for (std::size_t i = 0; i < xy.size(); i += 2) {
    x0 = std::min(x0, xy[i]);
    y0 = std::min(y0, xy[i + 1]);
  }
  for (const CandidateEdgeFrame& g : geometry) mean_length += g.l;
  mean_length /= static_cast<double>(geometry.size());
  const double cell = std::max(mean_length, 2 * reach);
  auto cell_of = [&](double x, double y) {
    return std::make_pair(static_cast<std::int64_t>(std::floor((x - x0) / cell)),
                          static_cast<std::int64_t>(std::floor((y - y0) / cell)));
  };
  // Cell (i, j) → one 64-bit key; unsigned arithmetic (shifting a negative index is undefined).
  auto key = [](std::int64_t i, std::int64_t j) {
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(i) << 32) ^
                                     (static_cast<std::uint64_t>(j) & 0xffffffffu));
  };
  // (cell key, index into topo.edges), sorted
  std::vector<std::pair<std::int64_t, std::int32_t>> entries;
  entries.reserve(topo.edges.size() * 4);
  // [block] every element of it removed (a block with one removed element in it keeps its edges:
  // a vertex's one edge per block is chosen among all of them, as without the list).
  std::vector<std::uint8_t> block_out;
  if (removed && removed->size() == topo.block_of.size()) {
    std::int32_t blocks = 0;
    for (const std::int32_t b : topo.block_of) blocks = std::max(blocks, b + 1);
    block_out.assign(static_cast<std::size_t>(blocks), 1);
    for (std::size_t e = 0; e < removed->size(); ++e)
      if (!(*removed)[e]) block_out[static_cast<std::size_t>(topo.block_of[e])] = 0;
  }
  for (std::size_t k = 0; k < topo.edges.size(); ++k) {
    const std::int32_t e = topo.edges[k], f = topo.next[e];
    if (!block_out.empty() && block_out[static_cast<std::size_t>(topo.block_of[static_cast<std::size_t>(geometry[k].element)])])
      continue;
    const auto [i0, j0] = cell_of(std::min(xy[2 * e], xy[2 * f]) - reach, std::min(xy[2 * e + 1], xy[2 * f + 1]) - reach);
    const auto [i1, j1] = cell_of(std::max(xy[2 * e], xy[2 * f]) + reach, std::max(xy[2 * e + 1], xy[2 * f + 1]) + reach);
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j) entries.emplace_back(key(i, j), static_cast<std::int32_t>(k));
  }
  std::sort(entries.begin(), entries.end());
  list.offset.assign(1, 0);
  list.edges.clear();
  for (std::int32_t p : topo.vertices) {
    const double px = xy[2 * p], py = xy[2 * p + 1];
    const std::int32_t ea = topo.element_of[p];
    if (!block_out.empty() && block_out[static_cast<std::size_t>(topo.block_of[static_cast<std::size_t>(ea)])]) {
      list.offset.push_back(static_cast<std::int32_t>(list.edges.size()));
      continue;
    }
    const auto [ci, cj] = cell_of(px, py);
    const std::int64_t k = key(ci, cj);
    for (auto it = std::lower_bound(entries.begin(), entries.end(), std::make_pair(k, std::int32_t{-1}));
         it != entries.end() && it->first == k; ++it) {
      const CandidateEdgeFrame& g = geometry[static_cast<std::size_t>(it->second)];
      if (g.element == ea) continue;
      // Distance from P to the segment (to its start if it has no direction).
      const double rx = px - g.x, ry = py - g.y;
      const double s = g.usable ? std::clamp(rx * g.tx + ry * g.ty, 0.0, g.l) : 0.0;
      const double ox = rx - (g.usable ? s * g.tx : 0.0), oy = ry - (g.usable ? s * g.ty : 0.0);
      if (ox * ox + oy * oy > reach * reach) continue;
      if (topo.is_continuous(p, g.element)) continue;
      list.edges.push_back(it->second);
    }
    list.offset.push_back(static_cast<std::int32_t>(list.edges.size()));
  }
}

}  // namespace

std::vector<ContactCandidate> detect_contacts(const ContactTopology& topo,
                                              const std::vector<double>& xy, double d0,
                                              double shallow,
                                              const ClosedContacts& closed,
                                              DetectionStats* stats, ElementPairs* near_pairs,
                                              CandidateList* list, double open_gap,
                                              const std::vector<std::uint8_t>* removed) {
  std::vector<ContactCandidate> out;
  if (topo.edges.empty()) return out;
  const ContactTolerances& tl = kContactTolerances;
  const double p_max = std::min(tl.closed_depth * topo.mesh_size, d0);
  // The deepest a vertex may be against an edge and be found: a new contact's depth, or a
  // closed one's depth after the last step plus that, at most p_max (the narrow phase below).
  const double new_depth_max = std::max(shallow, tl.gap_round_off * topo.mesh_size);
  double deep_max = new_depth_max;
  if (!closed.pairs.empty()) {
    double was = closed.depth.empty() ? p_max : 0.0;
    for (double d : closed.depth) was = std::max(was, d);
    deep_max = std::max(deep_max, std::min(p_max, was + new_depth_max));
  }
  // The widest gap a contact is found at: d0, or less where the stepper checks that no vertex
  // moves more than half of it in the step (time_stepper.cpp, the reach check) — unless a vertex
  // may be found deeper than that: each vertex keeps the edge of smallest |g| per block, and
  // only while every accepted depth is below the gap looked to is that edge the one d0 would
  // give (an open edge left out, g > gap_max, is farther than any kept one), so that the
  // contacts found are exactly d0's open at most gap_max wide. With gap_max = d0 the list's
  // need is d0's as before (p_max ≤ d0): the same lists, bit for bit.
  const double gap_max = open_gap >= 0 && deep_max <= open_gap ? std::min(open_gap, d0) : d0;

  // The candidates: the Verlet list, built anew when a vertex has moved too far for it; it also
  // keeps the call's working arrays from one call to the next.
  CandidateList own;
  CandidateList& cand = list ? *list : own;
  // Each candidate edge's start, unit tangent and length, once per call (not once per vertex
  // that meets it: about 25 vertices per edge in a brick wall).
  std::vector<CandidateEdgeFrame>& geometry = cand.frames;
  edge_geometry(topo, xy, geometry);
  out.reserve(cand.last_found + cand.last_found / 8 + 16);
  const double beside = tl.beside_edge * topo.mesh_size;  // how far past its ends an edge reaches
  const double need = std::max(gap_max, deep_max) + beside;
  if (!list_holds(cand, xy, need)) {
    build_candidate_list(topo, xy, geometry, need, cand, removed);
    if (stats) ++stats->list_builds;
  }

  std::size_t tested = 0;
  struct Best {
    std::int32_t block;
    ContactCandidate c;
    double abs, face;
  };
  std::vector<Best> bests;
  for (std::size_t vi = 0; vi < topo.vertices.size(); ++vi) {
    const std::int32_t p = topo.vertices[vi];
    const double px = xy[2 * p], py = xy[2 * p + 1];
    const std::int32_t ea = topo.element_of[p];
    // P's own outward normal: the mean of its candidate edges' normals. An edge of no length (two
    // loop vertices a round-off apart, where a crack was cut within round-off of a mesh node) has
    // no direction: its unit normal is noise, and counted it turned P's normal by up to 90°, so
    // that the corner of a crack face "faced" an edge it lies beside and the real vertex at that
    // point faced none (a uniaxial specimen, h 0.125 m, dynamic: such a corner sank 1 mm into
    // the fragment beside it, over steps, held by nothing).
    double nx = 0, ny = 0;
    for (std::int32_t s : {topo.prev[p], p}) {
      if (!topo.edge_candidate[s]) continue;
      const std::int32_t f = topo.next[s];
      const double dx = xy[2 * f] - xy[2 * s], dy = xy[2 * f + 1] - xy[2 * s + 1];
      const double l = length(dx, dy);
      if (l > tl.degenerate_edge * topo.mesh_size) {
        nx += dy / l;
        ny -= dx / l;
      }
    }
    const double nl = length(nx, ny);
    if (nl < tl.slit_tip_normal) continue;  // the tip of a slit: both faces are this element's own
    nx /= nl;
    ny /= nl;
    // Single pass: an upward-facing flat vertex only touches where it pokes clearly into the
    // other side (between that side's vertices; it must still be held).
    const bool master_side = !topo.corner[p] && (ny > 0 || (ny == 0 && nx > 0));
    // One contact is kept per joint point (the mirror rule below). When the kept one is lost —
    // its vertex slid a fraction of a µm off the other face, as a corner can with Poisson
    // expansion — the other face's vertex there takes over: its depth is that contact's closure,
    // not a new contact's (which must be shallow). mirror_closed: the blocks of coincident vertices closed against P's block (at most a few).
    std::int32_t mirror_closed[4];
    double mirror_depth[4];
    int n_mirror_closed = 0;
    for (std::int32_t i = topo.mirror_offset[p]; !closed.pairs.empty() && i < topo.mirror_offset[p + 1]; ++i) {
      const std::int32_t m = topo.mirrors[i];
      const double d = closed.depth_with(m, topo.block_of[ea], p_max);
      if (n_mirror_closed < 4 && d >= 0 && length(xy[2 * m] - px, xy[2 * m + 1] - py) <= tl.same_point * topo.mesh_size) {
        mirror_depth[n_mirror_closed] = d;
        mirror_closed[n_mirror_closed++] = topo.block_of[topo.element_of[m]];
      }
    }
    const auto [closed_lo, closed_hi] = closed.range(p);
    bests.clear();
    for (std::int32_t ci = cand.offset[vi]; ci < cand.offset[vi + 1]; ++ci) {
      const CandidateEdgeFrame& eg = geometry[static_cast<std::size_t>(cand.edges[ci])];
      const std::int32_t q2 = eg.q2, eb = eg.element;  // of another element, not continuous with P
      ++tested;
      if (!eg.usable) continue;
      const double tx = eg.tx, ty = eg.ty, ex = ty, ey = -tx;
      const double rx = px - eg.x, ry = py - eg.y;
      const double omega = (rx * tx + ry * ty) / eg.l;
      // A little past the ends: a vertex right above a vertex of the other face projects onto
      // both neighbouring edges at ω ≈ 0 or 1 and lies inside only one of their elements;
      // round-off must not push it off that one (the point is clamped onto the edge).
      if (omega < -tl.beside_edge || omega > 1 + tl.beside_edge) continue;
      const double g = rx * ex + ry * ey;
      // Cheap geometric rejections first (continuity was left out when the list was built).
      if (g > gap_max || (g < -d0 && g < -p_max)) continue;
      if (near_pairs && std::abs(g) <= gap_max) near_pairs->emplace_back(ea, eb);
      const std::int32_t block_b = topo.block_of[eb];
      // How deep P may be against B's block: a new contact's depth, or — closed against that
      // block after the last step — as deep as it was then plus a new contact's depth, at most
      // p_max. (Against the block at any depth up to p_max, a vertex that slid off its own face
      // took another face of the same block 47 mm deep at the step's start, and its spring threw
      // a cover 5 cm at every Δt: the step-path slope, h 0.5 m, dynamic.)
      double was_depth = -1;
      for (std::size_t i = closed_lo; i < closed_hi; ++i)
        if (closed.pairs[i].second == block_b) was_depth = std::max(was_depth, closed.depth.empty() ? p_max : closed.depth[i]);
      for (int i = 0; i < n_mirror_closed; ++i)
        if (mirror_closed[i] == block_b) was_depth = std::max(was_depth, mirror_depth[i]);
      const bool was_closed = was_depth >= 0;
      const double eps = tl.gap_round_off * topo.mesh_size;
      const double new_depth = std::max(shallow, eps);
      // Against the other face of its own joint, a face's side is the one decided as cut. A face
      // of a cohesive crack that holds tension is found from either side as well: its contact
      // carries the crack's cohesion and damage, and where the side rule dropped both faces'
      // vertices (a vertex joining two segments of a crack is sided by its normal now, |ny| ~
      // 1e-5, which the faces' own deformation flips) the cohesion was lost (a bar's crack of
      // 0.19 m kept 0.05 m of its faces two steps after its peak). The mirror rule below keeps one
      // of the two.
      const bool master = topo.face_joint[p] >= 0 && topo.face_joint[p] == topo.edge_joint[q2]
                              ? topo.face_master[p] != 0
                              : master_side;
      if (master && g >= -topo.master_depth && !closed.holds_with(p, block_b)) continue;
      if (g > gap_max || g < -(was_closed ? std::min(p_max, was_depth + new_depth) : new_depth)) continue;
      // The edge must face P (checked before the tests inside B below, which cost loops over
      // elements: every test here only drops a candidate, so their order does not change what
      // is kept).
      const double face = nx * ex + ny * ey;  // −1: exactly opposite
      if (face > tl.facing_cos) continue;
      if (g < -eps && deeper_than_reach(topo, xy, eb, eg.x, eg.y, ex, ey, -g, tl.closed_extent))
        continue;
      // Inside B: tested at P moved onto the edge's span (ω within [β, 1 − β], β = beside_edge),
      // so a vertex a round-off past the end of the edge — the corner of one block over the
      // corner of the other, both moved apart by the same Poisson expansion — is judged as the
      // vertex beside the edge that it is. Tested where it is, such a corner pair lost both
      // contacts at once (each corner a few 1e-7 m outside the other block) and the joint's end
      // lost its tributary length: it closed more there than in the middle.
      const double shift = (std::clamp(omega, tl.beside_edge, 1 - tl.beside_edge) - omega) * eg.l;
      const double ix = px + shift * tx, iy = py + shift * ty;
      if (g < -eps && (!inside_element(topo, xy, topo.first_vertex[eb], ix, iy) ||
                       on_loop(topo, xy, topo.first_vertex[eb], ix, iy, eps))) {
        // Sunk at a mesh node, next to an end of the edge: the element below the node may hold
        // it instead. Only there, and only shallow; elsewhere a vertex outside B is not in contact.
        const bool near_end = omega < tl.node_sink_omega || omega > 1 - tl.node_sink_omega;
        if (!near_end || g < -tl.node_sink_depth * topo.mesh_size || !inside_near(topo, xy, eb, ix, iy)) continue;
      }
      const double ag = std::abs(g);
      const double tol = tl.gap_round_off * topo.mesh_size;
      Best* b = nullptr;
      for (Best& x : bests)
        if (x.block == block_b) b = &x;
      const bool better = !b || ag < b->abs - tol ||
                          (ag <= b->abs + tol && (face < b->face - tl.facing_tie ||
                                                  (face <= b->face + tl.facing_tie && q2 < b->c.edge)));
      if (!better) continue;
      if (!b) {
        bests.push_back({});
        b = &bests.back();
      }
      *b = {block_b, {p, q2, ea, eb, std::clamp(omega, 0.0, 1.0), g}, ag, face};
    }
    // In the order of the blocks, so that the output does not depend on the grid's order.
    std::sort(bests.begin(), bests.end(), [](const Best& a, const Best& b) { return a.block < b.block; });
    for (const Best& b : bests) out.push_back(b.c);
  }
  cand.last_found = out.size();
  // One contact per point of a joint: drop the mirror of a contact between coincident vertices.
  std::vector<char>& drop = cand.drop;
  drop.assign(out.size(), 0);
  const double tol = tl.same_point * topo.mesh_size;
  auto near = [&](std::int32_t u, std::int32_t v) {
    return length(xy[2 * u] - xy[2 * v], xy[2 * u + 1] - xy[2 * v + 1]) <= tol;
  };
  // `out` ascends by (vertex, block of the edge), one contact per pair: the vertices in order,
  // each one's by block. first_out[v]: v's first contact in `out`, or −1 (with a binary search
  // over `out` per contact this part took 102 of detection's 324 µs a step on the 10 × 10 brick
  // wall at h = 2 m, 420 of 1,120 on the 20 × 20; about 35 and 110 µs now).
  // Kept at −1 between calls (reset below for the vertices set here): no pass over every loop
  // vertex per call.
  std::vector<std::int32_t>& first_out = cand.first_out;
  if (first_out.size() != topo.next.size()) first_out.assign(topo.next.size(), -1);
  for (std::size_t c = out.size(); c-- > 0;) first_out[static_cast<std::size_t>(out[c].vertex)] = static_cast<std::int32_t>(c);
  auto contact_of = [&](std::int32_t v, std::int32_t block) -> std::size_t {
    const std::int32_t f = first_out[static_cast<std::size_t>(v)];
    if (f < 0) return out.size();
    for (std::size_t k = static_cast<std::size_t>(f); k < out.size() && out[k].vertex == v; ++k)
      if (topo.block_of[out[k].elem_b] == block) return k;
    return out.size();
  };
  for (std::size_t c = 0; c < out.size(); ++c) {
    const ContactCandidate& a = out[c];
    for (std::int32_t q : {a.edge, topo.next[a.edge]}) {
      if (!near(q, a.vertex)) continue;
      // q's contact against P's block, if any
      const std::size_t m = contact_of(q, topo.block_of[a.elem_a]);
      if (m == out.size() || drop[m] || drop[c]) continue;
      const ContactCandidate& b = out[m];
      if (!near(b.edge, a.vertex) && !near(topo.next[b.edge], a.vertex)) continue;
      const bool a_closed = closed.with(a.vertex, topo.block_of[a.elem_b]);
      const bool q_closed = closed.with(q, topo.block_of[b.elem_b]);
      const bool keep_a = a_closed != q_closed ? a_closed : a.vertex < q;
      drop[keep_a ? m : c] = 1;
    }
  }
  if (near_pairs) {
    std::sort(near_pairs->begin(), near_pairs->end());
    near_pairs->erase(std::unique(near_pairs->begin(), near_pairs->end()), near_pairs->end());
  }
  for (const ContactCandidate& c : out) first_out[static_cast<std::size_t>(c.vertex)] = -1;
  // The kept ones, in order, moved down over the dropped ones (no second list).
  std::size_t kept = 0;
  for (std::size_t c = 0; c < out.size(); ++c)
    if (!drop[c]) out[kept++] = out[c];
  out.resize(kept);
  if (stats) {
    stats->pairs_tested += tested;
    stats->contacts += kept;
  }
  return out;
}

}  // namespace nmm::solve
