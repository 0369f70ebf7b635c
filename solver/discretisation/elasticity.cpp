// Plane elasticity (docs/physics.md §1). With engineering shear strain γxy:
//   plane strain: D = E/((1+ν)(1−2ν)) · [[1−ν, ν, 0], [ν, 1−ν, 0], [0, 0, (1−2ν)/2]]
//   plane stress: D = E/(1−ν²)        · [[1, ν, 0], [ν, 1, 0], [0, 0, (1−ν)/2]]
// The displacement in an element is u = Σ_k w_k·u_k over its three covers, so
//   B = [ b0 0 b1 0 b2 0 ; 0 c0 0 c1 0 c2 ; c0 b0 c1 b1 c2 b2 ]   (w_k = a_k + b_k x + c_k y)
// and K_e = A_e·Bᵀ D B, with A_e the element polygon's area (not the triangle's).
#include "solver/discretisation/elasticity.h"

namespace nmm::solve {

Mat3 elasticity_matrix(const MaterialDef& m, PlaneKind plane) {
  const double E = m.young, nu = m.poisson;
  Mat3 D = Mat3::Zero();
  if (plane == PlaneKind::strain) {
    const double f = E / ((1 + nu) * (1 - 2 * nu));
    D << 1 - nu, nu, 0, nu, 1 - nu, 0, 0, 0, (1 - 2 * nu) / 2;
    D *= f;
  } else {
    const double f = E / (1 - nu * nu);
    D << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
    D *= f;
  }
  return D;
}

Mat36 strain_matrix(const TriangleWeights& w) {
  Mat36 B = Mat36::Zero();
  for (int k = 0; k < 3; ++k) {
    B(0, 2 * k) = w.b[k];
    B(1, 2 * k + 1) = w.c[k];
    B(2, 2 * k) = w.c[k];
    B(2, 2 * k + 1) = w.b[k];
  }
  return B;
}

}  // namespace nmm::solve
