// The approximation space: numbering and shape functions of cover order n (cover_space.h).
//
// In the element's scaled coordinates (ξ, η) = (x − o)/h the weight of cover k is
//   w_k = a_k + b_k·(x − o) + c_k·(y − o) = a_k + (b_k h)·ξ + (c_k h)·η
// and its basis term p_j((x − c_k)/h) = (ξ − ξ_k)^p (η − η_k)^q with (ξ_k, η_k) = (c_k − o)/h.
// φ_kj = w_k·p_j, ∂φ/∂x = (1/h)·∂φ/∂ξ, ∂φ/∂y = (1/h)·∂φ/∂η: all exact polynomials, so every
// element integral is an exact moment sum (element_integration.h).
#include "solver/discretisation/cover_space.h"

#include <stdexcept>
#include <string>

namespace nmm::solve {

void ElementBasis::values(double x, double y, double* out) const {
  const double xi = (x - ox) / h, eta = (y - oy) / h;
  for (int a = 0; a < functions(); ++a) out[a] = phi[a](xi, eta);
}

CoverSpace::CoverSpace(const Mesh& mesh, int order, double min_weight, double min_support,
                       std::int32_t first_crack_joint)
    : order_(order) {
  if (order < 0 || order > 2)
    throw std::invalid_argument("cover order " + std::to_string(order) + " (0, 1 or 2)");
  h_ = basis_scale(mesh);
  ties_ = assign_cover_unknowns(mesh, min_weight, dofs_per_cover(), min_support, first_crack_joint);
  unknowns_ = ties_.unknowns();
  const std::size_t ne = mesh.element_count();
  const int m = dofs_per_cover();
  element_unknowns_.resize(ne * static_cast<std::size_t>(element_dofs()));
  for (std::size_t e = 0; e < ne; ++e) {
    int* g = element_unknowns_.data() + e * static_cast<std::size_t>(element_dofs());
    for (int k = 0; k < 3; ++k) {
      const int first = ties_.unknown[mesh.element_covers[3 * e + k]];
      for (int i = 0; i < m; ++i) g[k * m + i] = first + i;
    }
  }
}

std::vector<int> CoverSpace::higher_order_unknowns() const {
  std::vector<int> u;
  for (std::size_t c = 0; c < ties_.master.size(); ++c) {
    if (basis_cover(c) != static_cast<int>(c)) continue;  // tied: its master's
    for (int l = 0; l < dofs_per_cover(); ++l)
      if (higher_order(l)) u.push_back(first_unknown(c) + l);
  }
  return u;
}

ElementBasis CoverSpace::element_basis(double ox, double oy, const TriangleWeights& w,
                                       const double centre[6]) const {
  ElementBasis b;
  element_basis(ox, oy, w, centre, b);
  return b;
}

void CoverSpace::element_basis(double ox, double oy, const TriangleWeights& w,
                               const double centre[6], ElementBasis& b) const {
  b.ox = ox;
  b.oy = oy;
  b.h = h_;
  const int P = terms();
  b.phi.resize(3 * P);
  b.dx.resize(3 * P);
  b.dy.resize(3 * P);
  const double inv_h = 1.0 / h_;
  for (int k = 0; k < 3; ++k) {
    Poly wk;
    wk.degree = 1;
    wk.c[0] = w.a[k];
    wk.c[1] = w.b[k] * h_;
    wk.c[2] = w.c[k] * h_;
    const double sk = (centre[2 * k] - ox) * inv_h, tk = (centre[2 * k + 1] - oy) * inv_h;
    for (int j = 0; j < P; ++j) {
      const int a = k * P + j;
      if (j == 0) {
        b.phi[a] = wk;  // p_0 = 1: no product, the n = 0 shape function exactly
      } else {
        b.phi[a] = wk * shifted_monomial(kMonomials.p[j], kMonomials.q[j], sk, tk);
      }
      b.dx[a] = b.phi[a].d_xi();
      b.dx[a] *= inv_h;
      b.dy[a] = b.phi[a].d_eta();
      b.dy[a] *= inv_h;
    }
  }
}

}  // namespace nmm::solve
