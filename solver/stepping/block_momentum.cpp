// Each block's net out-of-balance force and moment, handed to the next step (block_momentum.h).
#include "solver/stepping/block_momentum.h"

namespace nmm::solve {

BlockMomentum::BlockMomentum(const Mesh& mesh, const CoverSpace& space, const std::vector<double>& group_mass)
    : dpc_(static_cast<std::size_t>(space.dofs_per_cover())),
      blocks_(mesh.block_count()),
      group_block_(group_mass.size(), -1),
      group_cover_(group_mass.size(), -1),
      group_mass_(group_mass),
      block_mass_(mesh.block_count(), 0.0) {
  // A group's block is that of the elements its covers lie in. Tied sliver covers (cover_unknowns.h)
  // lie beside their master, so a group does not straddle a joint in practice; should it, the
  // last element's block takes the group's force, which moves the force by a sliver's width.
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::int32_t c = mesh.element_covers[3 * e + k];
      const std::size_t g = static_cast<std::size_t>(space.first_unknown(static_cast<std::size_t>(c))) / dpc_;
      group_block_[g] = mesh.element_block[e];
      group_cover_[g] = c;
    }
  for (std::size_t g = 0; g < group_mass_.size(); ++g)
    if (group_block_[g] >= 0) block_mass_[static_cast<std::size_t>(group_block_[g])] += group_mass_[g];
}

void BlockMomentum::centres(const std::vector<double>& cover_xy, std::vector<double>& xc,
                            std::vector<double>& inertia) const {
  xc.assign(2 * blocks_, 0.0);
  inertia.assign(blocks_, 0.0);
  for (std::size_t g = 0; g < group_block_.size(); ++g) {
    if (group_block_[g] < 0) continue;
    const auto b = static_cast<std::size_t>(group_block_[g]);
    const auto c = static_cast<std::size_t>(group_cover_[g]);
    xc[2 * b] += group_mass_[g] * cover_xy[2 * c];
    xc[2 * b + 1] += group_mass_[g] * cover_xy[2 * c + 1];
  }
  for (std::size_t b = 0; b < blocks_; ++b)
    if (block_mass_[b] > 0) {
      xc[2 * b] /= block_mass_[b];
      xc[2 * b + 1] /= block_mass_[b];
    }
  for (std::size_t g = 0; g < group_block_.size(); ++g) {
    if (group_block_[g] < 0) continue;
    const auto b = static_cast<std::size_t>(group_block_[g]);
    const auto c = static_cast<std::size_t>(group_cover_[g]);
    const double dx = cover_xy[2 * c] - xc[2 * b], dy = cover_xy[2 * c + 1] - xc[2 * b + 1];
    inertia[b] += group_mass_[g] * (dx * dx + dy * dy);
  }
}

void BlockMomentum::net_forces(const Eigen::VectorXd& r, double k, const std::vector<double>& cover_xy,
                               std::vector<double>& out) const {
  std::vector<double> xc, inertia;
  centres(cover_xy, xc, inertia);
  out.assign(3 * blocks_, 0.0);
  for (std::size_t g = 0; g < group_block_.size(); ++g) {
    if (group_block_[g] < 0) continue;
    const auto b = static_cast<std::size_t>(group_block_[g]);
    const auto c = static_cast<std::size_t>(group_cover_[g]);
    const auto i = static_cast<Eigen::Index>(g * dpc_);  // the constant coefficients (u, v)
    const double dx = cover_xy[2 * c] - xc[2 * b], dy = cover_xy[2 * c + 1] - xc[2 * b + 1];
    out[3 * b] += k * r[i];
    out[3 * b + 1] += k * r[i + 1];
    out[3 * b + 2] += k * (dx * r[i + 1] - dy * r[i]);
  }
}

void BlockMomentum::add_forces(const std::vector<double>& f, const std::vector<double>& cover_xy,
                               Eigen::VectorXd& rhs) const {
  std::vector<double> xc, inertia;
  centres(cover_xy, xc, inertia);
  for (std::size_t g = 0; g < group_block_.size(); ++g) {
    if (group_block_[g] < 0) continue;
    const auto b = static_cast<std::size_t>(group_block_[g]);
    if (!(block_mass_[b] > 0)) continue;
    const auto c = static_cast<std::size_t>(group_cover_[g]);
    const auto i = static_cast<Eigen::Index>(g * dpc_);
    const double dx = cover_xy[2 * c] - xc[2 * b], dy = cover_xy[2 * c + 1] - xc[2 * b + 1];
    const double alpha = inertia[b] > 0 ? f[3 * b + 2] / inertia[b] : 0.0;  // 1/s² · m/m: M_b / I_b
    rhs[i] += group_mass_[g] * (f[3 * b] / block_mass_[b] - alpha * dy);
    rhs[i + 1] += group_mass_[g] * (f[3 * b + 1] / block_mass_[b] + alpha * dx);
  }
}

}  // namespace nmm::solve
