// Tributary joint lengths: a partition of each joint among its contact points.
//
// A contact is a vertex P facing an edge of another element (contact_detection.cpp); along the
// edge's unit tangent t, P stands at most for half of each of its own candidate edges that face
// the contacted edge (normals opposed within ~45°: a corner's other side is not on this joint):
//     own(P) = [lo, hi],  lo = min(0, ½·(X_prev − P)·t),  hi = max(0, ½·(X_next − P)·t)
// Where only one face makes contacts and its vertices are the other face's (a joint cut by the
// lattice, bodies meshed by one lattice), these halves tile the joint. They do not where the
// contact points of the two faces do not match: at the end of a face that stops on the other
// face (the corner of the narrower block makes a contact between two vertices of the wider
// one), where a vertex of the other face pokes through and is held too, or where the faces have
// slid by a fraction of an element. The halves then overlap, the overlap is counted twice, and
// the joint there is stiffer and stronger than written (and a Bandis–Barton joint closes less
// at one end than at the other, which tilts the block on top).
//
// First, P's halves end where the contacted face ends (an end of the contacted edge that is a
// corner of its block). Then each contact's share is cut at the midpoint to its nearest
// neighbour on the same joint (a contact between the same two blocks whose edge is parallel
// within 10°, on the same line, and whose own halves overlap P's):
//     L = min(hi, min u_j/2 over u_j > 0) − max(lo, max u_j/2 over u_j < 0),  u_j = (P_j − P)·t
// a one-dimensional Voronoi cell of the contact points, bounded by P's own faces. Neighbours that
// tile already (matching vertices) do not overlap, so nothing changes there. Two contacts at one
// point whose halves overlap split it by index, the lower taking the side before the point and
// the higher the side beyond — except what one's halves reach past the other's on the other's
// side, which stays its own (at a crack's corner that two vertices a round-off apart share, one
// with a round-off of face and one with 0.5 mm on the same side, the split left the corner
// 1e-3·h of face). An edge of no length (degenerate_edge) is no half-edge. Where the faces have slid, the corner of one face
// and the first contact point of the other stand more than their two halves apart: a gap of up
// to h between P's halves and the next contact's on the same joint is shared at its middle. A
// contact with no length of its own (a bare corner touching a face) is a point: `corner_length`.
// Checked by tests/test_contact_patch.cpp (the tributary lengths add up to the joint's length).
#include "solver/contact/tributary_length.h"

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
constexpr double kParallelCos = 0.984807753;  // cos 10°
// ... and within this distance (×h) of each other's line (a face pressed into the other side
// is at most a few closures away; a different face of the same blocks is a block's width away).
constexpr double kSameLine = 0.1;
}  // namespace

std::vector<double> tributary_lengths(const ContactTopology& topo, const std::vector<double>& xy,
                                      const std::vector<ContactCandidate>& contacts,
                                      double corner_length) {
  const std::size_t n = contacts.size();
  struct Frame {
    double px, py, tx, ty;  // P; the contacted edge's unit tangent
    double lo, hi;          // m, P's own half-edges along t
    std::int32_t b0, b1;    // the two blocks, lower first
  };
  std::vector<Frame> f(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ContactCandidate& c = contacts[i];
    const std::int32_t p = c.vertex, q2 = c.edge, q3 = topo.next[q2];
    const double dx = xy[2 * q3] - xy[2 * q2], dy = xy[2 * q3 + 1] - xy[2 * q2 + 1];
    const double l = length(dx, dy);
    Frame& fr = f[i];
    fr.px = xy[2 * p];
    fr.py = xy[2 * p + 1];
    fr.tx = dx / l;
    fr.ty = dy / l;
    const double nx = fr.ty, ny = -fr.tx;
    fr.lo = fr.hi = 0;
    for (std::int32_t s : {topo.prev[p], p}) {
      if (!topo.edge_candidate[s]) continue;
      const std::int32_t e = topo.next[s];
      const double ex = xy[2 * e] - xy[2 * s], ey = xy[2 * e + 1] - xy[2 * s + 1];
      const double el = length(ex, ey);
      // An edge of no length stands for no joint, and its direction is noise (contact_detection.cpp).
      if (!(el > kContactTolerances.degenerate_edge * topo.mesh_size) ||
          (ey / el) * nx + (-ex / el) * ny >= kContactTolerances.tributary_cos)
        continue;
      const std::int32_t other = s == p ? e : s;
      const double a = 0.5 * ((xy[2 * other] - fr.px) * fr.tx + (xy[2 * other + 1] - fr.py) * fr.ty);
      fr.lo = std::min(fr.lo, a);
      fr.hi = std::max(fr.hi, a);
    }
    // The contacted face ends at a corner of its block: no length of joint beyond it (a flat
    // vertex of the wider face at the narrower block's corner, kept for the pair of coincident
    // points, would otherwise count its half-edge over the overhang).
    if (topo.corner[q2]) fr.lo = std::max(fr.lo, std::min(0.0, (xy[2 * q2] - fr.px) * fr.tx + (xy[2 * q2 + 1] - fr.py) * fr.ty));
    if (topo.corner[q3]) fr.hi = std::min(fr.hi, std::max(0.0, (xy[2 * q3] - fr.px) * fr.tx + (xy[2 * q3 + 1] - fr.py) * fr.ty));
    const std::int32_t ba = topo.block_of[c.elem_a], bb = topo.block_of[c.elem_b];
    fr.b0 = std::min(ba, bb);
    fr.b1 = std::max(ba, bb);
  }

  // Contacts with a length of their own, listed by pair of blocks and grid cell
  // (contact_neighbours.h).
  const double h = topo.mesh_size;
  std::vector<ContactNeighbours::Entry> entries;
  entries.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (f[i].hi > f[i].lo) entries.push_back({f[i].b0, f[i].b1, f[i].px, f[i].py, static_cast<std::uint32_t>(i)});
  const ContactNeighbours near(entries, h);

  std::vector<double> length(n, corner_length);
  const double tie = kContactTolerances.gap_round_off * h;
  for (std::size_t k = 0; k < near.size(); ++k) {
    const std::size_t i = near.index(k);
    const Frame& a = f[i];
    double lo = a.lo, hi = a.hi;
    // Nearest own-half boundaries of the neighbours beyond P's halves (no overlap), each side.
    double next_hi = std::numeric_limits<double>::infinity(), next_lo = -next_hi;
    // m, along t: P's cell without the contacts at P itself, and how far those reach (a lower
    // index's half below P, a higher index's above): P keeps what lies past them.
    double lo_v = a.lo, hi_v = a.hi;
    double beyond_lo = std::numeric_limits<double>::infinity(), beyond_hi = -beyond_lo;
    near.for_each_near(k, a.px, a.py, [&](std::uint32_t j) {
      const Frame& b = f[j];
      if (std::abs(a.tx * b.tx + a.ty * b.ty) < kParallelCos) return;
      const double rx = b.px - a.px, ry = b.py - a.py;
      if (std::abs(rx * a.ty - ry * a.tx) > kSameLine * h) return;
      const double u = rx * a.tx + ry * a.ty;
      // Only a contact whose own half-edges overlap P's shares P's stretch of joint (two
      // vertices of one face at one point, in two elements, stand for its two sides).
      const bool along = a.tx * b.tx + a.ty * b.ty > 0;
      const double b_lo = u + (along ? b.lo : -b.hi), b_hi = u + (along ? b.hi : -b.lo);
      if (std::min(a.hi, b_hi) - std::max(a.lo, b_lo) <= tie) {
        if (b_lo >= a.hi - tie) next_hi = std::min(next_hi, b_lo);
        if (b_hi <= a.lo + tie) next_lo = std::max(next_lo, b_hi);
        return;
      }
      // Two contacts at one point split it by index: the higher takes the side beyond, the
      // lower the side before; what either half reaches past the other's stays its own.
      const bool same_point = std::abs(u) <= tie;
      if (same_point) {
        if (j > i) {
          hi = std::min(hi, 0.0);
          beyond_hi = std::max(beyond_hi, b_hi);
        } else {
          lo = std::max(lo, 0.0);
          beyond_lo = std::min(beyond_lo, b_lo);
        }
        return;
      }
      if (u > 0) {
        hi = std::min(hi, 0.5 * u);
        hi_v = std::min(hi_v, 0.5 * u);
      } else {
        lo = std::max(lo, 0.5 * u);
        lo_v = std::max(lo_v, 0.5 * u);
      }
    });
    // A gap of at most h between P's halves and the next contact's on the same joint (the faces
    // have slid: a corner of one face and the first contact point of the other no longer stand
    // half an edge apart each) is shared at its middle.
    if (hi == a.hi && next_hi - a.hi > tie && next_hi - a.hi <= h) hi = 0.5 * (a.hi + next_hi);
    if (lo == a.lo && a.lo - next_lo > tie && a.lo - next_lo <= h) lo = 0.5 * (a.lo + next_lo);
    length[i] = std::max(hi - lo, 0.0);
    // A corner of a crack that two vertices a round-off apart share: split at the point, the one
    // whose only half-edge lay on the other's side kept none of it (1e-3·h where 0.5 mm bore on
    // the face; it sank 1 mm). What P's own halves reach past the others' at P stays P's.
    if (std::isfinite(beyond_lo)) length[i] += std::max(std::min(beyond_lo, 0.0) - lo_v, 0.0);
    if (std::isfinite(beyond_hi)) length[i] += std::max(hi_v - std::max(beyond_hi, 0.0), 0.0);
    // Less face than a bare corner's is a sliver where cracks met within round-off (4.9e-10 m,
    // 3.1e-10 m): no face, so a corner, whose spring holds it like any other corner's.
    if (!(length[i] >= corner_length)) length[i] = corner_length;
  }
  return length;
}

}  // namespace nmm::solve
