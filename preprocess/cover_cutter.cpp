// Cover cutting with an exact arrangement (CGAL Arrangement_2, EPECK kernel, segment traits).
//
// Method (docs/physics.md §1, docs/preprocess.md):
// 1. Mathematical mesh: equilateral triangles of side h on a lattice anchored at the origin,
//    node (i, j) at x = (i + ½·(j mod 2))·h, y = j·h·√3/2, kept where a triangle's bounding box
//    meets a body's bounding box. Node coordinates are doubles, computed once.
// 2. One sweep inserts every curve: each mesh edge once, each joint segment, each body boundary
//    segment. Curves carry tags (Arr_consolidated_curve_data_traits_2) so every arrangement edge
//    knows all its origins: mesh edge (with the triangles on its two sides), joint, body boundary
//    (with the side the body lies on). Overlapping curves (a joint along a mesh edge, touching
//    bodies, collinear joints) merge into one edge carrying all their tags.
// 3. Labelling. Every face lies in one triangle and in at most one body. A face's triangle is
//    read off any of its halfedges on a mesh edge; faces without one (enclosed by joints) share
//    the triangle of the faces they connect to across non-mesh edges (union–find). Likewise for
//    the body across non-boundary edges: a halfedge on a boundary segment says "inside body b"
//    when the body lies on its left (CGAL keeps each halfedge's face on its left), else
//    "outside". Two different answers in one component mean overlapping bodies (bad input).
// 4. Faces inside a body are the manifold elements (ME). A face with holes (a body hole or a
//    joint network wholly inside one triangle) gets a zero-width bridge from each hole's top
//    vertex straight up to the nearest boundary of the face, inserted exactly into the
//    arrangement, so each ME boundary is one weakly simple loop.
// 5. Physical covers: for node n, the pieces of star(n) ∩ body minus joints are the components
//    of the MEs in the six triangles around n, joined across the spokes of n wherever a spoke
//    piece is a mesh edge only (no joint, no boundary on it). A joint ending inside the star
//    leaves the pieces on its two faces joined around its tip, so it does not split the cover.
//    Blocks: components of all MEs joined across every mesh-only edge.
//    Gap ends (scene mesh.split_gap_ends, off by default): where a body's boundary turns back on
//    itself by at least 150° within less than h — the end of a slot narrower than the mesh, at a
//    vertex (a sharp notch) or along an edge shorter than h between two reflex corners (a flat
//    slot end) — the gap is carried on from the end's middle, along the bisector of the walls,
//    to the edge of the mesh triangle that holds the end: an extension curve (kEdgeExtension),
//    cut into the arrangement like a joint but with no contact and no block boundary on it. A
//    cover is then a piece of star ∩ body minus joints and extensions: a star the gap enters and
//    ends in is split along the gap and its extension when they separate it (the node opposite
//    the exit edge), and stays whole when its pieces join round the extension's end (the exit
//    edge's nodes). This is the crack of the extended finite element and manifold methods with
//    its tip moved onto the edge of the element holding it (Wells & Sluys 2001, IJNME 50:2667;
//    Zheng & Xu 2014, IJNME 97:986 on covers a tip cuts partially): the walls of a slot narrower
//    than h are no longer tied by the covers reaching round its end; the jump across the
//    extension falls to zero at the triangle's edge, so the field is continuous ahead of it.
// 6. Coordinates go to double once, after the last insertion: each arrangement vertex's exact
//    coordinates rounded to the nearest double (round_exact), a function of the exact point
//    alone. CGAL::to_double of a lazy number would return the midpoint of whatever interval its
//    construction left (up to 1e-5 wide, relative), and that interval depends on which
//    predicates happened to force the exact value: the same joint across the same mesh edge
//    rounded 1 ulp apart in a region cut and a whole cut, and the re-cut, which links blocks by
//    rounded edges, split a block (issue 48). So the same scene always gives the same bytes, and
//    a point gives the same double in every cut that has it. Sliver elements (a joint passing 1e-9·h beside a node)
//    are kept as they are: dropping or merging them would lose area or change the topology. Only
//    specks are dropped: faces that, rounded, enclose no positive area or fit in 1e-9·h (Cutter::
//    speck), where three cuts meet within round-off of one point. A piece of mesh edge that
//    rounds to one point joins neither covers nor blocks (the re-cut links by rounded edges).
#include "preprocess/cover_cutter.h"
#include "preprocess/loop_area.h"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/lattice.h"
#include "common/math_constants.h"
#include "nmm_version.h"
#include "common/stopwatch.h"

namespace nmm::pre {

namespace {

// What an arrangement curve came from. `id` is a mesh edge, joint or boundary segment index.
struct CurveTag {
  std::uint8_t kind = 0;  // one EdgeOrigin flag
  std::int32_t id = -1;
  bool operator==(const CurveTag& o) const { return kind == o.kind && id == o.id; }
};

using Kernel     = CGAL::Epeck;
using SegTraits  = CGAL::Arr_segment_traits_2<Kernel>;
using Traits     = CGAL::Arr_consolidated_curve_data_traits_2<SegTraits, CurveTag>;
using Point      = Traits::Point_2;
using Segment    = Kernel::Segment_2;
using Curve      = Traits::Curve_2;
// Vertices carry their rounded coordinates (round_vertices), faces their index.
using Dcel       = CGAL::Arr_extended_dcel<Traits, Vec2, std::uint8_t, std::int32_t>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;
using Halfedge_handle = Arrangement::Halfedge_const_handle;
using Face_handle     = Arrangement::Face_const_handle;

bool lex_less(const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// Union–find with path halving; indices are small integers.
struct UnionFind {
  std::vector<std::int32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::int32_t find(std::int32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void unite(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // smallest index is the root
  }
};

// A mesh edge between lattice nodes a and b (a lexicographically before b), with the triangles
// to the left and right of the direction a → b (-1 outside the kept mesh).
struct MeshEdge {
  std::int32_t a, b;
  std::int32_t left = -1, right = -1;
};

// A body boundary segment; the body lies left of its left-to-right direction when `body_left`.
struct BoundarySeg {
  std::int32_t body;
  bool body_left;
};

// The mathematical mesh before cutting: lattice nodes, candidate triangles, their edges.
struct RawMesh {
  Lattice lat;
  std::vector<Vec2> node_xy;                    // full lattice
  std::vector<std::array<std::int32_t, 3>> tri;  // candidate triangles, CCW
  std::vector<MeshEdge> edges;
};

// `region`: when given, only the lattice triangles it lists (their node indices, sorted) are
// kept (cut_region); otherwise every triangle whose bounding box meets a body's.
RawMesh make_raw_mesh(const SceneDef& scene, const std::vector<std::array<std::int32_t, 3>>* region = nullptr) {
  RawMesh m;
  m.lat = make_lattice(scene.bodies, scene.mesh_size);  // ranges checked by parse_scene()
  const Lattice& L = m.lat;
  std::vector<Box> boxes;
  for (const BodyDef& b : scene.bodies) boxes.push_back(bounding_box(b.outer));
  const std::int64_t i1 = L.i0 + L.ni - 1, j1 = L.j0 + L.nj - 1;
  m.node_xy.resize(static_cast<std::size_t>(L.ni * L.nj));
  for (std::int64_t j = L.j0; j <= j1; ++j)
    for (std::int64_t i = L.i0; i <= i1; ++i) m.node_xy[L.index(i, j)] = L.node(i, j);

  auto keep = [&](const std::array<std::int32_t, 3>& t) {
    if (region) {
      std::array<std::int32_t, 3> key = t;
      std::sort(key.begin(), key.end());
      return std::binary_search(region->begin(), region->end(), key);
    }
    Box tb{m.node_xy[t[0]].x, m.node_xy[t[0]].y, m.node_xy[t[0]].x, m.node_xy[t[0]].y};
    for (int k = 1; k < 3; ++k) {
      const Vec2& p = m.node_xy[t[k]];
      tb = {std::min(tb.x0, p.x), std::min(tb.y0, p.y), std::max(tb.x1, p.x), std::max(tb.y1, p.y)};
    }
    for (const Box& b : boxes)
      if (tb.overlaps(b)) return true;
    return false;
  };
  // Between rows j and j+1 the shifted row is the odd one; see the file comment for the lattice.
  for (std::int64_t j = L.j0; j < j1; ++j) {
    const bool odd = ((j % 2) + 2) % 2 == 1;
    for (std::int64_t i = L.i0; i < i1; ++i) {
      std::array<std::int32_t, 3> up, down;
      if (!odd) {
        up = {L.index(i, j), L.index(i + 1, j), L.index(i, j + 1)};
        down = {L.index(i + 1, j), L.index(i + 1, j + 1), L.index(i, j + 1)};
      } else {
        up = {L.index(i, j), L.index(i + 1, j), L.index(i + 1, j + 1)};
        down = {L.index(i, j), L.index(i + 1, j + 1), L.index(i, j + 1)};
      }
      if (keep(up)) m.tri.push_back(up);
      if (keep(down)) m.tri.push_back(down);
    }
  }
  // Edges: one per pair of nodes, with the triangle on each side of the a → b direction.
  struct HalfRef {
    std::int64_t key;
    std::int32_t tri;
    bool tri_left;
  };
  std::vector<HalfRef> refs;
  refs.reserve(m.tri.size() * 3);
  const std::int64_t stride = L.ni * L.nj;
  for (std::size_t t = 0; t < m.tri.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      std::int32_t p = m.tri[t][k], q = m.tri[t][(k + 1) % 3];
      // The triangle is left of p → q (counter-clockwise); store the edge as a → b, a before b.
      const bool left = lex_less(m.node_xy[p], m.node_xy[q]);
      if (!left) std::swap(p, q);
      refs.push_back({static_cast<std::int64_t>(p) * stride + q, static_cast<std::int32_t>(t), left});
    }
  std::sort(refs.begin(), refs.end(),
            [](const HalfRef& x, const HalfRef& y) { return x.key < y.key; });
  for (std::size_t r = 0; r < refs.size();) {
    MeshEdge e{static_cast<std::int32_t>(refs[r].key / stride),
               static_cast<std::int32_t>(refs[r].key % stride)};
    std::size_t s = r;
    for (; s < refs.size() && refs[s].key == refs[r].key; ++s)
      (refs[s].tri_left ? e.left : e.right) = refs[s].tri;
    m.edges.push_back(e);
    r = s;
  }
  return m;
}

Point to_point(const Vec2& p) { return Point(p.x, p.y); }

// The double nearest to an exact coordinate (ties to the lower), from the exact value and not
// from the interval CGAL's filter carries (file comment, step 6). Inputs (lattice nodes, joint
// and boundary ends) are doubles already and cost nothing; a constructed point is computed
// exactly once here.
double round_exact(const Kernel::FT& v) {
  double r;
  if (CGAL::fit_in_double(v.approx(), r)) return r;
  using ET = Kernel::FT::ET;
  const ET& e = v.exact();
  const std::pair<double, double> iv = CGAL::to_interval(e);  // the tightest interval about e
  if (iv.first == iv.second) return iv.first;
  const ET mid = (ET(iv.first) + ET(iv.second)) / 2;
  return e <= mid ? iv.first : iv.second;
}

Vec2 round_exact(const Point& p) { return {round_exact(p.x()), round_exact(p.y())}; }

// Per-face labels found by union–find over the arrangement's faces.
struct FaceLabels {
  std::vector<Face_handle> faces;   // by face index (face->data())
  std::vector<std::int32_t> tri;    // triangle or -1
  std::vector<std::int32_t> body;   // body or -1
};

class Cutter {
 public:
  Cutter(const SceneDef& scene, const std::string& file) : scene_(scene), file_(file) {}
  /// A cut of the listed lattice triangles only (cut_region; sorted node-index triples).
  Cutter(const SceneDef& scene, const std::string& file, const std::vector<std::array<std::int32_t, 3>>& region)
      : scene_(scene), file_(file), region_(&region) {}

  Mesh run(CutTimings* timings);
  /// The lattice node indices of the kept triangles, in the output mesh's triangle order.
  const std::vector<std::array<std::int32_t, 3>>& kept_triangles() const { return kept_; }

  /// GrowingCut: run() that keeps the arrangement as the sweep left it (the bridges for holes go
  /// into a copy), so that grow() can add joints to it.
  Mesh run_kept();
  /// Inserts the segments of the scene's joints from `first_joint` on into the kept arrangement,
  /// one at a time (CGAL's incremental insertion), and extracts the mesh as run_kept() does. The
  /// scene (the reference this cutter holds) must be the kept one with joints appended.
  Mesh grow(std::size_t first_joint);

 private:
  void make_raw_mesh_of_scene();
  void insert_curves();
  void joint_curves(std::size_t first_joint, std::vector<Curve>& curves) const;
  void number_faces();
  void label_faces();
  std::vector<Curve> find_bridges() const;
  void bridge_holes();
  Mesh finish_kept();
  void round_vertices();
  void gap_end_extensions(std::vector<Curve>& curves) const;
  Mesh extract();
  bool speck(Face_handle face) const;

  const SceneDef& scene_;
  const std::string& file_;
  const std::vector<std::array<std::int32_t, 3>>* region_ = nullptr;  // cut_region's triangles
  Box region_box_{0, 0, 0, 0};  // m, their bounding box (region_ only)
  std::vector<std::array<std::int32_t, 3>> kept_;
  RawMesh raw_;
  std::vector<BoundarySeg> boundary_;
  Arrangement arr_;
  // The arrangement the mesh is extracted from: arr_, or (run_kept, grow) a copy of it with the
  // bridges for holes inserted.
  Arrangement bridged_;
  Arrangement* out_ = &arr_;
  FaceLabels lab_;
};

// The curves of the scene's joints from `first_joint` on, appended to `curves`: the one place
// that turns joints into segments, for the sweep (insert_curves) and a growth (grow) alike.
// Joint points within round-off of a lattice node or row are put on it (Lattice::snap), in every
// cut alike: the whole cut, a region cut and the re-cut check see the same segments (a growth
// that took them as typed let a crack along a mesh row, its end an ulp below the row, dip under
// it and cut off a sliver of 2.6e-18 m² with a cover of its own that the whole cut does not
// have: issue 48, tests GrowingCut.AGrowthSnaps…). A region cut needs only the segments that
// reach its triangles.
void Cutter::joint_curves(std::size_t first_joint, std::vector<Curve>& curves) const {
  auto reaches = [&](const Vec2& p, const Vec2& q) {
    return !region_ || Box{std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y)}
                           .overlaps(region_box_);
  };
  std::vector<Vec2> pts;
  for (std::size_t j = first_joint; j < scene_.joints.size(); ++j) {
    pts.clear();
    for (const Vec2& p : scene_.joints[j].points) pts.push_back(raw_.lat.snap(p));
    for (std::size_t k = 0; k + 1 < pts.size(); ++k)
      // A segment of no length (a crack grown by a round-off) cuts nothing, and CGAL's sweep
      // takes no degenerate segment.
      if (!(pts[k] == pts[k + 1]) && reaches(pts[k], pts[k + 1]))
        curves.emplace_back(Segment(to_point(pts[k]), to_point(pts[k + 1])),
                            CurveTag{kEdgeJoint, static_cast<std::int32_t>(j)});
  }
}

void Cutter::insert_curves() {
  std::vector<Curve> curves;
  curves.reserve(raw_.edges.size() + 16);
  for (std::size_t e = 0; e < raw_.edges.size(); ++e) {
    const MeshEdge& me = raw_.edges[e];
    curves.emplace_back(Segment(to_point(raw_.node_xy[me.a]), to_point(raw_.node_xy[me.b])),
                        CurveTag{kEdgeMesh, static_cast<std::int32_t>(e)});
  }
  joint_curves(0, curves);
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const BodyDef& body = scene_.bodies[b];
    if (region_ && !bounding_box(body.outer).overlaps(region_box_)) {
      // Not inserted, but numbered as in a whole cut (boundary_ indexes the curve tags).
      for (std::size_t r = 0; r <= body.holes.size(); ++r)
        boundary_.resize(boundary_.size() + (r == 0 ? body.outer : body.holes[r - 1]).size(), {-1, false});
      continue;
    }
    for (std::size_t r = 0; r <= body.holes.size(); ++r) {
      const Ring& ring = r == 0 ? body.outer : body.holes[r - 1];
      // The body lies left of a ring traversed counter-clockwise for the outer boundary and
      // clockwise for a hole.
      const bool ccw = ring_signed_area(ring) > 0;
      const bool body_left_of_ring = (r == 0) == ccw;
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const Vec2& p = ring[k];
        const Vec2& q = ring[(k + 1) % ring.size()];
        const bool l2r = lex_less(p, q);
        boundary_.push_back({static_cast<std::int32_t>(b), l2r == body_left_of_ring});
        curves.emplace_back(Segment(to_point(p), to_point(q)),
                            CurveTag{kEdgeBoundary, static_cast<std::int32_t>(boundary_.size() - 1)});
      }
    }
  }
  if (scene_.split_gap_ends) gap_end_extensions(curves);
  CGAL::insert(arr_, curves.begin(), curves.end());
}

// Step 5's gap ends: each end of a body-boundary gap narrower than h, carried on from the end's
// middle along the walls' bisector to the edge of the mesh triangle holding it (exact: the end
// on the triangle's edge is the exact intersection, so the extension parts that triangle and
// no other). Only triangles of this cut are searched: a region cut that lacks the triangle has
// none of the stars it splits whole (recut.cpp takes those stars' covers from the old mesh).
void Cutter::gap_end_extensions(std::vector<Curve>& curves) const {
  const double h = scene_.mesh_size;
  // The boundary turns back on itself at an end: a turn of at least 150° (5π/6 rad).
  constexpr double kTurnBack = 5 * kPi / 6;
  std::int32_t id = 0;
  for (const BodyDef& body : scene_.bodies) {
    for (std::size_t r = 0; r <= body.holes.size(); ++r) {
      Ring ring = r == 0 ? body.outer : body.holes[r - 1];
      if ((r == 0) != (ring_signed_area(ring) > 0)) std::reverse(ring.begin(), ring.end());  // body on the left
      const std::size_t n = ring.size();
      auto dir = [&](std::size_t k) {  // unit direction of edge k → k + 1
        const Vec2& p = ring[k % n];
        const Vec2& q = ring[(k + 1) % n];
        const double l = std::hypot(q.x - p.x, q.y - p.y);
        return Vec2{(q.x - p.x) / l, (q.y - p.y) / l};
      };
      auto turn = [&](std::size_t k) {  // rad at vertex k, < 0 clockwise: a reflex corner of the body
        const Vec2 a = dir(k + n - 1), b = dir(k);
        return std::atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y);
      };
      for (std::size_t k = 0; k < n; ++k) {
        Point start;
        Vec2 in, out;  // the wall into the end and the wall out of it
        const Vec2& p = ring[k];
        const Vec2& q = ring[(k + 1) % n];
        if (turn(k) <= -kTurnBack) {
          start = to_point(p);
          in = dir(k + n - 1), out = dir(k);
        } else if (turn(k) < 0 && turn(k + 1) < 0 && turn(k + 1) > -kTurnBack && turn(k) + turn(k + 1) <= -kTurnBack &&
                   std::hypot(q.x - p.x, q.y - p.y) < h) {
          start = CGAL::midpoint(to_point(p), to_point(q));
          in = dir(k + n - 1), out = dir(k + 1);
        } else {
          continue;
        }
        // On into the body: the walls' bisector, away from the gap.
        const Vec2 d{in.x - out.x, in.y - out.y};
        const Kernel::Ray_2 ray(start, Kernel::Vector_2(d.x, d.y));
        const Vec2 s = round_exact(start);
        const double tol = 1e-9 * h;
        for (const auto& t : raw_.tri) {
          const Vec2 &a = raw_.node_xy[t[0]], &b = raw_.node_xy[t[1]], &c = raw_.node_xy[t[2]];
          if (s.x < std::min({a.x, b.x, c.x}) - tol || s.x > std::max({a.x, b.x, c.x}) + tol ||
              s.y < std::min({a.y, b.y, c.y}) - tol || s.y > std::max({a.y, b.y, c.y}) + tol)
            continue;
          const auto hit = CGAL::intersection(ray, Kernel::Triangle_2(to_point(a), to_point(b), to_point(c)));
          if (!hit) continue;
          const Segment* seg = boost::get<Segment>(&*hit);
          if (!seg || seg->is_degenerate()) continue;
          const Point end = seg->source() == start ? seg->target() : seg->target() == start ? seg->source() : start;
          if (end == start) continue;  // the ray crosses this triangle further on: not the end's
          curves.emplace_back(Segment(start, end), CurveTag{kEdgeExtension, id});
          break;
        }
        ++id;
      }
    }
  }
}

void Cutter::number_faces() {
  lab_.faces.clear();
  std::int32_t n = 0;
  for (auto f = arr_.faces_begin(); f != arr_.faces_end(); ++f) {
    f->set_data(n++);
    lab_.faces.push_back(f);
  }
}

// Calls fn(halfedge) for every halfedge on the boundary of face f (outer and inner CCBs).
template <typename Fn>
void for_each_boundary_halfedge(Face_handle f, Fn fn) {
  for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) {
    auto c = *ccb, start = c;
    do fn(Halfedge_handle(c)); while (++c != start);
  }
  for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) {
    auto c = *ccb, start = c;
    do fn(Halfedge_handle(c)); while (++c != start);
  }
}

std::uint8_t edge_kinds(Halfedge_handle h) {
  std::uint8_t k = 0;
  for (const CurveTag& t : h->curve().data()) k |= t.kind;
  return k;
}

void Cutter::label_faces() {
  const std::size_t nf = lab_.faces.size();
  // Union faces across edges that do not change the label (non-mesh edges for the triangle,
  // non-boundary edges for the body).
  UnionFind tri_uf(nf), body_uf(nf);
  for (auto e = arr_.edges_begin(); e != arr_.edges_end(); ++e) {
    const std::uint8_t kinds = edge_kinds(e);
    const std::int32_t f1 = e->face()->data(), f2 = e->twin()->face()->data();
    if (!(kinds & kEdgeMesh)) tri_uf.unite(f1, f2);
    if (!(kinds & kEdgeBoundary)) body_uf.unite(f1, f2);
  }
  // Labels per component root, read off informative halfedges.
  constexpr std::int32_t kUnset = -2;
  std::vector<std::int32_t> tri_root(nf, kUnset), body_root(nf, kUnset), body_witness(nf, -1);
  for (auto h = arr_.halfedges_begin(); h != arr_.halfedges_end(); ++h) {
    const std::int32_t f = h->face()->data();
    const bool l2r = h->direction() == CGAL::ARR_LEFT_TO_RIGHT;
    for (const CurveTag& t : h->curve().data()) {
      if (t.kind == kEdgeMesh) {
        const MeshEdge& me = raw_.edges[t.id];
        tri_root[tri_uf.find(f)] = l2r ? me.left : me.right;
      }
    }
    if (!(edge_kinds(h) & kEdgeBoundary)) continue;
    // Inside body b if some boundary segment on this edge has body b on the halfedge's left.
    std::int32_t claim = -1, witness = -1;
    for (const CurveTag& t : h->curve().data()) {
      if (t.kind != kEdgeBoundary) continue;
      const BoundarySeg& s = boundary_[t.id];
      if (witness < 0) witness = s.body;
      if (l2r == s.body_left) {
        if (claim >= 0 && claim != s.body) {
          throw InputError(file_, "/bodies/" + std::to_string(std::max(claim, s.body)),
                           "overlaps body " + std::to_string(std::min(claim, s.body)));
        }
        claim = s.body;
        witness = s.body;
      }
    }
    const std::int32_t root = body_uf.find(f);
    if (body_root[root] == kUnset) {
      body_root[root] = claim;
      body_witness[root] = witness;
    } else if (body_root[root] != claim) {
      // One connected region said to be inside two bodies, or inside and outside one: bodies
      // overlap (the geometry checks already ensured each polygon is simple).
      const std::int32_t a = body_witness[root], b = witness;
      const Vec2 p = round_exact(h->source()->point());
      std::ostringstream msg;
      msg << "overlaps body " << std::min(a, b) << " (near x = " << p.x << ", y = " << p.y
          << "); bodies may touch but not overlap";
      throw InputError(file_, "/bodies/" + std::to_string(std::max(a, b)), msg.str());
    }
  }
  lab_.tri.assign(nf, -1);
  lab_.body.assign(nf, -1);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::int32_t t = tri_root[tri_uf.find(static_cast<std::int32_t>(f))];
    const std::int32_t b = body_root[body_uf.find(static_cast<std::int32_t>(f))];
    lab_.tri[f] = t == kUnset ? -1 : t;
    lab_.body[f] = b == kUnset ? -1 : b;
    if (lab_.body[f] >= 0 && lab_.tri[f] < 0) {
      if (region_) {
        lab_.body[f] = -1;  // inside a body, outside the region's triangles: not cut here
        continue;
      }
      throw std::logic_error("cover cutter: a face inside a body lies outside the mesh");
    }
  }
}

void Cutter::bridge_holes() {
  for (const Curve& c : find_bridges()) CGAL::insert(arr_, c);
}

std::vector<Curve> Cutter::find_bridges() const {
  // Bridges for all holes are found first (handles stay valid), then inserted. Each goes from a
  // hole's top vertex straight up to the face boundary above it, which lies strictly higher, so
  // the bridges form a forest rooted at the outer boundary: no face is split. The top vertex and
  // the boundary above are the face's, whatever order the arrangement keeps its faces and loops in.
  std::vector<Curve> bridges;
  for (std::size_t f = 0; f < lab_.faces.size(); ++f) {
    const Face_handle face = lab_.faces[f];
    if (lab_.body[f] < 0 || face->number_of_inner_ccbs() == 0) continue;
    std::vector<Halfedge_handle> all;
    for_each_boundary_halfedge(face, [&](Halfedge_handle h) { all.push_back(h); });
    for (auto ccb = face->inner_ccbs_begin(); ccb != face->inner_ccbs_end(); ++ccb) {
      // Top vertex: greatest y, then greatest x.
      auto c = *ccb, start = c;
      Point top = c->source()->point();
      do {
        const Point& p = c->source()->point();
        if (p.y() > top.y() || (p.y() == top.y() && p.x() > top.x())) top = p;
      } while (++c != start);
      bool found = false;
      Kernel::FT best_y;
      for (Halfedge_handle h : all) {
        const Point& a = h->source()->point();
        const Point& b = h->target()->point();
        Kernel::FT y;
        if (a.x() == b.x()) {
          if (a.x() != top.x()) continue;
          y = a.y() < b.y() ? a.y() : b.y();
        } else {
          if ((a.x() > top.x() && b.x() > top.x()) || (a.x() < top.x() && b.x() < top.x())) continue;
          y = a.y() + (b.y() - a.y()) * (top.x() - a.x()) / (b.x() - a.x());
        }
        if (y > top.y() && (!found || y < best_y)) {
          best_y = y;
          found = true;
        }
      }
      if (!found) throw std::logic_error("cover cutter: a hole has no boundary above it");
      bridges.emplace_back(Segment(top, Point(top.x(), best_y)), CurveTag{kEdgeBridge, 0});
    }
  }
  return bridges;
}

void Cutter::round_vertices() {
  for (auto v = out_->vertices_begin(); v != out_->vertices_end(); ++v) v->set_data(round_exact(v->point()));
}

// A face that is no rock in doubles: its loop, rounded, fits in a box of side 1e-9·h or encloses
// no positive area. Exact arithmetic gives such specks where three cuts meet within round-off of
// one point (a crack ending on a joint beside a mesh edge); as an element it would have zero or
// negative mass and stiffness, and its covers no stiffness at all. The area's sign is the rounded
// loop's own (loop_area.h), whatever corner the arrangement's loop starts at.
bool Cutter::speck(Face_handle face) const {
  Box box = Box::empty();
  std::vector<Vec2> loop;
  auto c = *face->outer_ccbs_begin(), start = c;
  do {
    const Vec2 p = c->source()->data();
    box.add(p.x, p.y);
    loop.push_back(p);
  } while (++c != start);
  return box.longer_side() < 1e-9 * scene_.mesh_size || loop_area_sign(loop.data(), loop.size()) <= 0;
}

Mesh Cutter::extract() {
  Mesh mesh;
  mesh.mesh_size = scene_.mesh_size;
  mesh.dofs_per_cover = 2;
  const std::size_t nf = lab_.faces.size();

  // Manifold elements: faces inside a body, ordered by triangle (stable in face order).
  std::vector<std::int32_t> me_faces;
  for (std::size_t f = 0; f < nf; ++f)
    if (lab_.body[f] >= 0 && !speck(lab_.faces[f])) me_faces.push_back(static_cast<std::int32_t>(f));
  std::stable_sort(me_faces.begin(), me_faces.end(),
                   [&](std::int32_t a, std::int32_t b) { return lab_.tri[a] < lab_.tri[b]; });
  std::vector<std::int32_t> face_me(nf, -1);
  for (std::size_t e = 0; e < me_faces.size(); ++e)
    face_me[me_faces[e]] = static_cast<std::int32_t>(e);
  const std::size_t ne = me_faces.size();

  // Kept triangles and nodes, renumbered in lattice order.
  std::vector<std::int32_t> tri_new(raw_.tri.size(), -1), node_new(raw_.node_xy.size(), -1);
  for (std::int32_t f : me_faces) tri_new[lab_.tri[f]] = 0;
  std::int32_t nt = 0;
  for (std::size_t t = 0; t < raw_.tri.size(); ++t) {
    if (tri_new[t] < 0) continue;
    tri_new[t] = nt++;
    for (std::int32_t n : raw_.tri[t]) node_new[n] = 0;
  }
  std::int32_t nn = 0;
  for (std::size_t n = 0; n < raw_.node_xy.size(); ++n) {
    if (node_new[n] < 0) continue;
    node_new[n] = nn++;
    mesh.node_xy.push_back(raw_.node_xy[n].x);
    mesh.node_xy.push_back(raw_.node_xy[n].y);
  }
  kept_.clear();
  for (std::size_t t = 0; t < raw_.tri.size(); ++t)
    if (tri_new[t] >= 0) {
      for (std::int32_t n : raw_.tri[t]) mesh.triangle_nodes.push_back(node_new[n]);
      kept_.push_back(raw_.tri[t]);
    }

  // Element loops: the outer CCB of each face (holes were bridged into it).
  mesh.element_loop_offset.push_back(0);
  for (std::int32_t f : me_faces) {
    const Face_handle face = lab_.faces[f];
    if (face->number_of_inner_ccbs() != 0)
      throw std::logic_error("cover cutter: an element still has a hole after bridging");
    mesh.element_triangle.push_back(tri_new[lab_.tri[f]]);
    mesh.element_body.push_back(lab_.body[f]);
    auto c = *face->outer_ccbs_begin(), start = c;
    do {
      const Vec2 p = c->source()->data();
      mesh.loop_xy.push_back(p.x);
      mesh.loop_xy.push_back(p.y);
      std::uint8_t kinds = 0;
      std::int32_t joint = -1;
      for (const CurveTag& t : c->curve().data()) {
        kinds |= t.kind;
        if (t.kind == kEdgeJoint && (joint < 0 || t.id < joint)) joint = t.id;
      }
      mesh.loop_edge_origin.push_back(kinds);
      mesh.loop_edge_joint.push_back(joint);
      if (kinds & (kEdgeJoint | kEdgeBoundary)) {
        const std::int32_t v = static_cast<std::int32_t>(mesh.loop_edge_origin.size() - 1);
        mesh.contact_edge.push_back(v);
        mesh.contact_edge_element.push_back(face_me[f]);
        mesh.contact_edge_opposite.push_back(face_me[c->twin()->face()->data()]);
      }
    } while (++c != start);
    mesh.element_loop_offset.push_back(static_cast<std::int32_t>(mesh.loop_edge_origin.size()));
  }

  // Physical covers and blocks: union–find over (element, triangle corner) slots and elements,
  // joined across mesh-only edges (see the file comment, step 5).
  UnionFind slot_uf(3 * ne), block_uf(ne);
  for (auto e = out_->edges_begin(); e != out_->edges_end(); ++e) {
    // A gap end's extension joins blocks but not covers (step 5), on a mesh edge or inside a triangle.
    const std::uint8_t kinds = edge_kinds(e);
    const bool extension = (kinds & kEdgeExtension) != 0;
    if ((kinds & ~kEdgeExtension) != kEdgeMesh && kinds != kEdgeExtension) continue;
    // A piece of mesh edge that rounds to one point (three cuts meeting within round-off of it)
    // joins nothing: in doubles it is no edge, and the re-cut (recut.cpp), which links elements
    // by their rounded edges, must find the same blocks and covers as this cut.
    if (e->source()->data() == e->target()->data()) continue;
    const std::int32_t m1 = face_me[e->face()->data()], m2 = face_me[e->twin()->face()->data()];
    if (m1 < 0 || m2 < 0) continue;
    block_uf.unite(m1, m2);
    if (extension) continue;
    const MeshEdge& me = raw_.edges[e->curve().data().begin()->id];
    const auto& t1 = raw_.tri[lab_.tri[me_faces[m1]]];
    const auto& t2 = raw_.tri[lab_.tri[me_faces[m2]]];
    for (std::int32_t node : {me.a, me.b}) {
      const int k1 = static_cast<int>(std::find(t1.begin(), t1.end(), node) - t1.begin());
      const int k2 = static_cast<int>(std::find(t2.begin(), t2.end(), node) - t2.begin());
      slot_uf.unite(3 * m1 + k1, 3 * m2 + k2);
    }
  }
  // Covers numbered by node, then by their first element.
  std::vector<std::int32_t> roots;
  for (std::size_t s = 0; s < 3 * ne; ++s)
    if (slot_uf.find(static_cast<std::int32_t>(s)) == static_cast<std::int32_t>(s))
      roots.push_back(static_cast<std::int32_t>(s));
  auto slot_node = [&](std::int32_t s) {
    return node_new[raw_.tri[lab_.tri[me_faces[s / 3]]][s % 3]];
  };
  std::stable_sort(roots.begin(), roots.end(), [&](std::int32_t a, std::int32_t b) {
    return slot_node(a) < slot_node(b);
  });
  std::vector<std::int32_t> root_cover(3 * ne, -1);
  for (std::size_t c = 0; c < roots.size(); ++c) {
    root_cover[roots[c]] = static_cast<std::int32_t>(c);
    mesh.cover_node.push_back(slot_node(roots[c]));
    mesh.cover_body.push_back(mesh.element_body[roots[c] / 3]);
  }
  mesh.element_covers.resize(3 * ne);
  for (std::size_t s = 0; s < 3 * ne; ++s)
    mesh.element_covers[s] = root_cover[slot_uf.find(static_cast<std::int32_t>(s))];

  std::vector<std::int32_t> block_of_root(ne, -1);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t r = block_uf.find(static_cast<std::int32_t>(e));
    if (block_of_root[r] < 0) {
      block_of_root[r] = static_cast<std::int32_t>(mesh.block_body.size());
      mesh.block_body.push_back(mesh.element_body[e]);
    }
    mesh.element_block.push_back(block_of_root[r]);
  }
  return mesh;
}

void Cutter::make_raw_mesh_of_scene() {
  raw_ = make_raw_mesh(scene_, region_);
  if (region_) {
    region_box_ = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const auto& tri : raw_.tri)
      for (std::int32_t n : tri) {
        const Vec2& p = raw_.node_xy[n];
        region_box_ = {std::min(region_box_.x0, p.x), std::min(region_box_.y0, p.y),
                       std::max(region_box_.x1, p.x), std::max(region_box_.y1, p.y)};
      }
  }
}

Mesh Cutter::run(CutTimings* timings) {
  CutTimings t;
  nmm::Stopwatch t0;
  make_raw_mesh_of_scene();
  t.mesh_generation = t0.seconds();

  t0.restart();
  insert_curves();
  t.arrangement = t0.seconds();

  t0.restart();
  number_faces();
  label_faces();
  const std::size_t faces_before = lab_.faces.size();
  bridge_holes();
  // Bridges never split a face, so the labels carry over unchanged.
  if (arr_.number_of_faces() != faces_before)
    throw std::logic_error("cover cutter: a hole bridge split a face");
  t.labelling = t0.seconds();

  t0.restart();
  round_vertices();
  Mesh mesh = extract();
  t.covers = t0.seconds();
  if (timings) *timings = t;
  return mesh;
}

Mesh Cutter::run_kept() {
  make_raw_mesh_of_scene();
  insert_curves();
  return finish_kept();
}

Mesh Cutter::grow(std::size_t first_joint) {
  // The same segments the sweep takes (joint_curves, snapped alike; a whole cut: no region), each
  // on its own: a zone walk from its left end, splitting the edges it crosses or runs along
  // (their tags merge, as in the sweep). The arrangement of a set of segments is one whatever
  // order they go in; only the order CGAL keeps faces, vertices and loops in differs, which
  // extract() does not depend on beyond numbering.
  std::vector<Curve> curves;
  joint_curves(first_joint, curves);
  for (const Curve& c : curves) CGAL::insert(arr_, c);
  return finish_kept();
}

Mesh Cutter::finish_kept() {
  number_faces();
  label_faces();
  const std::vector<Curve> bridges = find_bridges();
  out_ = &arr_;
  if (!bridges.empty()) {
    // The bridges go into a copy, so that arr_ stays the arrangement of the scene's curves alone
    // for the next growth. The copy's faces carry their indices (face data), so the labels hold.
    bridged_ = arr_;
    out_ = &bridged_;
    for (auto f = bridged_.faces_begin(); f != bridged_.faces_end(); ++f) lab_.faces[f->data()] = f;
    const std::size_t faces_before = bridged_.number_of_faces();
    for (const Curve& c : bridges) CGAL::insert(bridged_, c);
    if (bridged_.number_of_faces() != faces_before) throw std::logic_error("cover cutter: a hole bridge split a face");
  }
  round_vertices();
  Mesh mesh = extract();
  mesh.tool_version = NMM_VERSION;
  return mesh;
}

// The cut inputs of a scene (what make_raw_mesh, insert_curves and gap_end_extensions read): the
// bodies' rings (and their materials' indices, which label nothing but name the body's rock), the
// mesh size and the gap-end switch. Materials, supports, loads and the rest do not enter the cut.
bool same_bodies_and_mesh(const SceneDef& a, const SceneDef& b) {
  if (a.mesh_size != b.mesh_size || a.split_gap_ends != b.split_gap_ends || a.bodies.size() != b.bodies.size())
    return false;
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyDef &p = a.bodies[i], &q = b.bodies[i];
    if (p.material != q.material || p.outer != q.outer || p.holes != q.holes) return false;
  }
  return true;
}

}  // namespace

// The kept cut (GrowingCut): the scene it is of, with its file name (the cutter holds references
// to both), and the cutter whose arrangement is that scene's curves after the sweep and growths.
struct GrowingCut::Impl {
  SceneDef scene;
  std::string file;
  std::unique_ptr<Cutter> cutter;
};

GrowingCut::GrowingCut() : impl_(std::make_unique<Impl>()) {}
GrowingCut::~GrowingCut() = default;
GrowingCut::GrowingCut(GrowingCut&&) noexcept = default;
GrowingCut& GrowingCut::operator=(GrowingCut&&) noexcept = default;

Mesh GrowingCut::cut(const SceneDef& scene, const std::string& file) {
  if (scene.bodies.empty()) throw InputError(file, "/bodies", "no bodies");
  Impl& k = *impl_;
  // A growth: the kept scene's bodies and mesh, and its joints, each unchanged, first.
  bool growth = k.cutter != nullptr && same_bodies_and_mesh(k.scene, scene) && scene.joints.size() >= k.scene.joints.size();
  for (std::size_t j = 0; growth && j < k.scene.joints.size(); ++j)
    growth = scene.joints[j].set == k.scene.joints[j].set && scene.joints[j].points == k.scene.joints[j].points;
  try {
    if (growth) {
      const std::size_t first = k.scene.joints.size();
      k.scene.joints.insert(k.scene.joints.end(), scene.joints.begin() + static_cast<std::ptrdiff_t>(first),
                            scene.joints.end());
      k.file = file;
      ++grown_;
      return k.cutter->grow(first);
    }
    k.cutter.reset();
    k.scene = scene;
    k.file = file;
    k.cutter = std::make_unique<Cutter>(k.scene, k.file);
    ++fresh_;
    return k.cutter->run_kept();
  } catch (...) {
    k.cutter.reset();  // an arrangement left half-grown is no scene's
    throw;
  }
}

RegionCut cut_region(const SceneDef& scene, const std::vector<std::array<std::int32_t, 3>>& lattice_triangles,
                     const std::string& file) {
  std::vector<std::array<std::int32_t, 3>> region = lattice_triangles;
  for (auto& t : region) std::sort(t.begin(), t.end());
  std::sort(region.begin(), region.end());
  Cutter cutter(scene, file, region);
  RegionCut out;
  out.mesh = cutter.run(nullptr);
  out.mesh.tool_version = NMM_VERSION;
  out.lattice_triangles = cutter.kept_triangles();
  return out;
}

Mesh build_mesh(const SceneDef& scene, const std::string& file, CutTimings* timings) {
  if (scene.bodies.empty()) throw InputError(file, "/bodies", "no bodies");
  Cutter cutter(scene, file);
  Mesh mesh = cutter.run(timings);
  mesh.tool_version = NMM_VERSION;
  return mesh;
}

}  // namespace nmm::pre
