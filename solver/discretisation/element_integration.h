// Integration over manifold elements (docs/physics.md §1): simplex integration of polynomials over a
// counter-clockwise polygon, and the linear weight functions of the element's triangle.
#pragma once

#include <array>
#include <cstddef>

#include "solver/discretisation/polynomial.h"

namespace nmm::solve {

/// Exact integrals over a polygon of 1, x, y, x², xy, y², with x and y measured from an origin.
struct PolygonMoments {
  double a = 0;    ///< ∫ 1 dA, m²
  double sx = 0;   ///< ∫ x dA, m³
  double sy = 0;   ///< ∫ y dA, m³
  double sxx = 0;  ///< ∫ x² dA, m⁴
  double sxy = 0;  ///< ∫ x·y dA, m⁴
  double syy = 0;  ///< ∫ y² dA, m⁴
};

/// Moments of the polygon with n vertices xy[2·i], xy[2·i+1] (m, CCW, weakly simple allowed)
/// about (ox, oy).
PolygonMoments polygon_moments(const double* xy, std::size_t n, double ox, double oy);

/// Linear weight functions of a triangle: w_k(x, y) = a[k] + b[k]·x + c[k]·y, with x, y measured
/// from the same origin as the triangle's corners. Σ_k w_k = 1; w_k = 1 at corner k, 0 at the
/// others. b and c are the constant gradients (1/m).
struct TriangleWeights {
  double a[3], b[3], c[3];
  double twice_area;  ///< 2·area of the triangle, m² (> 0 for CCW corners)
  double at(int k, double x, double y) const { return a[k] + b[k] * x + c[k] * y; }
};

/// Weights of the triangle with corners p[0..5] = (x0, y0, x1, y1, x2, y2) (relative to the
/// origin). twice_area ≤ 0 means the triangle has collapsed or inverted.
TriangleWeights triangle_weights(const double* p);

/// ∫ w_k dA over a polygon with moments m (same origin as the weights).
double integral_w(const TriangleWeights& w, const PolygonMoments& m, int k);

/// ∫ w_k·w_l dA over a polygon with moments m.
double integral_ww(const TriangleWeights& w, const PolygonMoments& m, int k, int l);

/// Exact integrals of the monomials ξ^p·η^q (p + q ≤ degree, indexed as in polynomial.h) over a
/// polygon, with ξ = (x − ox)/scale, η = (y − oy)/scale: m[i] = ∫ ξ^p η^q dA in m² (dA physical).
/// General simplex formula (element_integration.cpp), for any degree ≤ kMaxDegree.
struct MonomialMoments {
  int degree = 0;
  std::array<double, kMaxMonomials> m{};  ///< m², one per monomial
};
MonomialMoments monomial_moments(const double* xy, std::size_t n, double ox, double oy,
                                 double scale, int degree);

/// ∫ a dA and ∫ a·b dA over the polygon of m (a, b in the same scaled coordinates; the degrees
/// must not exceed m.degree).
double integral(const Poly& a, const MonomialMoments& m);
double integral(const Poly& a, const Poly& b, const MonomialMoments& m);

}  // namespace nmm::solve
