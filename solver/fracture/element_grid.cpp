// Elements by cell of a uniform grid: see element_grid.h.
#include "solver/fracture/element_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "solver/fracture/element_geometry.h"

namespace nmm::solve {

ElementGrid::ElementGrid(const Mesh& mesh) : mesh_(mesh), elements_(mesh.element_count()), h_(mesh.mesh_size) {
  x0_ = y0_ = std::numeric_limits<double>::infinity();
  double x1 = -x0_, y1 = -y0_;
  for (std::size_t v = 0; v < mesh.loop_vertex_count(); ++v) {
    x0_ = std::min(x0_, mesh.loop_xy[2 * v]);
    y0_ = std::min(y0_, mesh.loop_xy[2 * v + 1]);
    x1 = std::max(x1, mesh.loop_xy[2 * v]);
    y1 = std::max(y1, mesh.loop_xy[2 * v + 1]);
  }
  nx_ = static_cast<std::int64_t>((x1 - x0_) / h_) + 1;
  ny_ = static_cast<std::int64_t>((y1 - y0_) / h_) + 1;
  std::vector<std::pair<std::int64_t, std::int32_t>> cells;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    double bx0 = std::numeric_limits<double>::infinity(), by0 = bx0, bx1 = -bx0, by1 = -bx0;
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v) {
      bx0 = std::min(bx0, mesh.loop_xy[2 * v]);
      by0 = std::min(by0, mesh.loop_xy[2 * v + 1]);
      bx1 = std::max(bx1, mesh.loop_xy[2 * v]);
      by1 = std::max(by1, mesh.loop_xy[2 * v + 1]);
    }
    for (std::int64_t j = cell_y(by0); j <= cell_y(by1); ++j)
      for (std::int64_t i = cell_x(bx0); i <= cell_x(bx1); ++i)
        cells.emplace_back(j * nx_ + i, static_cast<std::int32_t>(e));
  }
  std::sort(cells.begin(), cells.end());
  offset_.assign(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
  for (const auto& c : cells) ++offset_[static_cast<std::size_t>(c.first) + 1];
  for (std::size_t k = 1; k < offset_.size(); ++k) offset_[k] += offset_[k - 1];
  element_.reserve(cells.size());
  for (const auto& c : cells) element_.push_back(c.second);
}

std::int32_t ElementGrid::at(const Vec2& p) const {
  const std::int64_t i = cell_x(p.x), j = cell_y(p.y);
  if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return -1;
  const std::size_t c = static_cast<std::size_t>(j * nx_ + i);
  const std::vector<std::int32_t> candidates(element_.begin() + static_cast<std::ptrdiff_t>(offset_[c]),
                                             element_.begin() + static_cast<std::ptrdiff_t>(offset_[c + 1]));
  return element_holding(mesh_, candidates, p);
}

std::int64_t ElementGrid::cell_x(double x) const {
  return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((x - x0_) / h_)), -1, nx_);
}
std::int64_t ElementGrid::cell_y(double y) const {
  return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((y - y0_) / h_)), -1, ny_);
}

}  // namespace nmm::solve
