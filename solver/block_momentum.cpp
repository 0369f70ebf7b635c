// Each block's net out-of-balance force, handed to the next step (block_momentum.h).
#include "solver/block_momentum.h"

namespace nmm::solve {

BlockMomentum::BlockMomentum(const Mesh& mesh, const CoverSpace& space, const std::vector<double>& group_mass)
    : dpc_(static_cast<std::size_t>(space.dofs_per_cover())),
      blocks_(mesh.block_count()),
      group_block_(group_mass.size(), -1),
      group_share_(group_mass.size(), 0.0) {
  // A group's block is that of the elements its covers lie in. Tied sliver covers (cover_unknowns.h)
  // lie beside their master, so a group does not straddle a joint in practice; should it, the
  // last element's block takes the group's force, which moves the force by a sliver's width.
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) {
      const auto c = static_cast<std::size_t>(mesh.element_covers[3 * e + static_cast<std::size_t>(k)]);
      group_block_[static_cast<std::size_t>(space.first_unknown(c)) / dpc_] = mesh.element_block[e];
    }
  std::vector<double> block_mass(blocks_, 0.0);
  for (std::size_t g = 0; g < group_mass.size(); ++g)
    if (group_block_[g] >= 0) block_mass[static_cast<std::size_t>(group_block_[g])] += group_mass[g];
  for (std::size_t g = 0; g < group_mass.size(); ++g) {
    const std::int32_t b = group_block_[g];
    if (b >= 0 && block_mass[static_cast<std::size_t>(b)] > 0)
      group_share_[g] = group_mass[g] / block_mass[static_cast<std::size_t>(b)];
  }
}

void BlockMomentum::net_forces(const Eigen::VectorXd& r, double k, std::vector<double>& out) const {
  out.assign(2 * blocks_, 0.0);
  for (std::size_t g = 0; g < group_block_.size(); ++g) {
    const std::int32_t b = group_block_[g];
    if (b < 0) continue;
    const auto i = static_cast<Eigen::Index>(g * dpc_);  // the constant coefficients (u, v)
    out[2 * static_cast<std::size_t>(b)] += k * r[i];
    out[2 * static_cast<std::size_t>(b) + 1] += k * r[i + 1];
  }
}

void BlockMomentum::add_forces(const std::vector<double>& f, Eigen::VectorXd& rhs) const {
  for (std::size_t g = 0; g < group_block_.size(); ++g) {
    const std::int32_t b = group_block_[g];
    if (b < 0 || group_share_[g] == 0) continue;
    const auto i = static_cast<Eigen::Index>(g * dpc_);
    rhs[i] += group_share_[g] * f[2 * static_cast<std::size_t>(b)];
    rhs[i + 1] += group_share_[g] * f[2 * static_cast<std::size_t>(b) + 1];
  }
}

}  // namespace nmm::solve
