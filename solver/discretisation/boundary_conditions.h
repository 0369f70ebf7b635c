// Supports and tractions along the body boundary (scene keys "supports", "tractions"), and the
// faces where two bodies touch (they carry the in-situ stress across: insitu_stress.h).
//
// The boundary under a polyline: every element loop edge flagged kEdgeBoundary whose two
// endpoints lie on one segment of the polyline (within 1e-6·h, in the mesh as cut). Outer
// boundaries and hole faces alike; a polyline that touches no boundary edge is bad input.
//
// On an edge from a to b (current positions, length L, outward normal n, unit tangent s of the
// polyline segment), with the element's linear weights N = [w_0 w_1 w_2] (one per cover):
//   traction  f_k = ∫ w_k t ds,  t = normal·n + shear·s  (or t = σ_insitu(x)·n)
//   support   K  += k_s ∫ N_dᵀ N_d ds,  f −= k_s ∫ N_dᵀ u_d ds   for each held direction d
// with u the displacement since the start (linear along the edge: the field is linear in an
// element each step at n = 0). At cover order n the integrands are of degree ≤ 2n + 2 along the
// edge, so the (n + 2)-point Gauss rule integrates them exactly (n = 0: ξ = ½ ∓ 1/(2√3),
// weights L/2).
//
// A support is a penalty spring per unit length, k_s = solver.support_stiffness or by default
// 100·E_max/h N/m² (an edge of length h then holds like a fixed point, 100·E_max N/m): under a
// reaction traction p it gives way by p/k_s (1 MPa with E = 10 GPa, h = 1 m: 1 µm). It acts on
// exactly the covers whose support touches the held stretch (those of the elements owning the
// edges). A penalty rather than an exact constraint keeps the unknowns and the sparsity pattern
// the same whatever is held, and lets a restart change the supports freely.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/element_integration.h"
#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::solve {

/// An element loop edge v → next(v) on the boundary under a polyline.
struct BoundaryEdge {
  std::int32_t element = -1;  ///< element owning the edge
  std::int32_t vertex = -1;   ///< global loop vertex index of the edge's start
  std::int32_t next = -1;     ///< global loop vertex index of its end
  double sx = 0, sy = 0;      ///< –, unit tangent of the polyline segment it lies on
};

/// The boundary edges under `polyline` (InputError naming `path` if there are none).
std::vector<BoundaryEdge> edges_under(const Mesh& mesh, const std::vector<Vec2>& polyline,
                                      const std::string& scene_name, const std::string& path);

/// A boundary edge of an element of one body lying on the boundary of another body.
struct InterfaceEdge {
  BoundaryEdge edge;
  std::int32_t other_body = -1;  ///< the body on the other side
};
std::vector<InterfaceEdge> interface_edges(const Mesh& mesh, const SceneDef& scene);

/// The element's shape functions in its current frame (cover_space.h), and the Gauss rule
/// along its edges: `points` = order + 2 integrates φ_a·φ_b (degree 2n + 2 along a straight
/// edge) and a linear traction times φ_a exactly; n = 0 keeps the two-point rule.
struct EdgeFrame {
  const ElementBasis* basis = nullptr;
  int points = 2;  ///< Gauss points per edge, 2..4
};

/// Gauss–Legendre points on [0, 1] and weights (summing to 1) of the n-point rule, n = 2..4.
const double* gauss_points(int n);
const double* gauss_weights(int n);

/// Nodal forces [fx0 fy0 fx1 fy1 …] (N, 2 per shape function) of a traction t(ξ) on the edge
/// from a to b, where traction(x, y, nx, ny, out) fills out = {tx, ty} (Pa) at a point with
/// outward normal n.
template <class Traction>
std::vector<double> edge_traction_forces(const EdgeFrame& f, const double a[2],
                                         const double b[2], Traction traction) {
  const int nf = f.basis->functions();
  std::vector<double> out(2 * static_cast<std::size_t>(nf), 0.0), phi(static_cast<std::size_t>(nf));
  const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
  if (!(len > 0)) return out;
  const double nx = dy / len, ny = -dx / len;  // CCW loop: the outside is on the right
  const double* gp = gauss_points(f.points);
  const double* gw = gauss_weights(f.points);
  for (int q = 0; q < f.points; ++q) {
    const double x = a[0] + gp[q] * dx, y = a[1] + gp[q] * dy;
    double t[2];
    traction(x, y, nx, ny, t);
    f.basis->values(x, y, phi.data());
    for (int k = 0; k < nf; ++k) {
      const double w = phi[k] * gw[q] * len;
      out[2 * k] += w * t[0];
      out[2 * k + 1] += w * t[1];
    }
  }
  return out;
}

/// Penalty support on the edge a → b: adds k_s ∫NᵀN ds to the (2·nf)² (column-major) k for the
/// held directions, and −k_s ∫Nᵀu ds to f, with u linear from ua (at a) to ub (at b).
void edge_support(const EdgeFrame& f, const double a[2], const double b[2], const double ua[2],
                  const double ub[2], bool fix_x, bool fix_y, double k_s, double* k, double* f_out);

}  // namespace nmm::solve
