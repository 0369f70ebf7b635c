// The strain energy a crack releases: see crack_release.h for the derivation.
#include "solver/fracture/crack_release.h"

#include <algorithm>

#include "solver/discretisation/element_integration.h"
#include "solver/discretisation/polynomial.h"

namespace nmm::solve {

Eigen::VectorXd cut_release_force(const Model& model, const Configuration& config, const RunState& s,
                                  const std::vector<std::uint8_t>& removed,
                                  const std::vector<std::int32_t>& cover_parent, const Eigen::VectorXd& B) {
  const Mesh& mesh = model.mesh();
  const CoverSpace& space = config.space();
  const std::size_t covers = mesh.cover_count();
  const int P = space.terms(), dpc = space.dofs_per_cover();
  // kg/m, each cover's mass moments M_k[j][l] = Σ_e ρ_e ∫_e w_k p_j p_l dA (the header's
  // equation; p_j about the cover's basis node, scaled by h, as its cover function). Order 0:
  // its mass Σ_e ρ_e ∫_e w_k dA, the consistent mass's row sum, by the linear weights' moments.
  std::vector<Eigen::MatrixXd> moments(covers, Eigen::MatrixXd::Zero(P, P));
  const double h = space.scale();
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (e < removed.size() && removed[e]) continue;
    const ElementFrame& f = config.frame(e);
    if (!(f.w.twice_area > 0)) continue;
    const std::size_t b = static_cast<std::size_t>(mesh.element_loop_offset[e]);
    const std::size_t n = static_cast<std::size_t>(mesh.element_loop_offset[e + 1]) - b;
    const double rho = model.density(e);
    if (P == 1) {
      const PolygonMoments m = polygon_moments(s.loop_xy.data() + 2 * b, n, f.ox, f.oy);
      for (int k = 0; k < 3; ++k)
        moments[static_cast<std::size_t>(mesh.element_covers[3 * e + static_cast<std::size_t>(k)])](0, 0) +=
            rho * integral_w(f.w, m, k);
      continue;
    }
    // ∫ φ_kj · p_l dA with φ_kj = w_k p_j the element's shape functions (degree n + 1) and p_l
    // about the same node, in the element's scaled frame: degree 2n + 1, integrated exactly.
    const ElementBasis& basis = config.basis(e);
    const MonomialMoments m = monomial_moments(s.loop_xy.data() + 2 * b, n, f.ox, f.oy, h, 2 * space.order() + 1);
    for (int k = 0; k < 3; ++k) {
      const std::size_t c = static_cast<std::size_t>(mesh.element_covers[3 * e + static_cast<std::size_t>(k)]);
      const std::size_t node = static_cast<std::size_t>(space.basis_cover(c));
      const double sx = (s.cover_xy[2 * node] - f.ox) / h, sy = (s.cover_xy[2 * node + 1] - f.oy) / h;
      for (int l = 0; l < P; ++l) {
        const Poly pl = shifted_monomial(kMonomials.p[static_cast<std::size_t>(l)],
                                         kMonomials.q[static_cast<std::size_t>(l)], sx, sy);
        for (int j = 0; j < P; ++j) moments[c](j, l) += rho * integral(basis.phi[static_cast<std::size_t>(k * P + j)], pl, m);
      }
    }
  }
  // Per unknown pair (a cover and those tied to it): its parent cover, moments, and B summed per
  // parent.
  const std::size_t pairs = static_cast<std::size_t>(space.unknowns() / dpc);
  std::vector<std::int32_t> parent(pairs, -1);
  std::vector<Eigen::MatrixXd> pair_moments(pairs, Eigen::MatrixXd::Zero(P, P));
  for (std::size_t c = 0; c < covers && c < cover_parent.size(); ++c) {
    const auto u = static_cast<std::size_t>(space.first_unknown(c) / dpc);
    if (static_cast<std::size_t>(space.cover_of_unknown(static_cast<int>(u) * dpc)) == c) parent[u] = cover_parent[c];
    pair_moments[u] += moments[c];
  }
  const std::size_t parents = static_cast<std::size_t>(*std::max_element(parent.begin(), parent.end()) + 1);
  std::vector<Eigen::MatrixXd> parent_moments(parents, Eigen::MatrixXd::Zero(P, P));
  std::vector<int> parent_pieces(parents, 0);
  // N/m, B of the parent's unknowns as P × 2 (term j, direction s: unknown 2j + s).
  using Terms = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
  std::vector<Terms> parent_force(parents, Terms::Zero(P, 2));
  const auto terms = [&](const Eigen::VectorXd& v, std::size_t u) {
    return Eigen::Map<const Terms>(v.data() + static_cast<Eigen::Index>(u) * dpc, P, 2);
  };
  for (std::size_t u = 0; u < pairs; ++u) {
    if (parent[u] < 0) continue;
    const auto p = static_cast<std::size_t>(parent[u]);
    parent_moments[p] += pair_moments[u];
    ++parent_pieces[p];
    parent_force[p] += terms(B, u);
  }
  // The parent's body force per unit mass, g = M_P⁻¹ B_P (P × 2: its coefficients on p_l); n = 0:
  // the piece's share m_i / m_P of B_P, as the earlier rule computed it (bit for bit).
  std::vector<Terms> g(parents);
  for (std::size_t p = 0; p < parents; ++p)
    if (parent_pieces[p] >= 2 && parent_moments[p](0, 0) > 0 && P > 1)
      g[p] = parent_moments[p].ldlt().solve(parent_force[p]);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(B.size());
  for (std::size_t u = 0; u < pairs; ++u) {
    if (parent[u] < 0) continue;
    const auto p = static_cast<std::size_t>(parent[u]);
    if (parent_pieces[p] < 2 || !(parent_moments[p](0, 0) > 0)) continue;  // not split: nothing opened
    Eigen::Map<Terms> ru(r.data() + static_cast<Eigen::Index>(u) * dpc, P, 2);
    if (P == 1)
      ru = terms(B, u) - (pair_moments[u](0, 0) / parent_moments[p](0, 0)) * parent_force[p];
    else
      ru = terms(B, u) - pair_moments[u] * g[p];
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
