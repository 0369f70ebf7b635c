#pragma once
// The momentum a dynamic step's out-of-balance force would take from each block, handed to the
// next step as a load (docs/contact.md "What the tolerance allows in a motion").
//
// A step with contacts is accepted with an out-of-balance force r on each unknown, |r_i| ≤ F_tol
// (contact_solve.cpp "Tolerance"). Shi's velocity update integrates that step as if the loads were
// b − r, so with the velocity factor k (solver.dynamic_factor; 0 in a static run)
//     M·v_{n+1} = k·(M·v_n + Δt·(F + f_contact − f_internal) − Δt·r_n):
// every step takes k·r_n·Δt of momentum. Residuals of one sign (a sliding block: each step's last
// Newton direction approaches balance from the same side) add up to a drift that does not vanish
// as Δt → 0. Handing each block's net residual force to the next step,
//     R_b = k · Σ_{unknown groups g of block b} (r_{g,x}, r_{g,y})      (constant coefficients:
//                                                                          a rigid translation)
//     f_g = (m_g / m_b) · R_b         (spread by lumped mass m_g, as a body force is)
// makes those errors telescope: over a run a block's momentum is off by one step's residual at
// most, whatever the number of steps. Only the block's translation: the rest of r pulls covers
// against each other, and re-applying it as a load on a sliver cover of tiny mass (joints through
// mesh nodes) excites the stiff, light modes the residual came from (measured: a cover moved
// 0.9 m in one step). The time stepper applies it only after a step that took a Newton direction:
// a step already in balance at its start leaves a block at rest at rest instead of pushing it
// with its tolerance-level imbalance.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/mesh.h"
#include "solver/cover_space.h"

namespace nmm::solve {

class BlockMomentum {
 public:
  BlockMomentum() = default;
  /// group_mass: [unknown group] kg/m, the lumped mass of each independent cover (unknown group
  /// g holds the unknowns g·dpc … g·dpc + dpc − 1; equilibrium_indicator.h).
  BlockMomentum(const Mesh& mesh, const CoverSpace& space, const std::vector<double>& group_mass);

  /// out[2b], out[2b+1] (N/m) = k × block b's net force in r (N/m, in unknown order).
  void net_forces(const Eigen::VectorXd& r, double k, std::vector<double>& out) const;
  /// rhs (N/m) += each block's force f ([2·block], as net_forces gives it), spread over the
  /// block's covers by lumped mass.
  void add_forces(const std::vector<double>& f, Eigen::VectorXd& rhs) const;

 private:
  std::size_t dpc_ = 2;                    // unknowns per cover
  std::size_t blocks_ = 0;
  std::vector<std::int32_t> group_block_;  // [unknown group] block of its covers (−1: none)
  std::vector<double> group_share_;        // [unknown group] –, its mass over its block's
};

}  // namespace nmm::solve
