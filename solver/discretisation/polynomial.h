// Bivariate polynomials in scaled local coordinates, the currency of higher-order cover
// functions (cover_space.h) and of exact integration over element polygons
// (element_integration.h).
//
// A polynomial of degree ≤ D in (ξ, η) is stored as the coefficients of its monomials ξ^p·η^q,
// p + q ≤ D, ordered by total degree and, within one degree, by the power of η:
//   index(p, q) = (p + q)(p + q + 1)/2 + q     (1, ξ, η, ξ², ξη, η², ξ³, …)
// so the first (n+1)(n+2)/2 coefficients are exactly the polynomials of degree ≤ n: the seed's
// eq. 1 basis {1, x, y, …, x^n, …, y^n} for a cover of order n.
//
// kMaxDegree = 6 covers the products of two shape functions of cover order 2 (each of degree 3:
// a linear weight times a quadratic cover function), the highest degree the mass matrix needs.
#pragma once

#include <array>
#include <cassert>

namespace nmm::solve {

constexpr int kMaxDegree = 6;
constexpr int monomial_count(int degree) { return (degree + 1) * (degree + 2) / 2; }
constexpr int kMaxMonomials = monomial_count(kMaxDegree);
constexpr int monomial_index(int p, int q) { return (p + q) * (p + q + 1) / 2 + q; }

/// Exponents (p, q) of the monomial with index i.
struct MonomialTable {
  std::array<int, kMaxMonomials> p{}, q{};
  constexpr MonomialTable() {
    for (int d = 0; d <= kMaxDegree; ++d)
      for (int j = 0; j <= d; ++j) {
        p[monomial_index(d - j, j)] = d - j;
        q[monomial_index(d - j, j)] = j;
      }
  }
};
inline constexpr MonomialTable kMonomials{};

/// c[i]·ξ^p(i)·η^q(i) summed over the monomials of degree ≤ degree.
struct Poly {
  int degree = 0;
  std::array<double, kMaxMonomials> c{};

  int size() const { return monomial_count(degree); }
  double operator()(double xi, double eta) const {
    // Horner would need a different order; degrees are ≤ 6, so plain powers are fine.
    double px[kMaxDegree + 1], py[kMaxDegree + 1];
    px[0] = py[0] = 1;
    for (int k = 1; k <= degree; ++k) {
      px[k] = px[k - 1] * xi;
      py[k] = py[k - 1] * eta;
    }
    double s = 0;
    for (int i = 0; i < size(); ++i) s += c[i] * px[kMonomials.p[i]] * py[kMonomials.q[i]];
    return s;
  }
  /// ∂/∂ξ and ∂/∂η (degree − 1, at least 0).
  Poly d_xi() const {
    Poly r;
    r.degree = degree > 0 ? degree - 1 : 0;
    for (int i = 0; i < size(); ++i)
      if (kMonomials.p[i] > 0) r.c[monomial_index(kMonomials.p[i] - 1, kMonomials.q[i])] += kMonomials.p[i] * c[i];
    return r;
  }
  Poly d_eta() const {
    Poly r;
    r.degree = degree > 0 ? degree - 1 : 0;
    for (int i = 0; i < size(); ++i)
      if (kMonomials.q[i] > 0) r.c[monomial_index(kMonomials.p[i], kMonomials.q[i] - 1)] += kMonomials.q[i] * c[i];
    return r;
  }
  Poly& operator*=(double s) {
    for (int i = 0; i < size(); ++i) c[i] *= s;
    return *this;
  }
};

/// a·b (degrees must sum to ≤ kMaxDegree).
inline Poly operator*(const Poly& a, const Poly& b) {
  assert(a.degree + b.degree <= kMaxDegree);
  Poly r;
  r.degree = a.degree + b.degree;
  for (int i = 0; i < a.size(); ++i) {
    if (a.c[i] == 0) continue;
    for (int j = 0; j < b.size(); ++j)
      r.c[monomial_index(kMonomials.p[i] + kMonomials.p[j], kMonomials.q[i] + kMonomials.q[j])] +=
          a.c[i] * b.c[j];
  }
  return r;
}

/// The monomial ξ^p·η^q of the shifted variables: (ξ − s)^p·(η − t)^q, expanded.
inline Poly shifted_monomial(int p, int q, double s, double t) {
  // Binomial expansion: (ξ − s)^p = Σ_i C(p, i) ξ^i (−s)^(p−i).
  Poly r;
  r.degree = p + q;
  double cp = 1;  // C(p, i)
  for (int i = 0; i <= p; ++i) {
    double sp = 1;
    for (int k = 0; k < p - i; ++k) sp *= -s;
    double cq = 1;
    for (int j = 0; j <= q; ++j) {
      double tq = 1;
      for (int k = 0; k < q - j; ++k) tq *= -t;
      r.c[monomial_index(i, j)] += cp * sp * cq * tq;
      cq = cq * (q - j) / (j + 1);
    }
    cp = cp * (p - i) / (i + 1);
  }
  return r;
}

}  // namespace nmm::solve
