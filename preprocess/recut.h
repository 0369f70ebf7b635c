// Re-cutting the covers a new joint crosses (a crack that grew during a run), with the cover
// cutter itself (cover_cutter.h cut_region), and the map from the new mesh back to the old one
// that lets the solver carry its state over (solver/fracture/).
//
// Method (docs/fracture.md "Re-cutting"):
//   T  the triangles a new joint segment touches (bounding-box test, then the segment against the
//      triangle's closed region with a tolerance of 1e-9·h: a triangle too many is cut again to
//      the same pieces, one too few would be wrong);
//   R  every triangle with a node of T: the stars of T's nodes, so that those nodes' physical
//      covers (pieces of star ∩ body minus joints) come out whole;
//   cut_region(R) with the scene's joints, the new ones included: exactly what build_mesh gives
//      for R's triangles, by the same arrangement code on the curves that reach them;
//   splice: R's elements replaced by the cut's; the covers of T's nodes replaced by the cut's;
//      every other element and cover kept; blocks and contact edges recomputed over the whole
//      mesh from the loops (elements joined across mesh-only edges; a loop edge's opposite element
//      is the one whose loop runs the same edge the other way).
// Only R is cut exactly: the cost of the arrangement is that of the triangles the joint touches
// and their neighbours; the splice and the recomputed blocks are linear in the mesh.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::pre {

/// Where each piece of a re-cut mesh came from in the mesh before.
struct RecutMap {
  std::vector<std::int32_t> element_parent;  ///< [new me] the old element it is (a piece of)
  std::vector<std::int32_t> cover_parent;    ///< [new pc] the old cover it is (a piece of)
  /// [new loop vertex] the old loop vertex of the parent element at the same point, or -1 (a
  /// vertex the new joints made)
  std::vector<std::int32_t> vertex_parent;
  std::vector<std::int32_t> cut_triangles;   ///< triangles of T (the new joints touch them)
  std::size_t region_triangles = 0;          ///< triangles of R (cut again)
  /// s, diagnostics: finding T and R (a scan of the triangles), the exact cut of R, the splice
  double seconds_find = 0, seconds_cut = 0, seconds_splice = 0;
};

/// The mesh of `scene` — whose joints from `first_new_joint` on are new — re-cut from `old`, the
/// mesh of the same scene without them (same bodies, mesh size and earlier joints). Throws what
/// build_mesh throws.
Mesh recut(const Mesh& old, const SceneDef& scene, std::size_t first_new_joint, const std::string& file,
           RecutMap& map);

}  // namespace nmm::pre
