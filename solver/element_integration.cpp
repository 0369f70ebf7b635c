// Simplex integration (Shi 1991; physics.md §1). For a CCW polygon, summing over its edges
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
#include "element_integration.h"

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

}  // namespace nmm::solve
