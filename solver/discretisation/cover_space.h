// The approximation space of a run (in the spirit of deal.II's DoFHandler and MFEM's
// FiniteElementSpace): cover order n, unknowns per physical cover, the global numbering of the
// unknowns (through the sliver-cover ties of cover_unknowns.h), each element's unknowns, and the
// element's shape functions as polynomials. Nothing else in the solver knows how many unknowns a
// cover has.
//
// Seed eq. 1–3 with the weights of docs/physics.md §1: in a manifold element with covers k = 0, 1, 2
//   u(x) = Σ_k w_k(x) · Σ_j p_j((x − c_k)/h) · d_kj,      d_kj = (u, v) coefficients,
// with w_k the linear weights of the element's triangle, p_j the monomials of degree ≤ n
// (1, ξ, η, ξ², ξη, η²; polynomial.h), c_k the node of cover k (of its master for a tied sliver
// cover, so the tie d_s = d_m makes u_s ≡ u_m) and h the mesh size. Centring at the node and
// scaling by h keep every coefficient a displacement (m) and the matrix entries of one order of
// magnitude (the monomials stay O(1) on the cover).
//   n = 0: 2 unknowns per cover (constant cover functions, first-order NMM)
//   n = 1: 6 (linear cover functions), n = 2: 12 (quadratic).
// Unknown numbering: cover c's unknowns are first(c) + 2j + s for basis term j and direction
// s (0: x, 1: y), so n = 0 keeps the layout (u, v) of every earlier release. In an element, the
// local unknown 2(k·P + j) + s (P = terms per cover) is that of its cover k.
//
// Shape functions φ_kj = w_k·p_j are polynomials of degree n + 1, expressed in the element's
// scaled coordinates (ξ, η) = (x − o)/h with o the element frame's origin (the node of its first
// cover); their derivatives (1/m) are polynomials of degree n.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/discretisation/cover_unknowns.h"
#include "solver/discretisation/element_integration.h"
#include "common/mesh.h"
#include "solver/discretisation/polynomial.h"

namespace nmm::solve {

/// The shape functions of one element in its frame: φ[a], a = k·P + j.
struct ElementBasis {
  double ox = 0, oy = 0;  ///< m, origin of the scaled coordinates
  double h = 1;           ///< m, scale
  std::vector<Poly> phi;  ///< –, φ_a(ξ, η)
  std::vector<Poly> dx;   ///< 1/m, ∂φ_a/∂x
  std::vector<Poly> dy;   ///< 1/m, ∂φ_a/∂y
  int functions() const { return static_cast<int>(phi.size()); }
  /// φ_a at the point (x, y) (m) into out[0 .. functions()).
  void values(double x, double y, double* out) const;
};

/// m, the scale h of the scaled bases of a space on `mesh`: its mesh size (1 m for a mesh
/// without one).
inline double basis_scale(const Mesh& mesh) { return mesh.mesh_size > 0 ? mesh.mesh_size : 1.0; }

class CoverSpace {
 public:
  CoverSpace() = default;
  /// Order 0, 1 or 2; sliver covers (weight below min_weight everywhere, or support below
  /// min_support·h²) are tied as in cover_unknowns.h.
  CoverSpace(const Mesh& mesh, int order, double min_weight, double min_support = 0,
             std::int32_t first_crack_joint = -1);

  int order() const { return order_; }
  int terms() const { return monomial_count(order_); }      ///< P: polynomial terms per cover
  int dofs_per_cover() const { return 2 * terms(); }        ///< 2, 6, 12
  int element_dofs() const { return 3 * dofs_per_cover(); }  ///< unknowns of one element
  int unknowns() const { return unknowns_; }
  double scale() const { return h_; }  ///< m, h of the scaled bases

  /// The first unknown of cover c (its master's for a tied cover).
  int first_unknown(std::size_t c) const { return ties_.unknown[c]; }
  /// The cover owning unknown i (for messages).
  int cover_of_unknown(int i) const { return ties_.cover_of_unknown[i / dofs_per_cover()]; }
  /// The cover whose node centres the basis of cover c: its master.
  int basis_cover(std::size_t c) const { return ties_.master[c]; }
  const CoverUnknowns& ties() const { return ties_; }
  /// element_dofs() unknowns of element e, in local order 2(k·P + j) + s.
  const int* element_unknowns(std::size_t e) const {
    return element_unknowns_.data() + e * static_cast<std::size_t>(element_dofs());
  }
  /// True for local unknowns (of an element or a cover) of basis terms of degree ≥ 1.
  bool higher_order(int local) const { return (local / 2) % terms() != 0; }
  /// The unknowns of degree ≥ 1 terms of the untied covers (tied covers share their master's):
  /// those a factorisation regularises, as they may be linearly dependent (system_matrix.h).
  std::vector<int> higher_order_unknowns() const;

  /// The shape functions of an element whose triangle has weights w relative to the origin
  /// (ox, oy) (its frame), with basis centres `centre` (m, absolute x and y of the basis cover of
  /// each of the element's three covers).
  ElementBasis element_basis(double ox, double oy, const TriangleWeights& w,
                             const double centre[6]) const;
  /// The same into `out`, reusing its storage (no allocation once sized).
  void element_basis(double ox, double oy, const TriangleWeights& w, const double centre[6],
                     ElementBasis& out) const;

 private:
  int order_ = 0;
  double h_ = 1;
  int unknowns_ = 0;
  CoverUnknowns ties_;
  std::vector<int> element_unknowns_;  // [me · element_dofs()]
};

}  // namespace nmm::solve
