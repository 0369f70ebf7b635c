// The strain energy a crack releases: see crack_release.h for the derivation.
#include "solver/fracture/crack_release.h"

#include <algorithm>

#include "solver/discretisation/element_integration.h"

namespace nmm::solve {

Eigen::VectorXd cut_release_force(const Model& model, const Configuration& config, const RunState& s,
                                  const std::vector<std::uint8_t>& removed,
                                  const std::vector<std::int32_t>& cover_parent, const Eigen::VectorXd& B) {
  const Mesh& mesh = model.mesh();
  const CoverSpace& space = config.space();
  const std::size_t covers = mesh.cover_count();
  // kg/m, each cover's mass: Σ_e ρ_e ∫_e w_k dA (the consistent mass's row sum).
  std::vector<double> mass(covers, 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (e < removed.size() && removed[e]) continue;
    const ElementFrame& f = config.frame(e);
    if (!(f.w.twice_area > 0)) continue;
    const std::size_t b = static_cast<std::size_t>(mesh.element_loop_offset[e]);
    const std::size_t n = static_cast<std::size_t>(mesh.element_loop_offset[e + 1]) - b;
    const PolygonMoments m = polygon_moments(s.loop_xy.data() + 2 * b, n, f.ox, f.oy);
    for (int k = 0; k < 3; ++k)
      mass[static_cast<std::size_t>(mesh.element_covers[3 * e + static_cast<std::size_t>(k)])] +=
          model.density(e) * integral_w(f.w, m, k);
  }
  // Per unknown pair (a cover and those tied to it): its parent cover, mass, and B summed per
  // parent.
  const int dpc = space.dofs_per_cover();
  const std::size_t pairs = static_cast<std::size_t>(space.unknowns() / dpc);
  std::vector<std::int32_t> parent(pairs, -1);
  std::vector<double> pair_mass(pairs, 0.0);
  for (std::size_t c = 0; c < covers && c < cover_parent.size(); ++c) {
    const auto u = static_cast<std::size_t>(space.first_unknown(c) / dpc);
    if (static_cast<std::size_t>(space.cover_of_unknown(static_cast<int>(u) * dpc)) == c) parent[u] = cover_parent[c];
    pair_mass[u] += mass[c];
  }
  std::vector<double> parent_mass(static_cast<std::size_t>(*std::max_element(parent.begin(), parent.end()) + 1), 0.0);
  std::vector<int> parent_pieces(parent_mass.size(), 0);
  Eigen::MatrixXd parent_force = Eigen::MatrixXd::Zero(dpc, static_cast<Eigen::Index>(parent_mass.size()));
  for (std::size_t u = 0; u < pairs; ++u) {
    if (parent[u] < 0) continue;
    const auto p = static_cast<std::size_t>(parent[u]);
    parent_mass[p] += pair_mass[u];
    ++parent_pieces[p];
    parent_force.col(static_cast<Eigen::Index>(p)) += B.segment(static_cast<Eigen::Index>(u) * dpc, dpc);
  }
  Eigen::VectorXd r = Eigen::VectorXd::Zero(B.size());
  for (std::size_t u = 0; u < pairs; ++u) {
    if (parent[u] < 0) continue;
    const auto p = static_cast<std::size_t>(parent[u]);
    if (parent_pieces[p] < 2 || !(parent_mass[p] > 0)) continue;  // not split: nothing opened
    r.segment(static_cast<Eigen::Index>(u) * dpc, dpc) =
        B.segment(static_cast<Eigen::Index>(u) * dpc, dpc) -
        (pair_mass[u] / parent_mass[p]) * parent_force.col(static_cast<Eigen::Index>(p));
  }
  return r;
}

double crack_release_fluid(const Mesh& mesh, const RunState& s, const RunState& start, std::size_t first_new_joint,
                           const std::vector<double>& pressure, const std::vector<double>& start_pressure) {
  // −½ Σ ∫ (p − p0) n·Δu ds on each new face edge v → n, p and Δu linear along it: the exact rule
  // of the header, n·L from the start positions as the flow effect's face load takes them.
  double w = 0;
  const std::size_t nv = 2 * mesh.loop_vertex_count();
  if (pressure.size() < nv || start_pressure.size() < nv) return w;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (element_removed(mesh, s, static_cast<std::int32_t>(e))) continue;
    const std::int32_t b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
    for (std::int32_t v = b; v < end; ++v) {
      if (mesh.loop_edge_joint[v] < static_cast<std::int32_t>(first_new_joint)) continue;
      const auto i = static_cast<std::size_t>(v);
      const double pa = pressure[2 * i] - start_pressure[2 * i], pb = pressure[2 * i + 1] - start_pressure[2 * i + 1];
      if (pa == 0 && pb == 0) continue;
      const std::int32_t n = v + 1 < end ? v + 1 : b;
      const double lnx = start.loop_xy[2 * n + 1] - start.loop_xy[2 * v + 1];
      const double lny = -(start.loop_xy[2 * n] - start.loop_xy[2 * v]);
      // m²: Δu·n·L at the edge's two ends
      const double una =
          (s.loop_u[2 * v] - start.loop_u[2 * v]) * lnx + (s.loop_u[2 * v + 1] - start.loop_u[2 * v + 1]) * lny;
      const double unb =
          (s.loop_u[2 * n] - start.loop_u[2 * n]) * lnx + (s.loop_u[2 * n + 1] - start.loop_u[2 * n + 1]) * lny;
      w -= 0.5 * ((2 * pa + pb) * una + (pa + 2 * pb) * unb) / 6;  // J/m: −½ ∫ (p − p0) n·Δu ds
    }
  }
  return w;
}

}  // namespace nmm::solve
