// The lattice of mathematical-mesh nodes over a scene's bodies, and the range checks of every
// number derived from it (docs/preprocess.md, "Limits").
//
// Node (i, j) sits at x = (i + ½·(j mod 2))·h, y = j·h·√3/2: equilateral triangles of side h
// anchored at the origin. The lattice spans the bodies' bounding box plus one row and column on
// every side. The scene parser checks it (so a bad mesh size is an exit-2 line naming
// /mesh/size) and the cover cutter builds its mesh from the same struct, so both agree on every
// derived quantity: index ranges, node count, node coordinates.
//
// Why the checks: node indices are converted from doubles (x / h) to integers, node numbers are
// int32 in the mesh file, and the cutter and solver form products of coordinates (areas, second
// moments). A mesh size of 1e308 put nodes at ±1.5e308 m, whose products are inf; CGAL crashed
// on them. Every node coordinate is therefore bounded by kMaxLatticeCoordinate, so products of
// up to four coordinates stay far inside the double range.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/scene.h"

namespace nmm {

/// m: no mathematical node may lie farther than this from the origin in x or y. Bodies lie
/// within kMaxCoordinate (1e7 m); this leaves room for the lattice's border row at any mesh
/// size up to the bodies' own size, and keeps (4e7)⁴ = 2.6e30 far below the double range.
constexpr double kMaxLatticeCoordinate = 4 * kMaxCoordinate;

struct Lattice {
  double h = 0;   ///< m, side of the triangles
  double dy = 0;  ///< m, row spacing h·√3/2
  std::int64_t i0 = 0, j0 = 0;  ///< smallest column and row index
  std::int64_t ni = 0, nj = 0;  ///< columns and rows: node (i, j) for i in [i0, i0+ni)

  /// Position of node (i, j), m.
  Vec2 node(std::int64_t i, std::int64_t j) const {
    const double shift = ((j % 2) + 2) % 2 == 1 ? 0.5 : 0.0;
    return {(static_cast<double>(i) + shift) * h, static_cast<double>(j) * dy};
  }
  /// Index of node (i, j) in row-major order (checked to fit int32 by lattice_problem()).
  std::int32_t index(std::int64_t i, std::int64_t j) const {
    return static_cast<std::int32_t>((j - j0) * ni + (i - i0));
  }
  std::int64_t nodes() const { return ni * nj; }
  /// p, or the lattice point it was meant to be: the nearest node where p lies within round-off
  /// of it, else p with y on the nearest node row where it lies within round-off of that row
  /// (see snap_tolerance). A joint typed to end at (0.3, 0) with h = 0.05 ends 5.6e-17 m short
  /// of node 6's 6 × 0.05 = 0.30000000000000004: exactly, it stops before the star's edge, so
  /// the star of the node before it is not split and the crack's faces stay tied there (an edge
  /// crack's K_I 19.6 % low at h = 0.05 m, docs/crack-tips.md), where the same crack typed from
  /// the other side ran an ulp past its last node and split it.
  Vec2 snap(const Vec2& p) const;
};

/// m: how far a point may lie from a lattice node (or row) and still be taken as on it: 16
/// ulps of the larger coordinate or of h — round-off between a typed decimal and i·h, far
/// below any length a scene means (1e-15 m at 0.3 m).
double snap_tolerance(const Vec2& node, double h);

/// What is wrong with the lattice of mesh size h over these bodies, in words that name the mesh
/// size; "" when every derived quantity is in range. Needs only finite h > 0 and at least one
/// body with finite points (what parse_scene() has checked before it calls this).
std::string lattice_problem(const std::vector<BodyDef>& bodies, double h);

/// The lattice over the bodies. Throws std::logic_error if lattice_problem() is not empty: the
/// scene parser must have rejected such a scene with an InputError.
Lattice make_lattice(const std::vector<BodyDef>& bodies, double h);

}  // namespace nmm
