// Higher-order cover functions (cover_space.h, docs/higher-order-covers.md): exact monomial
// moments against closed-form integrals, the rank of K, patch tests at each order, free fall.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Dense>

#include "preprocess/cover_cutter.h"
#include "solver/stepping/time_stepper_probe.h"
#include "solver/stepping/restart.h"
#include "solver/discretisation/cover_space.h"
#include "common/error.h"
#include "solver/discretisation/element_integration.h"
#include "solver/output/energy.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {
namespace {

double fact(int n) { return n <= 1 ? 1.0 : n * fact(n - 1); }

// ∫ x^a y^b over [x0, x1] × [y0, y1], closed form.
double rect(int a, int b, double x0, double x1, double y0, double y1) {
  return (std::pow(x1, a + 1) - std::pow(x0, a + 1)) / (a + 1) *
         (std::pow(y1, b + 1) - std::pow(y0, b + 1)) / (b + 1);
}

// [pc] 1 for covers of an element cut by a body boundary: their residual holds the boundary's
// traction, so the equilibrium checks look at the others.
std::vector<char> covers_touching_boundary(const Mesh& m) {
  std::vector<char> touches(m.cover_count(), 0);
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    bool cut = false;
    for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v)
      cut |= (m.loop_edge_origin[v] & kEdgeBoundary) != 0;
    if (cut)
      for (int k = 0; k < 3; ++k) touches[m.element_covers[3 * e + k]] = 1;
  }
  return touches;
}

// The largest residual over every unknown of the covers away from the body boundary, and how
// many such covers there are: the equilibrium check of the patch tests.
struct InteriorResidual {
  double worst = 0;  ///< N (the residual's unit)
  int covers = 0;
};
InteriorResidual interior_residual(const Mesh& m, const CoverSpace& sp, const Eigen::VectorXd& r) {
  const std::vector<char> touches_boundary = covers_touching_boundary(m);
  InteriorResidual out;
  for (std::size_t cv = 0; cv < m.cover_count(); ++cv) {
    if (touches_boundary[cv]) continue;
    ++out.covers;
    for (int l = 0; l < sp.dofs_per_cover(); ++l)
      out.worst = std::max(out.worst, std::abs(r[sp.first_unknown(cv) + l]));
  }
  return out;
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
  s.materials.push_back({"rock", 2500, 1e10, 0.25, {}});
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
    TimeStepperProbe::assemble_rhs(st, 1.0);
    const SystemMatrix::Sparse full = st.view().system.matrix().selfadjointView<Eigen::Upper>();
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
    const int dependent = 2 * field_null_dimension(m, st.view().space);
    std::printf("order %d: %d unknowns, rank %d, %d zero eigenvalues = 3 rigid + %d dependent "
                "(largest |λ| of them %.1e, smallest kept %.1e of the largest)\n",
                order, st.view().space.unknowns(), st.view().space.unknowns() - zero, zero, dependent,
                largest_zero / top, smallest_kept / top);
    EXPECT_EQ(zero, 3 + dependent) << "order " << order;
    EXPECT_EQ(st.view().space.unknowns() - zero, st.view().space.unknowns() - 3 - dependent);
    EXPECT_EQ(dependent, order == 0 ? 0 : order == 1 ? 6 : 16);  // measured: 4 + 2, 12 + 4
    EXPECT_LE(dependent, order == 0 ? 0 : st.view().space.unknowns());
    EXPECT_GT(smallest_kept, 1e4 * largest_zero) << "a clear gap above the null space";
  }
}

TEST(CoverSpace, RemoveNullPartTakesOutZeroFieldCombinationsOnly) {
  // SystemMatrix::remove_null_part (docs/higher-order-covers.md "Keeping the null space out of
  // the contact solve"): x ← x − (P + E)⁻¹E x removes a vector's zero-field part, however large,
  // and leaves its field alone (up to ε/λ on the stiffest-to-resolve kept modes). The matrix: a
  // free plate's dynamic step matrix A = K + 2M/Δt², positive definite but for the zero-field
  // combinations. The zero-field vector: every cover's ξ coefficient of u equal (Σ w_k (x − c_k) ≡ 0).
  for (int order : {1, 2}) {
    SceneDef s = plate(0.3, order);
    s.bodies[0].outer = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
    s.solver.dynamic = true;
    s.has_gravity = true;
    s.gravity = {0, -9.81};
    const Mesh m = pre::build_mesh(s, "null");
    TimeStepper st(m, s, "null");
    ASSERT_EQ(st.view().space.ties().tied, 0u);
    st.step(1e-3);  // leaves the factorisation of this step's matrix
    const SystemMatrix& sys = st.view().system;
    ASSERT_TRUE(sys.has_factor());
    const SystemMatrix::Sparse a = sys.matrix().selfadjointView<Eigen::Upper>();
    const CoverSpace& sp = st.view().space;
    const Eigen::Index n = sp.unknowns();
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n), x(n);
    for (std::size_t c = 0; c < m.cover_count(); ++c) z[sp.first_unknown(c) + 2] = 1.0;  // term 1 = ξ, x
    for (Eigen::Index i = 0; i < n; ++i) x[i] = 1e-3 * std::sin(1.0 + 0.37 * static_cast<double>(i));
    const double a_max = a.coeffs().cwiseAbs().maxCoeff();
    ASSERT_LT((a * z).norm(), 1e-12 * a_max * z.norm()) << "order " << order << ": z is a zero-field combination";

    Eigen::VectorXd z1 = z;
    sys.remove_null_part(z1);
    Eigen::VectorXd x1 = x;
    sys.remove_null_part(x1);
    Eigen::VectorXd y1 = x + 1e3 * z;  // a large null part on top: the same result
    sys.remove_null_part(y1);
    const double field_change = (a * (x1 - x)).norm() / (a * x).norm();
    std::printf("order %d: %ld unknowns; zero-field vector kept %.1e of its size; a vector's field changed by "
                "%.1e; with 1e3 × the zero-field vector added, the result moved by %.1e of what was added\n",
                order, static_cast<long>(n), z1.norm() / z.norm(), field_change, (y1 - x1).norm() / (1e3 * z.norm()));
    EXPECT_LT(z1.norm(), 1e-5 * z.norm()) << "order " << order;
    EXPECT_LT(field_change, 1e-6) << "order " << order;
    EXPECT_LT((y1 - x1).norm(), 1e-5 * 1e3 * z.norm()) << "order " << order;
    EXPECT_GT((x1 - x).norm(), 1e-3 * x.norm()) << "order " << order << ": x had a null part to remove";
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
  const CoverSpace& sp = st.view().space;
  ASSERT_EQ(sp.dofs_per_cover(), 6);
  const double h = sp.scale();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(st.view().space.unknowns());
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
  std::vector<double> xy0 = st.view().state.loop_xy;
  TimeStepperProbe::impose_displacement(st, d);
  double worst_u = 0, umax = 0;
  for (std::size_t v = 0; v < xy0.size() / 2; ++v)
    for (int dir = 0; dir < 2; ++dir) {
      const double exact = u(xy0[2 * v], xy0[2 * v + 1], dir);
      worst_u = std::max(worst_u, std::abs(st.view().state.loop_xy[2 * v + dir] - xy0[2 * v + dir] - exact));
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
      const auto got = stress_at(st.view(), e, sx, sy);
      const Vec3 want = D * strain(x, y);
      for (int r = 0; r < 3; ++r) {
        worst_s = std::max(worst_s, std::abs(got[r] - want[r]));
        smax = std::max(smax, std::abs(want[r]));
      }
    }
  EXPECT_LT(worst_s, 1e-9 * smax) << "σ = D ε(x) exactly";
  // Equilibrium of interior covers, all six unknowns.
  const auto [worst_r, interior] = interior_residual(m, sp, TimeStepperProbe::assemble_rhs(st, 1.0));
  const double scale = smax * s.mesh_size;
  EXPECT_GT(interior, 20);
  // The geometry moved by u (≤ 4e-7 m), which perturbs the residual by about u/h relative.
  std::printf("quadratic patch at n = 1: worst interior residual %.2e of σ·h\n", worst_r / scale);
  EXPECT_LT(worst_r, 1e-5 * scale) << "interior covers in equilibrium";
}

TEST(CoverSpace, CubicFieldIsExactAtOrderTwo) {
  // Order n reproduces fields of degree n + 1: at n = 2 a cubic u. With linear weights
  // (Σ w_i = 1, Σ w_i x_i = x) the polar form does it: for a homogeneous F of degree m with
  // symmetric m-linear form B, Σ_i w_i(x)·B(x_i, x, …, x) = B(x, …, x) = F(x); so cover i takes
  // p_i(x) = ℓ(x) + B2(x_i, x) + B3(x_i, x, x), a quadratic, written in its scaled basis about
  // x_i (Taylor coefficients, exact by central differences for a quadratic). The cubic part is
  // chosen with divergence-free stress (a kernel of the 4 × 8 map from its coefficients to the
  // linear terms of div σ), the quadratic part's constant div σ is balanced by gravity: then every
  // cover whose star lies inside the body is in equilibrium, all 12 unknowns.
  SceneDef s = plate(0.2, 2);
  const MaterialDef& mat = s.materials[0];
  const Mat3 D = elasticity_matrix(mat, s.plane);
  auto stress_poly = [&](const Poly u[2], Poly sig[3]) {  // σ = D ε as polynomials in (x, y)
    const Poly exx = u[0].d_xi(), eyy = u[1].d_eta(), uxy = u[0].d_eta(), uyx = u[1].d_xi();
    for (int r = 0; r < 3; ++r) {
      sig[r].degree = exx.degree;
      for (int i = 0; i < exx.size(); ++i)
        sig[r].c[i] = D(r, 0) * exx.c[i] + D(r, 1) * eyy.c[i] + D(r, 2) * (uxy.c[i] + uyx.c[i]);
    }
  };
  auto div = [&](const Poly u[2], Poly out[2]) {
    Poly sig[3];
    stress_poly(u, sig);
    const Poly a = sig[0].d_xi(), b = sig[2].d_eta(), c = sig[2].d_xi(), d = sig[1].d_eta();
    out[0] = a;
    out[1] = c;
    for (int i = 0; i < a.size(); ++i) {
      out[0].c[i] += b.c[i];
      out[1].c[i] += d.c[i];
    }
  };
  // The cubic monomials x³, x²y, xy², y³ (indices 6..9) of ux and uy.
  Eigen::MatrixXd M(4, 8);
  for (int k = 0; k < 8; ++k) {
    Poly u[2];
    u[0].degree = u[1].degree = 3;
    u[k / 4].c[6 + k % 4] = 1;
    Poly dv[2];
    div(u, dv);
    for (int dir = 0; dir < 2; ++dir)
      for (int l = 0; l < 2; ++l) M(2 * dir + l, k) = dv[dir].c[1 + l];  // x and y terms
  }
  const Eigen::MatrixXd ker = Eigen::FullPivLU<Eigen::MatrixXd>(M).kernel();
  ASSERT_EQ(ker.cols(), 4);
  Poly u[2];
  u[0].degree = u[1].degree = 3;
  const double lin[4] = {1e-7, 2e-8, -3e-8, 5e-8}, quad[6] = {2e-7, -1e-7, 3e-8, -5e-8, 1.5e-7, 4e-8};
  for (int dir = 0; dir < 2; ++dir) {
    u[dir].c[1] = lin[2 * dir];
    u[dir].c[2] = lin[2 * dir + 1];
    for (int l = 0; l < 3; ++l) u[dir].c[3 + l] = quad[3 * dir + l];
  }
  const Eigen::VectorXd cubic = 4e-8 * (ker.col(0) - 0.7 * ker.col(1) + 0.4 * ker.col(2) + ker.col(3)) /
                                ker.cwiseAbs().maxCoeff();
  for (int k = 0; k < 8; ++k) u[k / 4].c[6 + k % 4] = cubic[k];
  Poly dv[2];
  div(u, dv);
  ASSERT_LT(std::abs(dv[0].c[1]) + std::abs(dv[0].c[2]) + std::abs(dv[1].c[1]) + std::abs(dv[1].c[2]),
            1e-12 * (std::abs(dv[0].c[0]) + std::abs(dv[1].c[0])));
  s.has_gravity = true;
  s.gravity = {-dv[0].c[0] / mat.density, -dv[1].c[0] / mat.density};  // ρ g + div σ = 0

  // p_i(x): the polar forms at x_i. B2(a, x) = Σ q·(a-x blossom), B3(a, x, x) likewise.
  auto cover_field = [&](double X, double Y, int dir, double x, double y) {
    const Poly& f = u[dir];
    const double l = f.c[1] * x + f.c[2] * y;
    const double q = f.c[3] * X * x + f.c[4] * 0.5 * (X * y + Y * x) + f.c[5] * Y * y;
    const double c = f.c[6] * X * x * x + f.c[7] * (2 * X * x * y + Y * x * x) / 3 +
                     f.c[8] * (X * y * y + 2 * Y * x * y) / 3 + f.c[9] * Y * y * y;
    return l + q + c;
  };
  const Mesh m = pre::build_mesh(s, "patch3");
  TimeStepper st(m, s, "patch3");
  const CoverSpace& sp = st.view().space;
  ASSERT_EQ(sp.dofs_per_cover(), 12);
  const double h = sp.scale();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(st.view().space.unknowns());
  for (std::size_t cv = 0; cv < m.cover_count(); ++cv) {
    if (sp.basis_cover(cv) != static_cast<int>(cv)) continue;
    const double X = m.node_xy[2 * m.cover_node[cv]], Y = m.node_xy[2 * m.cover_node[cv] + 1];
    const int f = sp.first_unknown(cv);
    for (int dir = 0; dir < 2; ++dir) {
      auto p = [&](double dx, double dy) { return cover_field(X, Y, dir, X + dx * h, Y + dy * h); };
      // Basis 1, ξ, η, ξ², ξη, η² with ξ = (x − X)/h: Taylor coefficients in ξ, η.
      const double c[6] = {p(0, 0),
                           0.5 * (p(1, 0) - p(-1, 0)),
                           0.5 * (p(0, 1) - p(0, -1)),
                           0.5 * (p(1, 0) - 2 * p(0, 0) + p(-1, 0)),
                           0.25 * (p(1, 1) - p(1, -1) - p(-1, 1) + p(-1, -1)),
                           0.5 * (p(0, 1) - 2 * p(0, 0) + p(0, -1))};
      for (int j = 0; j < 6; ++j) d[f + 2 * j + dir] = c[j];
    }
  }
  std::vector<double> xy0 = st.view().state.loop_xy;
  TimeStepperProbe::impose_displacement(st, d);
  double worst_u = 0, umax = 0;
  for (std::size_t v = 0; v < xy0.size() / 2; ++v)
    for (int dir = 0; dir < 2; ++dir) {
      const double exact = u[dir](xy0[2 * v], xy0[2 * v + 1]);
      worst_u = std::max(worst_u, std::abs(st.view().state.loop_xy[2 * v + dir] - xy0[2 * v + dir] - exact));
      umax = std::max(umax, std::abs(exact));
    }
  EXPECT_LT(worst_u, 1e-8 * umax) << "the cubic field is reproduced at every loop vertex";
  Poly sig[3];
  stress_poly(u, sig);
  double worst_s = 0, smax = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e)
    for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v) {
      const double x = m.loop_xy[2 * v], y = m.loop_xy[2 * v + 1];
      const std::int32_t c0 = m.element_covers[3 * e];
      const double nx = m.node_xy[2 * m.cover_node[c0]], ny = m.node_xy[2 * m.cover_node[c0] + 1];
      const auto got = stress_at(st.view(), e, x + u[0](nx, ny), y + u[1](nx, ny));
      for (int r = 0; r < 3; ++r) {
        worst_s = std::max(worst_s, std::abs(got[r] - sig[r](x, y)));
        smax = std::max(smax, std::abs(sig[r](x, y)));
      }
    }
  EXPECT_LT(worst_s, 1e-9 * smax) << "σ = D ε(x) exactly (quadratic)";
  const auto [worst_r, interior] = interior_residual(m, sp, TimeStepperProbe::assemble_rhs(st, 1.0));
  const double scale = smax * s.mesh_size;
  EXPECT_GT(interior, 10);
  std::printf("cubic patch at n = 2: displacement error %.2e, stress error %.2e (relative), worst "
              "interior residual %.2e of σ·h over %d covers\n",
              worst_u / umax, worst_s / smax, worst_r / scale, interior);
  EXPECT_LT(worst_r, 1e-5 * scale) << "interior covers in equilibrium";
}

TEST(CoverSpace, LinearFieldIsExactAtOrderZeroAndTwo) {
  // A linear field at n = 2 (quadratic covers): constant terms u(x_i), linear terms h·∇u,
  // quadratic terms zero: uniform stress everywhere.
  for (int order : {0, 2}) {
    SceneDef s = plate(0.2, order);
    const Mesh m = pre::build_mesh(s, "patch");
    TimeStepper st(m, s, "patch");
    const CoverSpace& sp = st.view().space;
    const double exx = 1e-4, eyy = -3e-5, gxy = 5e-5, h = sp.scale();
    Eigen::VectorXd d = Eigen::VectorXd::Zero(st.view().space.unknowns());
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
    TimeStepperProbe::impose_displacement(st, d);
    const Mat3 D = elasticity_matrix(s.materials[0], s.plane);
    const Vec3 sigma = D * Vec3(exx, eyy, gxy);
    const std::vector<double> mean = mean_stress(st.view());
    for (std::size_t e = 0; e < m.element_count(); ++e)
      for (int i = 0; i < 3; ++i) ASSERT_NEAR(mean[3 * e + i], sigma[i], 1e-9 * sigma.norm()) << "element " << e;
  }
}

TEST(CoverSpace, FreeFallIsExactAtOrderOne) {
  SceneDef s;
  s.materials.push_back({"rock", 2500, 1e10, 0.25, {}});
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
  const auto u = st.view().state.measure[0].displacement();
  EXPECT_NEAR(u[1], -0.5 * 9.81 * 1.0, 1e-9 * 4.905);
  EXPECT_NEAR(u[0], 0, 1e-10);
  double smax = 0;
  for (double x : mean_stress(st.view())) smax = std::max(smax, std::abs(x));
  EXPECT_LT(smax, 1e-3) << "Pa: a falling body carries no stress";
  // Every loop vertex fell the same.
  for (std::size_t v = 1; v < st.view().state.loop_xy.size(); v += 2)
    EXPECT_NEAR(st.view().state.loop_xy[v] - m.loop_xy[v], -4.905, 1e-8);
}

TEST(CoverSpace, EnergyTermsAtOrderOneAndTwo) {
  // energy.csv at n ≥ 1 (energy.h): the strain energy of a linear in-situ field on a 2 m × 1 m
  // box, ½ ∫ σ(y)ᵀ D⁻¹ σ(y) dA (Simpson in y: exact for the quadratic integrand), and the
  // kinetic and gravity energies of a body that fell for 1 s: ½ m (g t)² and −m g·½ g t².
  for (int order : {1, 2}) {
    SceneDef s;
    s.materials.push_back({"rock", 2500, 1e10, 0.25, {}});
    BodyDef b;
    b.material = 0;
    b.outer = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
    s.bodies.push_back(b);
    s.mesh_size = 0.35;
    s.plane = PlaneKind::strain;
    s.solver.cover_order = order;
    s.insitu_stress.present = true;
    s.insitu_stress.sxx = -3e6;
    s.insitu_stress.syy = -5e6;
    s.insitu_stress.sxy = 1e6;
    s.insitu_stress.y_ref = 1;
    s.insitu_stress.gyy = -2.5e5;
    s.insitu_stress.gxx = 4e5;
    const Mesh m = pre::build_mesh(s, "energy");
    TimeStepper st(m, s, "energy");
    EnergyMeter meter(st.view().model, &st.view().space);
    const Mat3 C = elasticity_matrix(s.materials[0], s.plane).inverse();
    auto u_density = [&](double y) {  // ½ σᵀ C σ per unit area at height y
      const Vec3 sg(-3e6 + (1 - y) * 4e5, -5e6 + (1 - y) * -2.5e5, 1e6);
      return 0.5 * sg.dot(C * sg);
    };
    const double want = 2.0 * (u_density(0) + 4 * u_density(0.5) + u_density(1)) / 6;
    const EnergyRow r = meter.state_terms(st.view().state, {});
    std::printf("n = %d: strain energy %.9e J/m, exact %.9e\n", order, r.strain, want);
    EXPECT_NEAR(r.strain, want, 1e-12 * want) << "order " << order;
    EXPECT_EQ(r.kinetic, 0.0);

    s.insitu_stress.present = false;
    s.has_gravity = true;
    s.gravity = {0, -9.81};
    TimeStepper fall(m, s, "fall");
    EnergyMeter fmeter(fall.view().model, &fall.view().space);
    for (int i = 0; i < 50; ++i) fall.step(0.02);
    const EnergyRow f = fmeter.state_terms(fall.view().state, {});
    const double mass = 2500 * 2.0, v = 9.81 * 1.0;
    std::printf("n = %d: after 1 s of free fall K = %.9e, V = %.9e J/m (½mv² = %.9e)\n", order,
                f.kinetic, f.gravity, 0.5 * mass * v * v);
    EXPECT_NEAR(f.kinetic, 0.5 * mass * v * v, 1e-9 * 0.5 * mass * v * v) << "order " << order;
    EXPECT_NEAR(f.gravity, -0.5 * mass * v * v, 1e-9 * 0.5 * mass * v * v) << "order " << order;
    EXPECT_LT(std::abs(f.strain), 1e-9 * 0.5 * mass * v * v) << "order " << order;
  }
}

TEST(CoverSpace, RollersAndTractionGiveUniformStressAtOrderOneAndTwo) {
  // A 1 m × 2 m column on rollers (bottom: y held, left: x held), pressed by 1 MPa on its top:
  // σyy = −1 MPa, σxx = τxy = 0 everywhere, whatever the order (edge integrals of degree 2n + 2
  // with the (n + 2)-point Gauss rule).
  for (int order : {1, 2}) {
    SceneDef s = plate(0.3, order);
    s.plane = PlaneKind::stress;
    s.bodies[0].outer = {{0, 0}, {1, 0}, {1, 2}, {0, 2}};
    s.supports.push_back({{{-0.1, 0}, {1.1, 0}}, false, true, {}, {}});
    s.supports.push_back({{{0, -0.1}, {0, 2.1}}, true, false, {}, {}});
    TractionDef t;
    t.points = {{-0.1, 2}, {1.1, 2}};
    t.normal = -1e6;
    s.tractions.push_back(t);
    const Mesh m = pre::build_mesh(s, "column");
    TimeStepper st(m, s, "column");
    st.step(1.0);
    const std::vector<double> mean = mean_stress(st.view());
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
    for (std::size_t v = 1; v < st.view().state.loop_xy.size(); v += 2) dy = std::min(dy, st.view().state.loop_xy[v] - m.loop_xy[v]);
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
  write_checkpoint(first.view(), path);
  TimeStepper second(m, s, "ckpt");
  second.restart_from(path);
  for (int i = 0; i < 3; ++i) second.step(1e-3);
  EXPECT_EQ(state_hash(second.view()), state_hash(straight.view()));
  // The tip has moved (the run is not trivially at rest).
  double umax = 0;
  for (double u : straight.view().state.cover_u) umax = std::max(umax, std::abs(u));
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
