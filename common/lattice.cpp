// Lattice over the bodies and the range checks of its derived numbers: see lattice.h.
//
// Order of the checks: each one only uses quantities the previous ones have bounded, so no
// intermediate value overflows or is converted to an integer out of range.
// 1. The bodies' bounding box (from points within ±kMaxCoordinate: finite, area finite).
// 2. Triangle count ≈ box area / (√3/4·h²) ≤ kMaxMeshTriangles (evaluated as a quotient of
//    finite numbers: inf when h² underflows, which is still "too many").
// 3. Lattice index bounds x/h and y/dy as doubles, within ±kMaxLatticeCoordinate/h before they
//    become integers; node coordinates (index·h) within ±kMaxLatticeCoordinate.
// 4. Node count ni·nj fits int32 (node numbers are int32 in the mesh and the mesh file).
#include "common/lattice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/number_format.h"
#include "common/ring_geometry.h"

namespace nmm {

namespace {

// Index bounds as doubles: one row and column beyond the box on every side.
struct IndexRange {
  double i0, i1, j0, j1;
};

IndexRange index_range(const Box& b, double h, double dy) {
  return {std::floor(b.x0 / h) - 1, std::ceil(b.x1 / h) + 1, std::floor(b.y0 / dy) - 1,
          std::ceil(b.y1 / dy) + 1};
}

}  // namespace

std::string lattice_problem(const std::vector<BodyDef>& bodies, double h) {
  if (!(h > 0) || !std::isfinite(h)) return "mesh size must be a finite number > 0";
  const Box b = bodies_box(bodies);
  if (!(b.x0 <= b.x1 && b.y0 <= b.y1)) return "no body points to lay the mesh over";
  // 2. Triangle count.
  const double triangle_area = std::sqrt(3.0) / 4.0;  // per h²
  const double box = (b.x1 - b.x0) * (b.y1 - b.y0);   // ≤ (2e7)² = 4e14 m²
  const double triangles = box / triangle_area / h / h;
  if (!(triangles <= kMaxMeshTriangles)) {
    const double smallest = std::sqrt(box / (triangle_area * kMaxMeshTriangles));
    const std::string count =
        std::isfinite(triangles) ? "about " + format_rough(triangles, 2) : "more than 1e+308";
    return "mesh size " + format_number(h) + " m would make " + count +
           " triangles over the bodies' bounding box (limit " +
           format_rough(kMaxMeshTriangles, 6) + "); use a larger size (at least " +
           format_rough(smallest, 3) + " m)";
  }
  // 3. Node coordinates. The farthest node lies at most 1.5 h (x) or 2·dy (y) beyond the box.
  const double dy = h * std::sqrt(3.0) / 2.0;
  const IndexRange r = index_range(b, h, dy);
  const double reach = std::max({std::fabs((r.i0 - 0.5) * h), std::fabs((r.i1 + 0.5) * h),
                                 std::fabs(r.j0 * dy), std::fabs(r.j1 * dy)});
  if (!(reach <= kMaxLatticeCoordinate))
    return "mesh size " + format_number(h) + " m is too large: the mathematical mesh over the " +
           "bodies would reach " +
           (std::isfinite(reach) ? format_rough(reach, 3) : std::string("beyond 1e+308")) +
           " m from the origin (limit " +
           format_rough(kMaxLatticeCoordinate, 3) +
           " m); use a size no larger than the bodies themselves";
  // 4. Node count (ni, nj ≤ 2·4e7/h + 3 here, so their product is a finite double).
  const double nodes = (r.i1 - r.i0 + 1) * (r.j1 - r.j0 + 1);
  if (!(nodes <= static_cast<double>(std::numeric_limits<std::int32_t>::max())))
    return "mesh size " + format_number(h) + " m would make " + format_rough(nodes, 3) +
           " mesh nodes over the bodies' bounding box (limit 2^31 - 1); use a larger size";
  return "";
}

Lattice make_lattice(const std::vector<BodyDef>& bodies, double h) {
  const std::string problem = lattice_problem(bodies, h);
  if (!problem.empty()) throw std::logic_error("make_lattice on an unchecked scene: " + problem);
  Lattice L;
  L.h = h;
  L.dy = h * std::sqrt(3.0) / 2.0;
  const IndexRange r = index_range(bodies_box(bodies), h, L.dy);
  L.i0 = static_cast<std::int64_t>(r.i0);
  L.j0 = static_cast<std::int64_t>(r.j0);
  L.ni = static_cast<std::int64_t>(r.i1) - L.i0 + 1;
  L.nj = static_cast<std::int64_t>(r.j1) - L.j0 + 1;
  return L;
}

double snap_tolerance(const Vec2& node, double h) {
  return 16 * std::numeric_limits<double>::epsilon() * std::max({std::abs(node.x), std::abs(node.y), h});
}

Vec2 Lattice::snap(const Vec2& p) const {
  if (!(h > 0) || !std::isfinite(p.x) || !std::isfinite(p.y)) return p;
  const double j = std::nearbyint(p.y / dy);
  const double shift = std::fmod(std::abs(j), 2.0) == 1.0 ? 0.5 : 0.0;
  const double i = std::nearbyint(p.x / h - shift);
  const Vec2 n = node(static_cast<std::int64_t>(i), static_cast<std::int64_t>(j));
  const double tol = snap_tolerance(n, h);
  if (std::abs(p.y - n.y) > tol) return p;
  if (std::abs(p.x - n.x) <= tol) return n;
  return {p.x, n.y};
}

}  // namespace nmm
