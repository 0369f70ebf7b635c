// Whether a crack parted an element it crossed, and which crack it was (docs/fracture.md "The
// rule", 5: re-armed elements).
//
// At cover order 0 an element's displacement is u(x) = Σ_k λ_k(x)·u_{c_k}, λ the barycentric
// coordinates in its mathematical triangle and c_k the physical cover of node k it takes
// (Mesh::element_covers). A crack cut through the triangle leaves a piece on each side; the
// jump across it is
//     [u](x) = Σ_k λ_k(x)·(u_{c_k⁺} − u_{c_k⁻}),
// which has no term for a node whose star the crack did not run right across (it must enter and
// leave the star's outer edges): both pieces take that node's cover, c_k⁺ = c_k⁻. Where a piece
// shares a cover with the piece across its crack, the crack has not parted the element: the
// faces cannot open freely, the pieces' strain stays tied to the rock on both sides, and the
// stress the crack was cut for stays (the step-path slope at h 0.6 m: eleven such elements at
// 1.1–2.3 × their strength for 50 steps, the wedge held). That is the case at every crack tip
// inside the rock, and wherever a crack of one to three elements ends inside a bridge.
//
// The crack to grow on from such an element is the one cut through its triangle: the segments
// joined to a segment inside the triangle end to end (consecutive segments of a crack share the
// same doubles as ends: a tip starts its next segment where the last one left off).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "common/vec2.h"

namespace nmm::solve {

/// The elements of each mathematical triangle of a mesh (CSR over Mesh::element_triangle).
class TriangleElements {
 public:
  explicit TriangleElements(const Mesh& mesh);
  /// Some piece of e's triangle across one of e's crack edges (loop_edge_joint ≥ first_crack,
  /// the first joint that is a crack; the edge reversed, its ends within 1e-9·h) takes the same
  /// physical cover as e at some node: the crack has not parted e from it. (Pieces only a scene
  /// joint separates from e are not compared.)
  bool shares_a_cover(const Mesh& mesh, std::size_t e, std::int32_t first_crack) const;
  /// The nodes of e's triangle (bit k: Mesh::triangle_nodes[3·t + k]) whose cover such a piece
  /// shares with e: the stars the crack has not yet run right across. 0 where e is parted.
  unsigned shared_nodes(const Mesh& mesh, std::size_t e, std::int32_t first_crack) const;
  bool of(const Mesh& mesh) const { return &mesh == mesh_ && mesh.element_count() == elements_; }

 private:
  const Mesh* mesh_ = nullptr;
  std::size_t elements_ = 0;
  std::vector<std::size_t> offset_;  // [triangles + 1]
  std::vector<std::int32_t> element_;
};

/// Point p lies inside (not on the outer edge of) the star of a node of e's triangle flagged in
/// `nodes` (bit k: Mesh::triangle_nodes[3·t + k]): a crack ending at p has not run across it.
bool inside_star(const Mesh& mesh, std::size_t e, unsigned nodes, const Vec2& p);

/// The crack segments (as cut) with their end points sorted, so that the segments joined end to
/// end are found by a binary search: built once for all the elements a call of Fracture::find
/// looks at (a shattering block has hundreds of them over their strength, and building the
/// lookup for each cost a twentieth of the run's CPU, the step-path slope at h 0.35 m).
class CrackEnds {
 public:
  CrackEnds(const std::vector<Vec2>& ends_a, const std::vector<Vec2>& ends_b);
  const std::vector<Vec2>& a() const { return *a_; }
  const std::vector<Vec2>& b() const { return *b_; }
  /// Calls f(i) for each segment i with an end exactly at p.
  template <class F>
  void at(const Vec2& p, F&& f) const;

 private:
  struct End {
    double x, y;        // m
    std::size_t index;  // into a()/b()
  };
  const std::vector<Vec2>* a_;
  const std::vector<Vec2>* b_;
  std::vector<End> sorted_;  // by (x, y), then index
};

/// The indices into `ends_a`/`ends_b` (a crack's segments, as cut) of the segments that lie in
/// triangle t of `mesh` (their mid-point within 1e-9·h of it), and of every segment joined to
/// those end to end (a shared end point, exactly): the cracks through the triangle.
std::vector<std::size_t> cracks_through_triangle(const Mesh& mesh, std::size_t t, const std::vector<Vec2>& ends_a,
                                                 const std::vector<Vec2>& ends_b);
/// The same with the segments' ends sorted once (CrackEnds): the same indices.
std::vector<std::size_t> cracks_through_triangle(const Mesh& mesh, std::size_t t, const CrackEnds& ends);

template <class F>
void CrackEnds::at(const Vec2& p, F&& f) const {
  auto less = [](const End& e, const Vec2& q) { return e.x < q.x || (e.x == q.x && e.y < q.y); };
  for (auto it = std::lower_bound(sorted_.begin(), sorted_.end(), p, less);
       it != sorted_.end() && it->x == p.x && it->y == p.y; ++it)
    f(it->index);
}

}  // namespace nmm::solve
