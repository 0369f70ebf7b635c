// Simplex integration (Shi 1991; docs/physics.md §1). For a CCW polygon, summing over its edges
// (x2, y2) → (x3, y3) with f = x2·y3 − x3·y2 (each edge and the origin span a signed triangle):
//   ∫1   += f/2
//   ∫x   += f (x2 + x3)/6                      ∫y   likewise
//   ∫x²  += f (x2² + x3² + x2·x3)/12           ∫y²  likewise
//   ∫xy  += f (2·x2·y2 + 2·x3·y3 + x2·y3 + x3·y2)/24
// Exact for these polynomials on any simple or weakly simple polygon (a slit or a bridge is
// walked both ways and cancels). Coordinates are taken relative to an origin near the element
// so the sums do not lose digits far from (0, 0).
//
// Triangle weights: with corners (xi, yi), 2Δ = (x1−x0)(y2−y0) − (x2−x0)(y1−y0) and, cyclically,
//   w_k = (x_{k+1}·y_{k+2} − x_{k+2}·y_{k+1} + (y_{k+1} − y_{k+2})·x + (x_{k+2} − x_{k+1})·y) / 2Δ.
//
// Monomials of any degree (higher-order covers): each edge (P, Q) and the origin span a signed
// triangle T = {s·P + t·Q : s, t ≥ 0, s + t ≤ 1} with Jacobian f = Px·Qy − Qx·Py, and
//   ∫_T ξ^a η^b = f Σ_{i≤a} Σ_{j≤b} C(a,i) C(b,j) Px^i Qx^(a−i) Py^j Qy^(b−j)
//                     · (i+j)! (a+b−i−j)! / (a+b+2)!
// from ∫_simplex s^k t^l ds dt = k! l! / (k+l+2)!. The signed triangles of a CCW polygon sum to
// the polygon (Green's theorem), convex or not. The degree-≤2 sums above are this formula's
// first terms.
#include "solver/discretisation/element_integration.h"

namespace nmm::solve {

PolygonMoments polygon_moments(const double* xy, std::size_t n, double ox, double oy) {
  PolygonMoments m;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i + 1 == n ? 0 : i + 1;
    const double x2 = xy[2 * i] - ox, y2 = xy[2 * i + 1] - oy;
    const double x3 = xy[2 * j] - ox, y3 = xy[2 * j + 1] - oy;
    const double f = x2 * y3 - x3 * y2;
    m.a += f;
    m.sx += f * (x2 + x3);
    m.sy += f * (y2 + y3);
    m.sxx += f * (x2 * x2 + x3 * x3 + x2 * x3);
    m.syy += f * (y2 * y2 + y3 * y3 + y2 * y3);
    m.sxy += f * (2 * x2 * y2 + 2 * x3 * y3 + x2 * y3 + x3 * y2);
  }
  m.a /= 2;
  m.sx /= 6;
  m.sy /= 6;
  m.sxx /= 12;
  m.syy /= 12;
  m.sxy /= 24;
  return m;
}

TriangleWeights triangle_weights(const double* p) {
  TriangleWeights w;
  w.twice_area = (p[2] - p[0]) * (p[5] - p[1]) - (p[4] - p[0]) * (p[3] - p[1]);
  const double inv = w.twice_area != 0 ? 1.0 / w.twice_area : 0.0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    w.a[k] = (p[2 * i] * p[2 * j + 1] - p[2 * j] * p[2 * i + 1]) * inv;
    w.b[k] = (p[2 * i + 1] - p[2 * j + 1]) * inv;
    w.c[k] = (p[2 * j] - p[2 * i]) * inv;
  }
  return w;
}

double integral_w(const TriangleWeights& w, const PolygonMoments& m, int k) {
  return w.a[k] * m.a + w.b[k] * m.sx + w.c[k] * m.sy;
}

double integral_ww(const TriangleWeights& w, const PolygonMoments& m, int k, int l) {
  return w.a[k] * w.a[l] * m.a + (w.a[k] * w.b[l] + w.a[l] * w.b[k]) * m.sx +
         (w.a[k] * w.c[l] + w.a[l] * w.c[k]) * m.sy + w.b[k] * w.b[l] * m.sxx +
         (w.b[k] * w.c[l] + w.b[l] * w.c[k]) * m.sxy + w.c[k] * w.c[l] * m.syy;
}

MonomialMoments monomial_moments(const double* xy, std::size_t n, double ox, double oy,
                                 double scale, int degree) {
  static constexpr double kFact[2 * kMaxDegree + 3] = {
      1, 1, 2, 6, 24, 120, 720, 5040, 40320, 362880, 3628800, 39916800, 479001600, 6227020800.0, 87178291200.0};
  static_assert(2 * kMaxDegree + 2 < 15, "factorial table");
  MonomialMoments r;
  r.degree = degree;
  const double inv = 1.0 / scale;
  double binom[kMaxDegree + 1][kMaxDegree + 1] = {};
  for (int a = 0; a <= degree; ++a)
    for (int i = 0; i <= a; ++i) binom[a][i] = kFact[a] / (kFact[i] * kFact[a - i]);
  for (std::size_t e = 0; e < n; ++e) {
    const std::size_t k = e + 1 == n ? 0 : e + 1;
    const double px = (xy[2 * e] - ox) * inv, py = (xy[2 * e + 1] - oy) * inv;
    const double qx = (xy[2 * k] - ox) * inv, qy = (xy[2 * k + 1] - oy) * inv;
    const double f = px * qy - qx * py;
    if (f == 0) continue;
    double ppx[kMaxDegree + 1], pqx[kMaxDegree + 1], ppy[kMaxDegree + 1], pqy[kMaxDegree + 1];
    ppx[0] = pqx[0] = ppy[0] = pqy[0] = 1;
    for (int d = 1; d <= degree; ++d) {
      ppx[d] = ppx[d - 1] * px;
      pqx[d] = pqx[d - 1] * qx;
      ppy[d] = ppy[d - 1] * py;
      pqy[d] = pqy[d - 1] * qy;
    }
    for (int idx = 0; idx < monomial_count(degree); ++idx) {
      const int a = kMonomials.p[idx], b = kMonomials.q[idx];
      double s = 0;
      for (int i = 0; i <= a; ++i)
        for (int j = 0; j <= b; ++j)
          s += binom[a][i] * binom[b][j] * ppx[i] * pqx[a - i] * ppy[j] * pqy[b - j] *
               kFact[i + j] * kFact[a + b - i - j];
      r.m[idx] += f * s / kFact[a + b + 2];
    }
  }
  for (double& v : r.m) v *= scale * scale;
  return r;
}

double integral(const Poly& a, const MonomialMoments& m) {
  double s = 0;
  for (int i = 0; i < a.size(); ++i) s += a.c[i] * m.m[i];
  return s;
}

double integral(const Poly& a, const Poly& b, const MonomialMoments& m) {
  double s = 0;
  for (int i = 0; i < a.size(); ++i) {
    if (a.c[i] == 0) continue;
    double t = 0;
    for (int j = 0; j < b.size(); ++j)
      t += b.c[j] * m.m[monomial_index(kMonomials.p[i] + kMonomials.p[j], kMonomials.q[i] + kMonomials.q[j])];
    s += a.c[i] * t;
  }
  return s;
}

}  // namespace nmm::solve
