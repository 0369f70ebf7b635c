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
// as Δt → 0. Handing each block's net residual force and moment to the next step makes those
// errors telescope: over a run a block's momentum is off by one step's residual at most, whatever
// the number of steps. With x_g the node of unknown group g's cover (its constant coefficients
// are the displacement there), m_g its lumped mass, x_b = Σ m_g·x_g / m_b the block's centre of
// mass and I_b = Σ m_g·|x_g − x_b|²:
//     R_b = k · Σ_g r_g,             M_b = k · Σ_g (x_g − x_b) × r_g      (r_g: the constant
//                                                                        coefficients' (x, y) row)
//     f_g = m_g · (R_b / m_b + (M_b / I_b) · ẑ × (x_g − x_b))
// spread by mass like a body force and an angular acceleration: Σ f_g = R_b and
// Σ (x_g − x_b) × f_g = M_b. Only the block's rigid motion: the rest of r pulls covers against
// each other, and re-applying it as a load on a sliver cover of tiny mass (joints through mesh
// nodes) excites the stiff, light modes the residual came from (measured: a cover moved 0.9 m in
// one step). The time stepper applies it only after a step that took a Newton direction: a step
// already in balance at its start leaves a block at rest at rest instead of pushing it with its
// tolerance-level imbalance. At cover orders n ≥ 1 the linear coefficients' share of the moment
// is left out (a rotation's constant terms carry all but O(h/size) of it).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/mesh.h"
#include "solver/discretisation/cover_space.h"

namespace nmm::solve {

class BlockMomentum {
 public:
  BlockMomentum() = default;
  /// group_mass: [unknown group] kg/m, the lumped mass of each independent cover (unknown group
  /// g holds the unknowns g·dpc … g·dpc + dpc − 1; equilibrium_indicator.h).
  BlockMomentum(const Mesh& mesh, const CoverSpace& space, const std::vector<double>& group_mass);

  /// out[3b … 3b+2] = k × block b's net force (N/m, x and y) and moment about its centre of mass
  /// (N·m/m) in r (N/m, in unknown order); cover_xy: [2·pc] m, the covers' current nodes.
  void net_forces(const Eigen::VectorXd& r, double k, const std::vector<double>& cover_xy,
                  std::vector<double>& out) const;
  /// rhs (N/m) += each block's force and moment f ([3·block], as net_forces gives them), spread
  /// over the block's covers by lumped mass.
  void add_forces(const std::vector<double>& f, const std::vector<double>& cover_xy, Eigen::VectorXd& rhs) const;

 private:
  /// Each block's centre of mass (m) and polar moment I_b (kg·m) at cover_xy.
  void centres(const std::vector<double>& cover_xy, std::vector<double>& xc, std::vector<double>& inertia) const;

  std::size_t dpc_ = 2;                    // unknowns per cover
  std::size_t blocks_ = 0;
  std::vector<std::int32_t> group_block_;  // [unknown group] block of its covers (−1: none)
  std::vector<std::int32_t> group_cover_;  // [unknown group] a cover of it (its node: x_g)
  std::vector<double> group_mass_;         // [unknown group] kg/m
  std::vector<double> block_mass_;         // [block] kg/m
};

}  // namespace nmm::solve
