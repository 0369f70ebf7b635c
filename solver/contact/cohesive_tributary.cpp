// Tributary lengths of softening crack faces (cohesive_law.h): a partition of each crack face
// among its contact points, kinks included, so that the faces' contacts add up to the crack's
// length and the energy they dissipate, L·ΔD(κ) a contact and step, adds up to G_f × area.
// The rule of tributary_length.cpp (which every other contact keeps: its lengths, and with them
// every run without softening faces, are unchanged) cuts a crack's kinks short: four vertices
// share a kink's point, two per face, and which of them keeps the contact changes from step to
// step; their halves were projected on the contacted edge and split by index at a shared point,
// and a cohesive bar's crack across 0.19 m summed to 0.137–0.19 m (docs/fracture.md).
//
// A contact is a vertex P facing an edge of another element (contact_detection.cpp). P stands
// for a stretch of the joint on each side of it, measured along its own face: its half-edges.
// On each side s (before P in its loop, after it) the half-edge is the vector
//     a_s = (Q − P) + ½·(R − Q)
// where Q is the first vertex reached from P over edges shorter than the sliver length
// ε = kSliverEdge·h (Q = P where there is none) and Q → R the first edge longer than ε, if it
// is a candidate edge facing the contacted one (normals opposed within ~45°: a corner's other
// side is not on this joint); else side s has nothing. A sliver of face (where cracks met within
// round-off: a spike of 1e-9 m into an element, two loop vertices 1e-16 m apart) is no face of
// its own: the vertex at it stands for the face beyond, or, with no facing face beyond, is a
// point. Along a face whose vertices all make contacts, the halves a_s of the vertices at the
// two ends of each edge meet at its middle, so the lengths |a_s| tile the face exactly, kinks
// included: each half lies along its own edge, not along the contacted edge's tangent (projected
// on it, a kink of θ lost 1 − cos θ of the half, and the cuts below misplaced it further). The
// vertices of the elements continuous with P at its point (the same block, the same covers) add
// their halves: the face beyond a mesh line through P is theirs, and at a sharp kink only one of
// the vertices there may make a contact (the other face's corner mirrors the rest).
//
// The contact points of the two faces of one joint need not match: a face that stops on the
// other face (the corner of the narrower block touches between two vertices of the wider one),
// a vertex of the other face that pokes through and is held too, faces slid by a fraction of an
// element, or both faces' vertices at a kink (a single-pass joint's faces are both corners
// there). Where the halves overlap they would be counted twice. So on each side s, with
// d = a_s/|a_s| and e = |a_s| (ended where the contacted face ends at a corner of its block in
// the same line; past a kink of the joint the other face goes on in its new direction):
//   - a contact j of the same two blocks ahead on that side (u = (P_j − P)·d > ε, within 0.1·h of
//     the line) whose own halves, projected on d, reach below e cuts P's side at u/2 (the
//     one-dimensional Voronoi cell of the contact points along the joint);
//   - where no contact ahead overlaps, a gap of at most h between e and the nearest one's halves
//     is shared at its middle (the faces have slid: a corner of one face and the first contact
//     of the other stand more than their two halves apart);
//   - the contacts at P's point (within ε) whose own halves run the same way (parallel within
//     10°) share what they cover equally: a stretch x ∈ [0, e] covered by P and k others gives
//     P dx/(k + 1). At a kink, the two faces' contacts at the kink point cover each side twice
//     and take half each; a sliver's vertex and the face's vertex beside it take half each.
// P's shares of its sides add up to L. A contact with no length (a bare corner touching a
// face, a vertex whose faces all face away) is a point: `corner_length`.
// (Written for every contact first, the rule moved the state hashes of 30 of 33 runs and the
// disc cells' paths: only softening crack faces take it; docs/notes/2026-11-cohesive.md.) Checked by tests/test_contact_patch.cpp
// CohesiveFaceLengthsAlongAKinkedCrackAddUpToItsLength: a kinked crack's contacts add up to its
// polyline length to 1e-12 m (tributary_length.h's rule: 2.4e-3–5.4e-2 m off).
#include "solver/contact/cohesive_tributary.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "solver/contact/contact_neighbours.h"
#include "solver/contact/contact_tolerances.h"
#include "common/vec2.h"

namespace nmm::solve {

namespace {
// Two contact edges are on one joint when parallel within 10° ...
// ×h, a loop edge shorter than this is a sliver of face, no face of its own (where cracks met
// within round-off): a half-edge runs over it to the face beyond, and contact points this close
// are one point, sharing what they cover. A bare corner's length (contact_tolerances.h
// corner_length): no stretch of face below it is taken for a face.
constexpr double kSliverEdge = 1e-3;
constexpr double kParallelCos = 0.984807753;  // cos 10°
// ... and within this distance (×h) of each other's line (a face pressed into the other side
// is at most a few closures away; a different face of the same blocks is a block's width away).
constexpr double kSameLine = 0.1;
// Halves at one point: two along a face, more only where a block's boundary folds there.
constexpr int kMaxSides = 4;
}  // namespace

std::vector<double> partitioned_tributary_lengths(const ContactTopology& topo, const std::vector<double>& xy,
                                      const std::vector<ContactCandidate>& contacts,
                                      double corner_length) {
  const std::size_t n = contacts.size();
  const double h = topo.mesh_size;
  const double eps = kSliverEdge * h;
  struct Side {
    double dx = 0, dy = 0;  // unit direction of the half-edge, away from P
    double e = 0;           // m, its length (0: no face on this side)
    double reach = 0;       // m, what of it P stands for, cut at the contacts ahead
  };
  struct Frame {
    double px, py;          // P
    Side side[kMaxSides];   // P's halves at its point, one per direction
    int sides = 0;
    std::int32_t b0, b1;    // the two blocks, lower first
  };
  std::vector<Frame> f(n);
  const auto at = [&](std::int32_t v) { return Vec2{xy[2 * v], xy[2 * v + 1]}; };
  for (std::size_t i = 0; i < n; ++i) {
    const ContactCandidate& c = contacts[i];
    const std::int32_t p = c.vertex, q2 = c.edge, q3 = topo.next[q2];
    const Vec2 P = at(p), Q2 = at(q2), Q3 = at(q3);
    const double l = length(Q3.x - Q2.x, Q3.y - Q2.y);
    const double tx = (Q3.x - Q2.x) / l, ty = (Q3.y - Q2.y) / l, nx = ty, ny = -tx;
    Frame& fr = f[i];
    fr.px = P.x;
    fr.py = P.y;
    // P's point in its block: P and the vertices of the elements continuous with it there (the
    // face beyond a mesh line through P belongs to the neighbouring element's vertex, which may
    // make no contact of its own: the mirror of the other face's vertex, one contact per point).
    std::int32_t at_point[kMaxSides];
    int points = 0;
    at_point[points++] = p;
    if (!topo.continuous_offset.empty())
      for (std::int32_t k = topo.continuous_offset[p]; k < topo.continuous_offset[p + 1] && points < kMaxSides; ++k) {
        const std::int32_t el = topo.continuous[static_cast<std::size_t>(k)].second, first = topo.first_vertex[el];
        std::int32_t v = first;
        do {
          const Vec2 V = at(v);
          if (v != p && length(V.x - P.x, V.y - P.y) <= eps) {
            at_point[points++] = v;
            break;
          }
          v = topo.next[v];
        } while (v != first);
      }
    for (int w = 0; w < points; ++w)
      for (int s = 0; s < 2; ++s) {
        const std::int32_t from = at_point[w];
        // Walk over slivers (at most a loop's worth) to the first real edge on this side.
        std::int32_t v = from;
        std::int32_t a = s == 0 ? topo.prev[v] : v, b = s == 0 ? v : topo.next[v];  // the edge a → b
        bool found = false;
        for (int guard = 0; guard < 64; ++guard) {
          const Vec2 A = at(a), B = at(b);
          if (length(B.x - A.x, B.y - A.y) > eps) {
            found = true;
            break;
          }
          v = s == 0 ? a : b;
          if (v == from) break;
          a = s == 0 ? topo.prev[v] : v;
          b = s == 0 ? v : topo.next[v];
        }
        if (!found || !topo.edge_candidate[a]) continue;
        const Vec2 A = at(a), B = at(b);
        const double ex = B.x - A.x, ey = B.y - A.y, el = length(ex, ey);
        if ((ey / el) * nx + (-ex / el) * ny >= kContactTolerances.tributary_cos) continue;
        const Vec2 Q = at(v), R = s == 0 ? A : B;
        const double ax = Q.x - P.x + 0.5 * (R.x - Q.x), ay = Q.y - P.y + 0.5 * (R.y - Q.y);
        double e = length(ax, ay);
        if (!(e > 0)) continue;
        Side sd;
        sd.dx = ax / e;
        sd.dy = ay / e;
        // The contacted face ends at a corner of its block: no length of joint beyond it (a flat
        // vertex of the wider face at the narrower block's corner, kept for the pair of
        // coincident points, would otherwise count its half-edge over the overhang). q2 ends
        // the face on the side that runs against t, q3 on the side that runs along it.
        // Only along the contacted edge's line: past a kink of the joint (a corner of the other
        // block within ~the same joint) the other face goes on in its new direction.
        const double along = sd.dx * tx + sd.dy * ty;
        const std::int32_t end = along > 0 ? q3 : q2;
        if (topo.corner[end] && std::abs(along) >= kParallelCos) {
          const Vec2 E = at(end);
          e = std::min(e, std::max(0.0, (E.x - P.x) * sd.dx + (E.y - P.y) * sd.dy));
        }
        sd.e = e;
        // One half per direction at the point (the same face seen from two vertices).
        bool seen = false;
        for (int k = 0; k < fr.sides; ++k)
          if (fr.side[k].dx * sd.dx + fr.side[k].dy * sd.dy >= kParallelCos) {
            seen = true;
            fr.side[k].e = std::max(fr.side[k].e, sd.e);
          }
        if (!seen && fr.sides < kMaxSides && sd.e > 0) fr.side[fr.sides++] = sd;
      }
    const std::int32_t ba = topo.block_of[c.elem_a], bb = topo.block_of[c.elem_b];
    fr.b0 = std::min(ba, bb);
    fr.b1 = std::max(ba, bb);
  }

  // Contacts with a length of their own, listed by pair of blocks and grid cell
  // (contact_neighbours.h).
  std::vector<ContactNeighbours::Entry> entries;
  entries.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (f[i].sides > 0) entries.push_back({f[i].b0, f[i].b1, f[i].px, f[i].py, static_cast<std::uint32_t>(i)});
  const ContactNeighbours near(entries, h);

  std::vector<double> out(n, corner_length);
  const double tie = kContactTolerances.gap_round_off * h;
  // Two passes over the same neighbours: first each side's reach, cut at the midpoints to the
  // contacts ahead (or stretched over a gap to them); then each side's share of it with the
  // contacts at P's point, from their reaches, so that what the contacts at one point cover
  // adds up once whoever computes it.
  const auto neighbours = [&](std::size_t k, const auto& visit) {
    const Frame& a = f[near.index(k)];
    near.for_each_near(k, a.px, a.py, [&](std::uint32_t j) { visit(f[j]); });
  };
  for (std::size_t k = 0; k < near.size(); ++k) {
    Frame& a = f[near.index(k)];
    for (int s = 0; s < a.sides; ++s) {
      Side& sd = a.side[s];
      bool cut = false;
      double next = std::numeric_limits<double>::infinity();  // nearest non-overlapping half ahead
      double e = sd.e;
      neighbours(k, [&](const Frame& b) {
        const double rx = b.px - a.px, ry = b.py - a.py;
        const double u = rx * sd.dx + ry * sd.dy;
        if (u <= eps || length(rx, ry) <= eps || std::abs(rx * sd.dy - ry * sd.dx) > kSameLine * h) return;
        // j's own halves along d: [lo, ·] from u.
        double lo = u;
        for (int q = 0; q < b.sides; ++q) lo = std::min(lo, u + b.side[q].e * (b.side[q].dx * sd.dx + b.side[q].dy * sd.dy));
        if (lo < sd.e - tie) {
          e = std::min(e, 0.5 * u);
          cut = true;
        } else {
          next = std::min(next, lo);
        }
      });
      if (!cut && next - sd.e > tie && next - sd.e <= h) e = 0.5 * (sd.e + next);
      sd.reach = e;
    }
  }
  std::vector<std::pair<double, double>> cover;  // m, along P's side: what the contacts at P's point cover
  std::vector<double> cuts;
  for (std::size_t k = 0; k < near.size(); ++k) {
    const std::size_t i = near.index(k);
    const Frame& a = f[i];
    double total = 0;
    for (int s = 0; s < a.sides; ++s) {
      const Side& sd = a.side[s];
      const double e = sd.reach;
      cover.clear();
      neighbours(k, [&](const Frame& b) {
        const double rx = b.px - a.px, ry = b.py - a.py;
        // At P's point along the joint: within ε of it along the side, and within the line's
        // width across it — the other face's vertex at the same point of an opening crack stands
        // the opening w away (Euclidean ε = 1e-3·h would part the two at w = 0.1 mm, h = 0.1 m:
        // each then took both its halves, a bar's crack of 0.19 m counted 0.286 m for a step).
        const double u = rx * sd.dx + ry * sd.dy;
        if (std::abs(u) > eps || std::abs(rx * sd.dy - ry * sd.dx) > kSameLine * h) return;
        // j shares what its halves cover the same way, [u, u + reach·cos].
        for (int q = 0; q < b.sides; ++q) {
          const Side& o = b.side[q];
          const double c = o.dx * sd.dx + o.dy * sd.dy;
          if (c >= kParallelCos) cover.push_back({std::min(u, u + o.reach * c), std::max(u, u + o.reach * c)});
        }
      });
      // Share [0, e] with them by how many cover each stretch.
      cuts.assign({0.0, e});
      for (const auto& [lo, hi] : cover) {
        if (lo > 0 && lo < e) cuts.push_back(lo);
        if (hi > 0 && hi < e) cuts.push_back(hi);
      }
      std::sort(cuts.begin(), cuts.end());
      for (std::size_t r = 0; r + 1 < cuts.size(); ++r) {
        const double x0 = cuts[r], x1 = cuts[r + 1], mid = 0.5 * (x0 + x1);
        if (!(x1 > x0)) continue;
        int by = 1;
        for (const auto& [lo, hi] : cover) by += lo < mid && mid < hi;
        total += (x1 - x0) / by;
      }
    }
    if (total > 0) out[i] = total;
  }
  return out;
}

}  // namespace nmm::solve
