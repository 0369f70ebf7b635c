// Sliver covers share the unknowns of a neighbour (joints passing next to mesh nodes).
//
// A joint passing a distance t inside the edge of a mathematical cover's star leaves, on the far
// side, a physical cover whose support is a strip of width t along the star's edge, where its
// weight w_s never exceeds about t/h. Its stiffness scales as E·t/h, its mass as ρ·t³/h, against
// contact springs of kn ~ 20·E: at t = 1e-9·h its rows are lost in rounding (CHOLMOD found the
// matrix "not positive definite" in a dynamic run, and near-null covers were flung 0.43 m in a
// step), yet it moves no point of the rock by more than w_s·d.
//
// Such a cover s (max over its support of w_s < min_weight) is tied to the significant cover m of
// its block that it overlaps most, by mass: m maximises Σ_e ∫_e w_s·w_m dA over the elements the
// two share. The tie d_s = d_m is a master–slave constraint, so the field stays conforming and a
// rigid translation stays exact (Σ w = 1); what is lost is w_s·(d_s − d_m), below min_weight
// times the displacement difference across one element, in a strip of width ≤ min_weight·h.
// An element keeps a significant cover by weight (its three weights sum to 1 > 3·min_weight);
// covers of next to no support are tied too (below min_weight·h² of area, see below). The slave keeps its own weight function and node (which moves by d_m).
#include "solver/discretisation/cover_unknowns.h"

#include <algorithm>
#include <map>

#include "solver/discretisation/element_integration.h"

namespace nmm::solve {

CoverUnknowns assign_cover_unknowns(const Mesh& mesh, double min_weight, int dofs_per_cover, double min_support,
                                    std::int32_t first_crack_joint) {
  const std::size_t nc = mesh.cover_count(), ne = mesh.element_count();
  CoverUnknowns u;
  u.dofs_per_cover = dofs_per_cover;
  u.max_weight.assign(nc, 0.0);
  u.master.resize(nc);
  for (std::size_t c = 0; c < nc; ++c) u.master[c] = static_cast<std::int32_t>(c);

  // The weights of each element's triangle, from the covers' nodes (origin: the first one).
  auto weights = [&](std::size_t e, double& ox, double& oy) {
    const std::int32_t* c = &mesh.element_covers[3 * e];
    ox = mesh.node_xy[2 * mesh.cover_node[c[0]]];
    oy = mesh.node_xy[2 * mesh.cover_node[c[0]] + 1];
    double p[6];
    for (int k = 0; k < 3; ++k) {
      p[2 * k] = mesh.node_xy[2 * mesh.cover_node[c[k]]] - ox;
      p[2 * k + 1] = mesh.node_xy[2 * mesh.cover_node[c[k]] + 1] - oy;
    }
    return triangle_weights(p);
  };
  // Linear weights peak at a vertex of the element's loop.
  for (std::size_t e = 0; e < ne; ++e) {
    double ox, oy;
    const TriangleWeights w = weights(e, ox, oy);
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v)
      for (int k = 0; k < 3; ++k) {
        double& m = u.max_weight[mesh.element_covers[3 * e + k]];
        m = std::max(m, w.at(k, mesh.loop_xy[2 * v] - ox, mesh.loop_xy[2 * v + 1] - oy));
      }
  }
  // In a run that can crack, a cover with next to no support is as void as a sliver: a corner of
  // a triangle that cracks cut off at a node, a ten-thousandth to a hundredth of an element in
  // area, whose own cover carries stiffness and mass of that size between crack faces whose
  // springs are a hundred times stiffer (a uniaxial specimen past its peak: such a cover moved
  // 6 mm, then 3 cm, as its step was cut shorter; fracture.h kLeastCoverSupport). Below min_support·h² of support it shares a neighbour's unknowns too.
  // A cover of a block that small altogether has no significant neighbour and keeps its own: that
  // block is debris (fracture.h). (Scenes that cannot crack keep every such cover of their joints'
  // corners, as they always did: min_support 0.)
  // Only covers a crack bounds: the scene's own small covers (a body's boundary or a joint
  // passing near a node, a support or traction on them) keep their unknowns as they always did.
  std::vector<double> support(nc, 0.0);
  std::vector<std::uint8_t> cracked(nc, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    const double a = element_area(mesh, e);
    bool crack = false;
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1] && first_crack_joint >= 0; ++v)
      crack = crack || ((mesh.loop_edge_origin[v] & kEdgeJoint) && mesh.loop_edge_joint[v] >= first_crack_joint);
    for (int k = 0; k < 3; ++k) {
      const auto c = static_cast<std::size_t>(mesh.element_covers[3 * e + k]);
      support[c] += a;
      cracked[c] = cracked[c] || crack;
    }
  }
  const double least = min_support * mesh.mesh_size * mesh.mesh_size;  // m²
  auto sliver = [&](std::int32_t c) {
    return u.max_weight[c] < min_weight || (cracked[c] && support[c] < least);
  };

  // Overlap of each sliver with the significant covers of its elements.
  std::map<std::pair<std::int32_t, std::int32_t>, double> overlap;  // (sliver, cover) → m²
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t* c = &mesh.element_covers[3 * e];
    if (!sliver(c[0]) && !sliver(c[1]) && !sliver(c[2])) continue;
    double ox, oy;
    const TriangleWeights w = weights(e, ox, oy);
    const std::size_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
    const PolygonMoments pm = polygon_moments(mesh.loop_xy.data() + 2 * b, n, ox, oy);
    for (int k = 0; k < 3; ++k) {
      if (!sliver(c[k])) continue;
      for (int j = 0; j < 3; ++j)
        if (!sliver(c[j])) overlap[{c[k], c[j]}] += std::max(0.0, integral_ww(w, pm, k, j));
    }
  }
  // Largest overlap wins; ties (zero-area elements) go to the lower cover index.
  std::vector<double> best(nc, -1.0);
  for (const auto& [pair, a] : overlap) {
    if (a > best[pair.first]) {
      best[pair.first] = a;
      u.master[pair.first] = pair.second;
    }
  }

  u.unknown.assign(nc, -1);
  for (std::size_t c = 0; c < nc; ++c) {
    if (u.master[c] != static_cast<std::int32_t>(c)) continue;
    u.unknown[c] = u.unknowns();
    u.cover_of_unknown.push_back(static_cast<std::int32_t>(c));
  }
  for (std::size_t c = 0; c < nc; ++c)
    if (u.master[c] != static_cast<std::int32_t>(c)) {
      u.unknown[c] = u.unknown[u.master[c]];
      ++u.tied;
    }
  return u;
}

}  // namespace nmm::solve
