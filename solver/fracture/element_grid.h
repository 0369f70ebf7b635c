// Where a point is among a mesh's manifold elements as cut (the reference configuration, where
// cracks are cut): the elements by cell of a uniform grid of side h over their loops' bounding
// boxes. A crack tip grows by asking which element lies just ahead of it (fracture.cpp).
//
// The mesh as cut changes only when cracks re-cut it, so a Fracture keeps one grid per mesh
// (built when a tip first needs it) instead of sorting every element into cells after every
// step: at 10⁵ elements the build is a sort of ~2·10⁵ (cell, element) pairs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "common/vec2.h"

namespace nmm::solve {

class ElementGrid {
 public:
  /// Sorts the elements of `mesh` into cells of side mesh.mesh_size; keeps a reference to it.
  explicit ElementGrid(const Mesh& mesh);
  /// The element whose loop as cut holds p, or -1.
  std::int32_t at(const Vec2& p) const;
  /// The grid was built for this mesh (the same object, with the same element count).
  bool of(const Mesh& mesh) const { return &mesh == &mesh_ && mesh.element_count() == elements_; }

 private:
  std::int64_t cell_x(double x) const;
  std::int64_t cell_y(double y) const;
  const Mesh& mesh_;
  std::size_t elements_ = 0;
  double h_ = 0, x0_ = 0, y0_ = 0;   // m: cell side, the grid's lower left corner
  std::int64_t nx_ = 0, ny_ = 0;     // cells along x and y
  std::vector<std::size_t> offset_;  // [cells + 1] CSR offsets into element_
  std::vector<std::int32_t> element_;
};

}  // namespace nmm::solve
