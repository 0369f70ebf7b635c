// Geometric checks of a scene with exact predicates (CGAL Epick: exact orientation and
// intersection tests on the input doubles, so a touch at one point is seen as a touch).
//
// - Every ring (outer boundary or hole) is simple: two edges meet only where they are neighbours,
//   and neighbours only at their shared vertex (no fold-back along a line).
// - Holes lie strictly inside their body's outer boundary and apart from each other (no touch).
// Rings with repeated points or all points on one line were already rejected by parse_scene().
// Each ring is tested by sort-and-sweep over the edges' x-extents, so a long outline costs
// about n·log n, not n².
#include "preprocess/scene_geometry.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "common/error.h"

namespace nmm::pre {

namespace {

using Kernel = CGAL::Epick;
using Point = Kernel::Point_2;
using Segment = Kernel::Segment_2;

Point pt(const Vec2& v) { return Point(v.x, v.y); }

// An edge of a ring: points k → k+1 of ring `ring` (0 outer, h+1 hole h).
struct Edge {
  int ring;
  std::size_t k;
  Segment seg;
  double x0, x1;
};

std::vector<Edge> ring_edges(const Ring& r, int ring) {
  std::vector<Edge> edges;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const Vec2& a = r[k];
    const Vec2& b = r[(k + 1) % r.size()];
    edges.push_back({ring, k, Segment(pt(a), pt(b)), std::min(a.x, b.x), std::max(a.x, b.x)});
  }
  return edges;
}

std::string ring_path(std::size_t body, int ring) {
  std::string p = "/bodies/" + std::to_string(body);
  return ring == 0 ? p + "/outer" : p + "/holes/" + std::to_string(ring - 1);
}

// True when edges e and f meet where they should not. n is the ring size when checking one
// ring; n = 0 checks only pairs from different rings, which may not meet at all.
bool bad_meeting(const Edge& e, const Edge& f, std::size_t n) {
  if (e.ring == f.ring && n == 0) return false;
  if (!CGAL::do_intersect(e.seg, f.seg)) return false;
  if (e.ring != f.ring) return true;
  const std::size_t a = std::min(e.k, f.k), b = std::max(e.k, f.k);
  const bool e_then_f = b == a + 1, wrap = a == 0 && b == n - 1;
  if (!e_then_f && !wrap) return true;
  // Neighbours share one vertex q; they overlap beyond it only when they fold back on a line.
  const Edge& first = (e_then_f ? (e.k == a ? e : f) : (e.k == b ? e : f));
  const Edge& second = (&first == &e) ? f : e;
  const Point& p = first.seg.source();
  const Point& q = first.seg.target();
  const Point& r = second.seg.target();
  return CGAL::collinear(p, q, r) && !CGAL::collinear_are_ordered_along_line(p, q, r);
}

// Finds the first pair of edges that meet badly, by sort-and-sweep on x.
bool find_crossing(std::vector<Edge> edges, std::size_t ring_size, Edge* out_a, Edge* out_b) {
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
    return a.x0 < b.x0 || (a.x0 == b.x0 && (a.ring < b.ring || (a.ring == b.ring && a.k < b.k)));
  });
  std::vector<const Edge*> active;
  for (const Edge& e : edges) {
    active.erase(std::remove_if(active.begin(), active.end(),
                                [&](const Edge* a) { return a->x1 < e.x0; }),
                 active.end());
    for (const Edge* a : active)
      if (bad_meeting(*a, e, ring_size)) {
        *out_a = *a;
        *out_b = e;
        return true;
      }
    active.push_back(&e);
  }
  return false;
}

std::string near(const Edge& a, const Edge& b) {
  // A point to look at: where the two edges meet (approximately, for the message only).
  const auto x = CGAL::intersection(a.seg, b.seg);
  Point p = a.seg.source();
  if (x) {
    if (const Point* q = boost::get<Point>(&*x)) p = *q;
    else if (const Segment* s = boost::get<Segment>(&*x)) p = s->source();
  }
  std::ostringstream os;
  os << " near x = " << p.x() << ", y = " << p.y();
  return os.str();
}

void check_ring_simple(const Ring& r, std::size_t body, int ring, const std::string& file) {
  Edge a{}, b{};
  if (find_crossing(ring_edges(r, ring), r.size(), &a, &b)) {
    std::ostringstream msg;
    msg << "self-intersecting polygon: edge " << a.k << " crosses edge " << b.k << near(a, b);
    throw InputError(file, ring_path(body, ring) + "/" + std::to_string(std::min(a.k, b.k)),
                     msg.str());
  }
}

bool strictly_inside(const Point& p, const Ring& r) {
  std::vector<Point> poly;
  for (const Vec2& v : r) poly.push_back(pt(v));
  return CGAL::bounded_side_2(poly.begin(), poly.end(), p, Kernel()) == CGAL::ON_BOUNDED_SIDE;
}

}  // namespace

void check_scene_geometry(const SceneDef& scene, const std::string& file) {
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodyDef& body = scene.bodies[b];
    check_ring_simple(body.outer, b, 0, file);
    for (std::size_t h = 0; h < body.holes.size(); ++h) {
      const Ring& hole = body.holes[h];
      const int ring = static_cast<int>(h) + 1;
      check_ring_simple(hole, b, ring, file);
      // Rings that neither cross nor touch are nested or apart: one vertex tells which.
      std::vector<Edge> both = ring_edges(body.outer, 0);
      const std::vector<Edge> he = ring_edges(hole, ring);
      both.insert(both.end(), he.begin(), he.end());
      Edge x{}, y{};
      if (find_crossing(both, 0, &x, &y))
        throw InputError(file, ring_path(b, ring),
                         "hole touches or crosses the outer boundary of its body" + near(x, y));
      if (!strictly_inside(pt(hole[0]), body.outer))
        throw InputError(file, ring_path(b, ring), "hole lies outside its body's outer boundary");
      for (std::size_t g = 0; g < h; ++g) {
        std::vector<Edge> pair = ring_edges(body.holes[g], static_cast<int>(g) + 1);
        pair.insert(pair.end(), he.begin(), he.end());
        if (find_crossing(pair, 0, &x, &y))
          throw InputError(file, ring_path(b, ring),
                           "hole touches or crosses hole " + std::to_string(g) + near(x, y));
        if (strictly_inside(pt(hole[0]), body.holes[g]) ||
            strictly_inside(pt(body.holes[g][0]), hole))
          throw InputError(file, ring_path(b, ring),
                           "hole lies inside hole " + std::to_string(g) + " (nested holes)");
      }
    }
  }
}

}  // namespace nmm::pre
