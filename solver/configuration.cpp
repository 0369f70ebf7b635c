// The configuration of a step: see configuration.h.
#include "configuration.h"

namespace nmm::solve {

Configuration::Configuration(const Mesh& mesh, const CoverSpace* space)
    : mesh_(&mesh), space_(space), frame_(mesh.element_count()) {}

std::int64_t Configuration::place(const std::vector<double>& cover_xy) {
  cover_xy_ = cover_xy;
  std::int64_t folded = -1;
  for (std::size_t e = 0; e < frame_.size(); ++e) {
    const std::int32_t* ec = &mesh_->element_covers[3 * e];
    ElementFrame& f = frame_[e];
    const int c0 = ec[0], c1 = ec[1], c2 = ec[2];
    f.ox = cover_xy[2 * c0];
    f.oy = cover_xy[2 * c0 + 1];
    const double p[6] = {0, 0, cover_xy[2 * c1] - f.ox, cover_xy[2 * c1 + 1] - f.oy,
                         cover_xy[2 * c2] - f.ox, cover_xy[2 * c2 + 1] - f.oy};
    f.w = triangle_weights(p);
    if (!(f.w.twice_area > 0) && folded < 0) folded = static_cast<std::int64_t>(e);
  }
  return folded;
}

const ElementBasis& Configuration::basis(std::size_t e) const {
  const std::int32_t* ec = &mesh_->element_covers[3 * e];
  double centre[6];
  for (int k = 0; k < 3; ++k) {
    const int m = space_->basis_cover(ec[k]);
    centre[2 * k] = cover_xy_[2 * m];
    centre[2 * k + 1] = cover_xy_[2 * m + 1];
  }
  space_->element_basis(frame_[e].ox, frame_[e].oy, frame_[e].w, centre, scratch_);
  return scratch_;
}

void Configuration::shape_values(std::size_t e, double x, double y, double* out) const {
  if (space_->order() == 0) {  // the weights themselves, with the first-order code's round-off
    const ElementFrame& f = frame_[e];
    for (int k = 0; k < 3; ++k) out[k] = f.w.at(k, x - f.ox, y - f.oy);
    return;
  }
  basis(e).values(x, y, out);
}

}  // namespace nmm::solve
