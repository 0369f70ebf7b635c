// The configuration of a step: see configuration.h.
#include "solver/discretisation/configuration.h"

namespace nmm::solve {

Configuration::Configuration(const Mesh& mesh, const CoverSpace* space)
    : mesh_(&mesh), space_(space), frame_(mesh.element_count()) {}

namespace {
// Element e's frame on the cover nodes cover_xy ([2·c] m): origin its first cover's node.
ElementFrame frame_on(const Mesh& mesh, std::size_t e, const std::vector<double>& cover_xy) {
  const std::int32_t* ec = &mesh.element_covers[3 * e];
  ElementFrame f;
  const int c0 = ec[0], c1 = ec[1], c2 = ec[2];
  f.ox = cover_xy[2 * c0];
  f.oy = cover_xy[2 * c0 + 1];
  const double p[6] = {0, 0, cover_xy[2 * c1] - f.ox, cover_xy[2 * c1 + 1] - f.oy,
                       cover_xy[2 * c2] - f.ox, cover_xy[2 * c2 + 1] - f.oy};
  f.w = triangle_weights(p);
  return f;
}
}  // namespace

std::int64_t Configuration::place(const std::vector<double>& cover_xy) {
  cover_xy_ = cover_xy;
  std::int64_t folded = -1;
  for (std::size_t e = 0; e < frame_.size(); ++e) {
    frame_[e] = frame_on(*mesh_, e, cover_xy);
    if (!(frame_[e].w.twice_area > 0) && folded < 0) folded = static_cast<std::int64_t>(e);
  }
  return folded;
}

std::int64_t Configuration::folded_by(const Eigen::VectorXd& d) const {
  std::vector<double> moved = cover_xy_;
  move_cover_nodes(d, moved);
  for (std::size_t e = 0; e < frame_.size(); ++e)
    if (!(frame_on(*mesh_, e, moved).w.twice_area > 0)) return static_cast<std::int64_t>(e);
  return -1;
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

void Configuration::move_points(const Eigen::VectorXd& d, std::vector<TrackedPoint>& points) const {
  const int nf = space_->element_dofs() / 2;
  std::vector<double> phi(static_cast<std::size_t>(nf));
  for (TrackedPoint& p : points) {
    const int* g = space_->element_unknowns(p.element);
    shape_values(static_cast<std::size_t>(p.element), p.x, p.y, phi.data());
    double ux = 0, uy = 0;
    for (int a = 0; a < nf; ++a) {
      ux += phi[a] * d[g[2 * a]];
      uy += phi[a] * d[g[2 * a + 1]];
    }
    p.x += ux;
    p.y += uy;
  }
}

void Configuration::move_cover_nodes(const Eigen::VectorXd& d, std::vector<double>& cover_xy) const {
  const int P = space_->terms();
  const std::size_t nc = mesh_->cover_count();
  std::vector<double> node_d(2 * nc, 0.0);
  for (std::size_t c = 0; c < nc; ++c) {
    const int first = space_->first_unknown(c);
    const int mc = space_->basis_cover(c);
    if (mc == static_cast<int>(c) || P == 1) {
      node_d[2 * c] = d[first];
      node_d[2 * c + 1] = d[first + 1];
      continue;
    }
    const double xi = (cover_xy[2 * c] - cover_xy[2 * mc]) / space_->scale();
    const double eta = (cover_xy[2 * c + 1] - cover_xy[2 * mc + 1]) / space_->scale();
    for (int j = 0; j < P; ++j) {
      Poly pj;
      pj.degree = kMonomials.p[j] + kMonomials.q[j];
      pj.c[j] = 1;
      const double pv = pj(xi, eta);
      node_d[2 * c] += pv * d[first + 2 * j];
      node_d[2 * c + 1] += pv * d[first + 2 * j + 1];
    }
  }
  for (std::size_t i = 0; i < cover_xy.size(); ++i) cover_xy[i] += node_d[i];
}

}  // namespace nmm::solve
