// Simplex integration and triangle weights against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/discretisation/elasticity.h"
#include "solver/discretisation/element_integration.h"

namespace nmm::solve {
namespace {

TEST(ElementIntegration, UnitSquareMoments) {
  const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const PolygonMoments m = polygon_moments(sq, 4, 0, 0);
  EXPECT_DOUBLE_EQ(m.a, 1.0);
  EXPECT_DOUBLE_EQ(m.sx, 0.5);
  EXPECT_DOUBLE_EQ(m.sy, 0.5);
  EXPECT_DOUBLE_EQ(m.sxx, 1.0 / 3);
  EXPECT_DOUBLE_EQ(m.syy, 1.0 / 3);
  EXPECT_DOUBLE_EQ(m.sxy, 0.25);
  // About its centre: ∫x = 0, ∫x² = 1/12, ∫xy = 0.
  const PolygonMoments c = polygon_moments(sq, 4, 0.5, 0.5);
  EXPECT_NEAR(c.sx, 0, 1e-15);
  EXPECT_NEAR(c.sxx, 1.0 / 12, 1e-15);
  EXPECT_NEAR(c.sxy, 0, 1e-15);
}

TEST(ElementIntegration, SlitAddsNothing) {
  // The square with a slit from (1, 0.5) to (0.4, 0.5) and back, as a crack tip leaves it.
  const double slit[] = {0, 0, 1, 0, 1, 0.5, 0.4, 0.5, 1, 0.5, 1, 1, 0, 1};
  const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const PolygonMoments a = polygon_moments(slit, 7, 0.2, 0.3), b = polygon_moments(sq, 4, 0.2, 0.3);
  EXPECT_NEAR(a.a, b.a, 1e-15);
  EXPECT_NEAR(a.sxx, b.sxx, 1e-15);
  EXPECT_NEAR(a.sxy, b.sxy, 1e-15);
}

TEST(ElementIntegration, TriangleWeightsAndConsistentMass) {
  const double p[] = {0, 0, 2, 0, 0.5, 1.5};  // relative to corner 0
  const TriangleWeights w = triangle_weights(p);
  EXPECT_DOUBLE_EQ(w.twice_area, 3.0);
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(w.at(k, p[2 * c], p[2 * c + 1]), k == c ? 1.0 : 0.0, 1e-15);
  EXPECT_NEAR(w.at(0, 0.7, 0.4) + w.at(1, 0.7, 0.4) + w.at(2, 0.7, 0.4), 1.0, 1e-15);
  // Over the triangle itself: ∫w_k = A/3, ∫w_k² = A/6, ∫w_k w_l = A/12 (the classical
  // consistent mass of a linear triangle).
  const PolygonMoments m = polygon_moments(p, 3, 0, 0);
  const double A = 1.5;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(integral_w(w, m, k), A / 3, 1e-15);
    for (int l = 0; l < 3; ++l) EXPECT_NEAR(integral_ww(w, m, k, l), k == l ? A / 6 : A / 12, 1e-15);
  }
}

TEST(Elasticity, PlaneStrainAndStressMatrices) {
  const MaterialDef m{"r", 2500, 1e10, 0.25, {}};
  const Mat3 ds = elasticity_matrix(m, PlaneKind::stress);
  EXPECT_NEAR(ds(0, 0), 1e10 / (1 - 0.0625), 1e-3);
  EXPECT_NEAR(ds(2, 2), 1e10 / 2.5, 1e-3);  // G = E / 2(1+ν)
  const Mat3 de = elasticity_matrix(m, PlaneKind::strain);
  EXPECT_NEAR(de(0, 0), 1e10 * 0.75 / (1.25 * 0.5), 1e-3);
  EXPECT_NEAR(de(0, 1), 1e10 * 0.25 / (1.25 * 0.5), 1e-3);
  EXPECT_NEAR(de(2, 2), 1e10 / 2.5, 1e-3);
}

}  // namespace
}  // namespace nmm::solve
