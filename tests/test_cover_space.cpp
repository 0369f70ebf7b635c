// Higher-order cover functions (cover_space.h, docs/higher-order-covers.md): exact monomial
// moments against closed-form integrals, the rank of K, patch tests at each order, free fall.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Dense>

#include "cover_cutter.h"
#include "cover_space.h"
#include "error.h"
#include "element_integration.h"
#include "time_stepper.h"

namespace nmm::solve {
namespace {

double fact(int n) { return n <= 1 ? 1.0 : n * fact(n - 1); }

// ∫ x^a y^b over [x0, x1] × [y0, y1], closed form.
double rect(int a, int b, double x0, double x1, double y0, double y1) {
  return (std::pow(x1, a + 1) - std::pow(x0, a + 1)) / (a + 1) *
         (std::pow(y1, b + 1) - std::pow(y0, b + 1)) / (b + 1);
}

TEST(MonomialMoments, TriangleSquareAndNonConvexPolygonAgainstClosedForms) {
  // Unit right triangle (0,0), (1,0), (0,1): ∫ x^a y^b = a! b! / (a + b + 2)!.
  const double tri[] = {0, 0, 1, 0, 0, 1};
  const MonomialMoments t = monomial_moments(tri, 3, 0, 0, 1, kMaxDegree);
  // Square [0, 1]²: 1/((a+1)(b+1)). L-shape [0,2]×[0,1] ∪ [0,1]×[1,2] (non-convex, CCW).
  const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const MonomialMoments s = monomial_moments(sq, 4, 0, 0, 1, kMaxDegree);
  const double ell[] = {0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2};
  const MonomialMoments l = monomial_moments(ell, 6, 0, 0, 1, kMaxDegree);
  // The same L-shape moved by (3, −2) and measured in ξ = (x − 3)/0.5: ∫ ξ^a η^b dA with
  // ξ ∈ [0, 4] etc.: 0.5^(−a−b) times the unshifted moment.
  double moved[12];
  for (int i = 0; i < 6; ++i) {
    moved[2 * i] = ell[2 * i] + 3;
    moved[2 * i + 1] = ell[2 * i + 1] - 2;
  }
  const MonomialMoments ls = monomial_moments(moved, 6, 3, -2, 0.5, kMaxDegree);
  for (int i = 0; i < kMaxMonomials; ++i) {
    const int a = kMonomials.p[i], b = kMonomials.q[i];
    const double te = fact(a) * fact(b) / fact(a + b + 2);
    EXPECT_NEAR(t.m[i], te, 1e-14 * te) << "triangle x^" << a << " y^" << b;
    const double se = 1.0 / ((a + 1) * (b + 1));
    EXPECT_NEAR(s.m[i], se, 1e-14 * se) << "square x^" << a << " y^" << b;
    const double le = rect(a, b, 0, 2, 0, 1) + rect(a, b, 0, 1, 1, 2);
    EXPECT_NEAR(l.m[i], le, 1e-13 * le) << "L-shape x^" << a << " y^" << b;
    EXPECT_NEAR(ls.m[i], le * std::pow(2.0, a + b), 1e-12 * le * std::pow(2.0, a + b));
  }
  // Degree ≤ 2 agrees with the first-order code's moments.
  const PolygonMoments pm = polygon_moments(ell, 6, 0.3, 0.7);
  const MonomialMoments lm = monomial_moments(ell, 6, 0.3, 0.7, 1, 2);
  EXPECT_NEAR(lm.m[0], pm.a, 1e-14);
  EXPECT_NEAR(lm.m[1], pm.sx, 1e-14);
  EXPECT_NEAR(lm.m[2], pm.sy, 1e-14);
  EXPECT_NEAR(lm.m[3], pm.sxx, 1e-14);
  EXPECT_NEAR(lm.m[4], pm.sxy, 1e-14);
  EXPECT_NEAR(lm.m[5], pm.syy, 1e-14);
}

TEST(Polynomial, ProductsDerivativesAndShifts) {
  // (ξ − 0.5)²(η + 2) at (1.5, −1): 1·1 = 1; its ∂/∂ξ = 2(ξ − 0.5)(η + 2) = 2.
  const Poly p = shifted_monomial(2, 1, 0.5, -2);
  EXPECT_NEAR(p(1.5, -1), 1.0, 1e-14);
  EXPECT_NEAR(p.d_xi()(1.5, -1), 2.0, 1e-14);
  EXPECT_NEAR(p.d_eta()(1.5, -1), 1.0, 1e-14);
  const Poly q = p * p;
  EXPECT_NEAR(q(0.2, 0.3), p(0.2, 0.3) * p(0.2, 0.3), 1e-13);
}

SceneDef plate(double h, int order) {
  SceneDef s;
  s.materials.push_back({"rock", 2500, 1e10, 0.25});
  BodyDef b;
  b.material = 0;
  b.outer = {{0.03, 0.01}, {1.71, 0.13}, {1.93, 1.07}, {0.87, 1.61}, {-0.21, 0.93}};
  s.bodies.push_back(b);
  s.mesh_size = h;
  s.plane = PlaneKind::strain;
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::equilibrium;
  s.solver.cover_order = order;
  return s;
}

// Dimension of the combinations of scalar shape functions that vanish everywhere: a field is
// zero iff, in every element, all coefficients of its polynomial (degree n + 1, in the
// element's scaled coordinates) vanish. Rows: (element, monomial); columns: scalar unknowns.
int field_null_dimension(const Mesh& m, const CoverSpace& sp) {
  const int P = sp.terms(), cols = sp.unknowns() / 2, M = monomial_count(sp.order() + 1);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m.element_count()) * M, cols);
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    const std::int32_t* ec = &m.element_covers[3 * e];
    const double ox = m.node_xy[2 * m.cover_node[ec[0]]], oy = m.node_xy[2 * m.cover_node[ec[0]] + 1];
    double p[6], centre[6];
    for (int k = 0; k < 3; ++k) {
      p[2 * k] = m.node_xy[2 * m.cover_node[ec[k]]] - ox;
      p[2 * k + 1] = m.node_xy[2 * m.cover_node[ec[k]] + 1] - oy;
      const int mc = sp.basis_cover(ec[k]);
      centre[2 * k] = m.node_xy[2 * m.cover_node[mc]];
      centre[2 * k + 1] = m.node_xy[2 * m.cover_node[mc] + 1];
    }
    const ElementBasis eb = sp.element_basis(ox, oy, triangle_weights(p), centre);
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < P; ++j)
        for (int i = 0; i < eb.phi[k * P + j].size(); ++i)
          S(static_cast<Eigen::Index>(e) * M + i, sp.first_unknown(ec[k]) / 2 + j) += eb.phi[k * P + j].c[i];
  }
  const Eigen::VectorXd sv = Eigen::BDCSVD<Eigen::MatrixXd>(S).singularValues();
  int null = 0;
  for (Eigen::Index i = 0; i < sv.size(); ++i) null += sv[i] < 1e-10 * sv[0];
  return null;
}

TEST(CoverSpace, RankOfTheFreeStiffnessMatrix) {
  // K of one free body, no fixed points. Its zero eigenvalues must be exactly the 3 rigid modes
  // plus the combinations of coefficients whose field is zero everywhere (linear dependence,
  // counted independently from the sampled shape functions, twice: x and y): no mode can
  // deform the rock without strain energy. For linear weights Σ_i w_i (x − x_i) ≡ 0 and
  // Σ_i w_i (y − y_i) ≡ 0 give at least 2 per component at n = 1 (6 at n = 2: times 1, x, y);
  // covers whose support in the body is one or two elements (at the boundary) add local ones.
  for (int order : {0, 1, 2}) {
    // A rectangle whose cut elements are all ≥ 2 % of h²: an element of 1e-5 h² (the pentagon
    // above has one) makes its covers' quadratic terms nearly, not exactly, dependent (energy
    // ∝ its size⁴), which the regularised factorisation handles but no threshold can count.
    SceneDef s = plate(0.3, order);
    s.bodies[0].outer = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
    const Mesh m = pre::build_mesh(s, "rank");
    TimeStepper st(m, s, "rank");
    st.assemble_rhs(1.0);
    const SystemMatrix::Sparse full = st.system().matrix().selfadjointView<Eigen::Lower>();
    const Eigen::VectorXd ev =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(full), Eigen::EigenvaluesOnly).eigenvalues();
    const double top = ev.maxCoeff();
    int zero = 0;
    double largest_zero = 0, smallest_kept = top;
    for (Eigen::Index i = 0; i < ev.size(); ++i) {
      if (std::abs(ev[i]) < 1e-12 * top) {
        ++zero;
        largest_zero = std::max(largest_zero, std::abs(ev[i]));
      } else {
        smallest_kept = std::min(smallest_kept, ev[i]);
      }
    }
    const int dependent = 2 * field_null_dimension(m, st.space());
    std::printf("order %d: %d unknowns, rank %d, %d zero eigenvalues = 3 rigid + %d dependent "
                "(largest |λ| of them %.1e, smallest kept %.1e of the largest)\n",
                order, st.unknowns(), st.unknowns() - zero, zero, dependent,
                largest_zero / top, smallest_kept / top);
    EXPECT_EQ(zero, 3 + dependent) << "order " << order;
    EXPECT_EQ(st.unknowns() - zero, st.unknowns() - 3 - dependent);
    EXPECT_EQ(dependent, order == 0 ? 0 : order == 1 ? 6 : 16);  // measured: 4 + 2, 12 + 4
    EXPECT_LE(dependent, order == 0 ? 0 : st.unknowns());
    EXPECT_GT(smallest_kept, 1e4 * largest_zero) << "a clear gap above the null space";
  }
}

TEST(CoverSpace, QuadraticFieldIsExactAtOrderOne) {
  // u = Σ_i w_i(x)·[u(x_i) + (∇ℓ + ½∇q(x_i))·(x − x_i)] reproduces u = ℓ + q (ℓ linear, q
  // quadratic) exactly, since Σ w_i x_i = x gives x_iᵀA x summed to xᵀA x. Imposed on every
  // cover, the stress must be D·ε(x) at every point, and a body force b = −div σ (constant:
  // gravity) must balance every cover whose star lies inside the body, cut elements included.
  SceneDef s = plate(0.15, 1);
  // u = (a1 x + a2 y + qx(x, y), …) with quadratic parts qx = c1 x² + c2 xy + c3 y².
  // Small (1e-7 strains), so the geometry update of impose_displacement() changes the residual
  // below the tolerance.
  const double c[6] = {2e-7, -1e-7, 3e-8, -5e-8, 1.5e-7, 4e-8};  // qx: c0..c2, qy: c3..c5
  const double lin[4] = {1e-7, 2e-8, -3e-8, 5e-8};                 // ∂ux/∂x, ∂ux/∂y, ∂uy/∂x, ∂uy/∂y
  auto u = [&](double x, double y, int dir) {
    const double* q = c + 3 * dir;
    return lin[2 * dir] * x + lin[2 * dir + 1] * y + q[0] * x * x + q[1] * x * y + q[2] * y * y;
  };
  auto grad_half_q = [&](double x, double y, int dir, int wrt) {  // ½ ∂q/∂x or ∂y
    const double* q = c + 3 * dir;
    return wrt == 0 ? q[0] * x + 0.5 * q[1] * y : 0.5 * q[1] * x + q[2] * y;
  };
  const MaterialDef& mat = s.materials[0];
  const Mat3 D = elasticity_matrix(mat, s.plane);
  // ε(x) = (ux,x, uy,y, ux,y + uy,x); σ = D ε linear; div σ constant.
  auto strain = [&](double x, double y) {
    const double uxx = lin[0] + 2 * c[0] * x + c[1] * y, uxy = lin[1] + c[1] * x + 2 * c[2] * y;
    const double uyx = lin[2] + 2 * c[3] * x + c[4] * y, uyy = lin[3] + c[4] * x + 2 * c[5] * y;
    return Vec3(uxx, uyy, uxy + uyx);
  };
  // ∂ε/∂x and ∂ε/∂y are constant.
  const Vec3 dex(2 * c[0], c[4], c[1] + 2 * c[3]), dey(c[1], 2 * c[5], 2 * c[2] + c[4]);
  const Vec3 dsx = D * dex, dsy = D * dey;
  const double divx = dsx[0] + dsy[2], divy = dsx[2] + dsy[1];
  s.has_gravity = true;
  s.gravity = {-divx / mat.density, -divy / mat.density};  // ρ g + div σ = 0

  const Mesh m = pre::build_mesh(s, "patch2");
  TimeStepper st(m, s, "patch2");
  const CoverSpace& sp = st.space();
  ASSERT_EQ(sp.dofs_per_cover(), 6);
  const double h = sp.scale();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(st.unknowns());
  for (std::size_t cv = 0; cv < m.cover_count(); ++cv) {
    if (sp.basis_cover(cv) != static_cast<int>(cv)) continue;
    const double x = m.node_xy[2 * m.cover_node[cv]], y = m.node_xy[2 * m.cover_node[cv] + 1];
    const int f = sp.first_unknown(cv);
    for (int dir = 0; dir < 2; ++dir) {
      d[f + dir] = u(x, y, dir);
      d[f + 2 + dir] = h * (lin[2 * dir] + grad_half_q(x, y, dir, 0));      // ξ term
      d[f + 4 + dir] = h * (lin[2 * dir + 1] + grad_half_q(x, y, dir, 1));  // η term
    }
  }
  // The field at every loop vertex, before the update moves them.
  std::vector<double> xy0 = st.loop_xy();
  st.impose_displacement(d);
  double worst_u = 0, umax = 0;
  for (std::size_t v = 0; v < xy0.size() / 2; ++v)
    for (int dir = 0; dir < 2; ++dir) {
      const double exact = u(xy0[2 * v], xy0[2 * v + 1], dir);
      worst_u = std::max(worst_u, std::abs(st.loop_xy()[2 * v + dir] - xy0[2 * v + dir] - exact));
      umax = std::max(umax, std::abs(exact));
    }
  // Round-off of positions (≈ 1e-16 m) against u ≈ 1e-7 m; a Taylor-gradient (not ½∇q)
  // choice would be off by ½·c·h² ≈ 5e-3 of u.
  EXPECT_LT(worst_u, 1e-8 * umax) << "the quadratic field is reproduced at every loop vertex";
  // Stress at each element's loop vertices (positions as cut: the stress polynomial lives in
  // the frame of the element's first cover node, which has moved with the field).
  double worst_s = 0, smax = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e)
    for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v) {
      const double x = m.loop_xy[2 * v], y = m.loop_xy[2 * v + 1];
      const std::int32_t c0 = m.element_covers[3 * e];
      const double sx = x + u(m.node_xy[2 * m.cover_node[c0]], m.node_xy[2 * m.cover_node[c0] + 1], 0);
      const double sy = y + u(m.node_xy[2 * m.cover_node[c0]], m.node_xy[2 * m.cover_node[c0] + 1], 1);
      const auto got = st.stress_at(e, sx, sy);
      const Vec3 want = D * strain(x, y);
      for (int r = 0; r < 3; ++r) {
        worst_s = std::max(worst_s, std::abs(got[r] - want[r]));
        smax = std::max(smax, std::abs(want[r]));
      }
    }
  EXPECT_LT(worst_s, 1e-9 * smax) << "σ = D ε(x) exactly";
  // Equilibrium of interior covers, all six unknowns.
  std::vector<char> touches_boundary(m.cover_count(), 0);
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    bool cut = false;
    for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v)
      cut |= (m.loop_edge_origin[v] & kEdgeBoundary) != 0;
    if (cut)
      for (int k = 0; k < 3; ++k) touches_boundary[m.element_covers[3 * e + k]] = 1;
  }
  const Eigen::VectorXd& r = st.assemble_rhs(1.0);
  const double scale = smax * s.mesh_size;
  int interior = 0;
  double worst_r = 0;
  for (std::size_t cv = 0; cv < m.cover_count(); ++cv) {
    if (touches_boundary[cv]) continue;
    ++interior;
    for (int l = 0; l < 6; ++l) worst_r = std::max(worst_r, std::abs(r[sp.first_unknown(cv) + l]));
  }
  EXPECT_GT(interior, 20);
  // The geometry moved by u (≤ 4e-7 m), which perturbs the residual by about u/h relative.
  std::printf("quadratic patch at n = 1: worst interior residual %.2e of σ·h\n", worst_r / scale);
  EXPECT_LT(worst_r, 1e-5 * scale) << "interior covers in equilibrium";
}

TEST(CoverSpace, LinearFieldIsExactAtOrderZeroAndTwo) {
  // A linear field at n = 2 (quadratic covers): constant terms u(x_i), linear terms h·∇u,
  // quadratic terms zero: uniform stress everywhere.
  for (int order : {0, 2}) {
    SceneDef s = plate(0.2, order);
    const Mesh m = pre::build_mesh(s, "patch");
    TimeStepper st(m, s, "patch");
    const CoverSpace& sp = st.space();
    const double exx = 1e-4, eyy = -3e-5, gxy = 5e-5, h = sp.scale();
    Eigen::VectorXd d = Eigen::VectorXd::Zero(st.unknowns());
    for (std::size_t cv = 0; cv < m.cover_count(); ++cv) {
      if (sp.basis_cover(cv) != static_cast<int>(cv)) continue;
      const double x = m.node_xy[2 * m.cover_node[cv]], y = m.node_xy[2 * m.cover_node[cv] + 1];
      const int f = sp.first_unknown(cv);
      d[f] = exx * x + 0.5 * gxy * y;
      d[f + 1] = eyy * y + 0.5 * gxy * x;
      if (order > 0) {
        d[f + 2] = h * exx;
        d[f + 3] = h * 0.5 * gxy;
        d[f + 4] = h * 0.5 * gxy;
        d[f + 5] = h * eyy;
      }
    }
    st.impose_displacement(d);
    const Mat3 D = elasticity_matrix(s.materials[0], s.plane);
    const Vec3 sigma = D * Vec3(exx, eyy, gxy);
    const std::vector<double> mean = st.mean_stress();
    for (std::size_t e = 0; e < m.element_count(); ++e)
      for (int i = 0; i < 3; ++i) ASSERT_NEAR(mean[3 * e + i], sigma[i], 1e-9 * sigma.norm()) << "element " << e;
  }
}

TEST(CoverSpace, FreeFallIsExactAtOrderOne) {
  SceneDef s;
  s.materials.push_back({"rock", 2500, 1e10, 0.25});
  BodyDef b;
  b.material = 0;
  b.outer = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  s.bodies.push_back(b);
  s.mesh_size = 0.4;
  s.plane = PlaneKind::stress;
  s.has_gravity = true;
  s.gravity = {0, -9.81};
  s.solver.cover_order = 1;
  s.measure_points.push_back({1, 0.5});
  const Mesh m = pre::build_mesh(s, "fall");
  TimeStepper st(m, s, "fall");
  for (int i = 0; i < 100; ++i) st.step(0.01);
  const auto u = st.displacement_at(st.measure_points()[0]);
  EXPECT_NEAR(u[1], -0.5 * 9.81 * 1.0, 1e-9 * 4.905);
  EXPECT_NEAR(u[0], 0, 1e-10);
  double smax = 0;
  for (double x : st.mean_stress()) smax = std::max(smax, std::abs(x));
  EXPECT_LT(smax, 1e-3) << "Pa: a falling body carries no stress";
  // Every loop vertex fell the same.
  for (std::size_t v = 1; v < st.loop_xy().size(); v += 2)
    EXPECT_NEAR(st.loop_xy()[v] - m.loop_xy[v], -4.905, 1e-8);
}

TEST(CoverSpace, RollersAndTractionGiveUniformStressAtOrderOneAndTwo) {
  // A 1 m × 2 m column on rollers (bottom: y held, left: x held), pressed by 1 MPa on its top:
  // σyy = −1 MPa, σxx = τxy = 0 everywhere, whatever the order (edge integrals of degree 2n + 2
  // with the (n + 2)-point Gauss rule).
  for (int order : {1, 2}) {
    SceneDef s = plate(0.3, order);
    s.plane = PlaneKind::stress;
    s.bodies[0].outer = {{0, 0}, {1, 0}, {1, 2}, {0, 2}};
    s.supports.push_back({{{-0.1, 0}, {1.1, 0}}, false, true});
    s.supports.push_back({{{0, -0.1}, {0, 2.1}}, true, false});
    TractionDef t;
    t.points = {{-0.1, 2}, {1.1, 2}};
    t.normal = -1e6;
    s.tractions.push_back(t);
    const Mesh m = pre::build_mesh(s, "column");
    TimeStepper st(m, s, "column");
    st.step(1.0);
    const std::vector<double> mean = st.mean_stress();
    double worst = 0;
    for (std::size_t e = 0; e < m.element_count(); ++e) {
      worst = std::max(worst, std::abs(mean[3 * e] - 0));
      worst = std::max(worst, std::abs(mean[3 * e + 1] + 1e6));
      worst = std::max(worst, std::abs(mean[3 * e + 2]));
    }
    EXPECT_LT(worst, 1e-4 * 1e6) << "order " << order;
    // The top shortens by σ·L/E = 1e6·2/1e10 = 0.2 mm, and the bottom roller gives way by
    // p/k_s with k_s = 100·E/h (boundary_conditions.h): 0.3 µm.
    double dy = 0;
    for (std::size_t v = 1; v < st.loop_xy().size(); v += 2) dy = std::min(dy, st.loop_xy()[v] - m.loop_xy[v]);
    EXPECT_NEAR(dy, -(2e-4 + 1e6 / (100 * 1e10 / 0.3)), 1e-9) << "order " << order;
  }
}

TEST(CoverSpace, CheckpointRestartIsBitwiseAtOrderOneAndRefusedAtAnotherOrder) {
  // A cantilever-like plate vibrating under gravity (dynamic, fixed points): 6 steps straight
  // against 3 + checkpoint + 3 from a fresh stepper. Equal state hashes: bitwise the same.
  auto scene = [](int order) {
    SceneDef s = plate(0.3, order);
    s.bodies[0].outer = {{0, 0}, {3, 0}, {3, 0.6}, {0, 0.6}};
    s.solver.dynamic = true;
    s.has_gravity = true;
    s.gravity = {0, -9.81};
    s.fixed_points = {{0, 0}, {0, 0.3}, {0, 0.6}};
    return s;
  };
  const SceneDef s = scene(1);
  const Mesh m = pre::build_mesh(s, "ckpt");
  TimeStepper straight(m, s, "ckpt");
  for (int i = 0; i < 6; ++i) straight.step(1e-3);
  TimeStepper first(m, s, "ckpt");
  for (int i = 0; i < 3; ++i) first.step(1e-3);
  const std::string path = ::testing::TempDir() + "/order1.nmmstate";
  first.write_checkpoint(path);
  TimeStepper second(m, s, "ckpt");
  second.restart_from(path);
  for (int i = 0; i < 3; ++i) second.step(1e-3);
  EXPECT_EQ(second.state_hash(), straight.state_hash());
  // The tip has moved (the run is not trivially at rest).
  double umax = 0;
  for (double u : straight.cover_displacement()) umax = std::max(umax, std::abs(u));
  EXPECT_GT(umax, 1e-9);
  // The same checkpoint into an order-0 run of the same mesh: refused, naming the orders.
  const SceneDef s0 = scene(0);
  TimeStepper other(m, s0, "ckpt");
  try {
    other.restart_from(path);
    FAIL() << "a checkpoint of order 1 must not restart an order-0 run";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("6 unknowns per physical cover"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nmm::solve
