// Which element holds a point: the first element whose loop contains it (even–odd rule,
// common/ring_geometry.h), else the nearest one, with its distance, so that a caller can accept a
// point on a boundary (within a tolerance) and refuse one outside every body. Used for the
// scene's fixed, load and measure points in the mesh as cut (model.h) and for bolts, located in
// the configuration they are installed in (solver/reinforcement/bolt_layout.h).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "common/mesh.h"
#include "common/vec2.h"

namespace nmm::solve {

struct PointLocation {
  std::int32_t element = -1;  ///< the element, -1 when there is none (every element skipped)
  double distance = std::numeric_limits<double>::infinity();  ///< m, 0 inside its loop
};

/// The element of `mesh` holding p among the loops at loop_xy ([2·v] m: the mesh as cut, or a
/// state's current loops); elements with skip[e] != 0 (if given) are passed over.
PointLocation locate_point(const Mesh& mesh, const std::vector<double>& loop_xy, Vec2 p,
                           const std::vector<std::uint8_t>* skip = nullptr);

}  // namespace nmm::solve
