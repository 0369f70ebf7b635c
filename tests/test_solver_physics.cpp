// The continuum solver against known answers: patch test, cantilever (Timoshenko), free fall,
// first vibration period of a cantilever (Euler–Bernoulli with the first-mode constant).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "reference/cantilever.h"
#include "solver/stepping/time_stepper_probe.h"
#include "preprocess/cover_cutter.h"
#include "common/error.h"
#include "solver/discretisation/form.h"
#include "solver/discretisation/model.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {
namespace {

using reference::beam;
using reference::clamp_left_end;

TEST(SolverPhysics, PatchTestUniformStressIsExact) {
  // A pentagon cut at odd angles by the mesh, and a linear displacement field u = E·x imposed on
  // every cover: each element must carry exactly σ = D·ε, and every cover away from the boundary
  // must be in equilibrium (no net internal force), cut elements included.
  SceneDef s = beam(1, 1, 0.15);
  s.bodies[0].outer = {{0.03, 0.01}, {1.71, 0.13}, {1.93, 1.07}, {0.87, 1.61}, {-0.21, 0.93}};
  s.plane = PlaneKind::strain;
  s.solver.dynamic = false;  // no inertia: the residual is the internal force alone
  s.solver.static_mode = StaticMode::equilibrium;
  const Mesh m = pre::build_mesh(s, "patch");
  TimeStepper st(m, s, "patch");
  const double exx = 1e-4, eyy = -3e-5, gxy = 5e-5;
  Eigen::VectorXd d(st.view().space.unknowns());
  for (std::size_t c = 0; c < m.cover_count(); ++c) {
    const double x = m.node_xy[2 * m.cover_node[c]], y = m.node_xy[2 * m.cover_node[c] + 1];
    d[2 * c] = exx * x + 0.5 * gxy * y;
    d[2 * c + 1] = eyy * y + 0.5 * gxy * x;
  }
  TimeStepperProbe::impose_displacement(st, d);
  const Mat3 D = elasticity_matrix(s.materials[0], s.plane);
  const Vec3 sigma = D * Vec3(exx, eyy, gxy);
  for (std::size_t e = 0; e < m.element_count(); ++e)
    for (int i = 0; i < 3; ++i)
      ASSERT_NEAR(st.view().state.stress[3 * e + i], sigma[i], 1e-9 * sigma.norm()) << "element " << e;
  // Covers whose star lies wholly inside the body: no net force.
  std::vector<char> touches_boundary(m.cover_count(), 0);
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    bool cut = false;
    for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v)
      cut |= (m.loop_edge_origin[v] & kEdgeBoundary) != 0;
    if (cut)
      for (int k = 0; k < 3; ++k) touches_boundary[m.element_covers[3 * e + k]] = 1;
  }
  const Eigen::VectorXd& r = TimeStepperProbe::assemble_rhs(st, 1.0);
  const double scale = sigma.norm() * s.mesh_size;  // force of σ over one element side, N
  int interior = 0;
  for (std::size_t c = 0; c < m.cover_count(); ++c) {
    if (touches_boundary[c]) continue;
    ++interior;
    EXPECT_NEAR(r[2 * c], 0, 1e-10 * scale);
    EXPECT_NEAR(r[2 * c + 1], 0, 1e-10 * scale);
  }
  EXPECT_GT(interior, 20);
}

// The cantilever of reference/cantilever.h at mesh size h: tip deflection's error against
// Timoshenko's.
double cantilever_tip_error(double h, double* tip_out = nullptr, int order = 0) {
  const SceneDef s = reference::cantilever(h, order);
  const Mesh m = pre::build_mesh(s, "cantilever");
  TimeStepper st(m, s, "cantilever");
  st.step(1.0);
  const double tip = -st.view().state.measure[0].displacement()[1];
  const double theory = reference::timoshenko_tip_deflection();
  if (tip_out) *tip_out = tip;
  return (tip - theory) / theory;
}

TEST(SolverPhysics, CantileverConvergesToTimoshenko) {
  // Constant-strain elements are too stiff in bending: the tip deflection approaches the
  // Timoshenko value from below as the mesh is refined.
  double prev = -1;
  for (double h : {0.5, 0.25, 0.125}) {
    double tip = 0;
    const double err = cantilever_tip_error(h, &tip);
    std::printf("cantilever h = %-6g tip = %.6e m  error = %+.2f %%\n", h, tip, 100 * err);
    EXPECT_LT(err, 0.0) << "h = " << h;
    EXPECT_GT(std::abs(prev), std::abs(err)) << "the error must fall as h falls, h = " << h;
    prev = err;
  }
  // −2.4 % at h = H/8; plane strain instead of plane stress would add another −6 %.
  EXPECT_LT(std::abs(prev), 0.04);
}

TEST(SolverPhysics, CantileverAtCoverOrderOne) {
  // Linear cover functions (6 unknowns per cover) give a quadratic field per element: bending
  // within 0.5 % of Timoshenko at h = 0.25, where constant covers are −8.9 % off.
  for (double h : {0.5, 0.25}) {
    double tip = 0;
    const double err = cantilever_tip_error(h, &tip, 1);
    std::printf("cantilever n = 1 h = %-6g tip = %.6e m  error = %+.3f %%\n", h, tip, 100 * err);
    if (h == 0.25) {
      EXPECT_LT(std::abs(err), 0.005);
    }
  }
}

// The cantilever with its load spread as a uniform shear traction over the end x = L and its
// clamp a support along x = 0 (no point force: the 2D field has no singularity under the load),
// measured at (L, H/2). Returns the error against Timoshenko.
double cantilever_traction_error(double h, int order, double* tip_out = nullptr) {
  const double L = 10, H = 1, P = 1e5;
  SceneDef s = beam(L, H, h);
  s.solver.cover_order = order;
  s.supports.push_back({{{0, -0.1}, {0, H + 0.1}}, true, true, {}, {}});
  TractionDef t;
  t.points = {{L, H + 0.1}, {L, -0.1}};  // direction −y: a positive shear pushes down
  t.shear = P / H;
  s.tractions.push_back(t);
  s.measure_points.push_back({L, H / 2});
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::equilibrium;
  const Mesh m = pre::build_mesh(s, "cantilever");
  TimeStepper st(m, s, "cantilever");
  st.step(1.0);
  const double tip = -st.view().state.measure[0].displacement()[1];
  const MaterialDef& mat = s.materials[0];
  const double I = H * H * H / 12, G = mat.young / (2 * (1 + mat.poisson));
  const double theory = P * L * L * L / (3 * mat.young * I) + P * L / (5.0 / 6.0 * G * H);
  if (tip_out) *tip_out = tip;
  return (tip - theory) / theory;
}

TEST(SolverPhysics, CantileverWithEndTractionAcrossOrders) {
  // With the point load of CantileverAtCoverOrderOne the 2D displacement under the load is
  // logarithmically unbounded, so richer spaces drift above beam theory there (n = 2: +0.66 %
  // at h = 0.25); spread over the end, every order ≥ 1 sits on Timoshenko (the 2D clamped beam
  // is 0.06 % stiffer), while n = 0 is −8.8 % at h = 0.25.
  double tip[3][2] = {};
  for (int order : {0, 1, 2})
    for (int i = 0; i < 2; ++i) {
      const double h = i == 0 ? 0.5 : 0.25;
      const double err = cantilever_traction_error(h, order, &tip[order][i]);
      std::printf("traction cantilever n = %d h = %-5g tip = %.6e m  error = %+.3f %%\n", order, h,
                  tip[order][i], 100 * err);
      if (order >= 1) {
        EXPECT_LT(std::abs(err), 0.002) << "n = " << order << ", h = " << h;
      } else {
        EXPECT_LT(err, -0.05) << "constant covers are too stiff in bending";
      }
    }
  // n = 2 at h = 0.5 already agrees with n = 1 and n = 2 at h = 0.25 within 0.1 %.
  EXPECT_NEAR(tip[2][0] / tip[2][1], 1.0, 1e-3);
  EXPECT_NEAR(tip[1][1] / tip[2][1], 1.0, 1e-3);
}

TEST(SolverPhysics, FreeFallIsExact) {
  // An unconstrained body under gravity: Shi's scheme integrates constant acceleration exactly,
  // s = ½ g t², v = g t, with no strain.
  SceneDef s = beam(2, 1, 0.4);
  s.has_gravity = true;
  s.gravity = {0, -9.81};
  s.measure_points.push_back({1, 0.5});
  const Mesh m = pre::build_mesh(s, "fall");
  TimeStepper st(m, s, "fall");
  const double dt = 0.01;
  for (int i = 0; i < 100; ++i) st.step(dt);
  const double t = st.view().state.time;
  EXPECT_NEAR(t, 1.0, 1e-12);
  const auto u = st.view().state.measure[0].displacement();
  EXPECT_NEAR(u[1], -0.5 * 9.81 * t * t, 1e-9 * 4.905);
  EXPECT_NEAR(u[0], 0, 1e-10);
  for (std::size_t i = 1; i < st.view().state.velocity.size(); i += 2) EXPECT_NEAR(st.view().state.velocity[i], -9.81, 1e-9);
  double smax = 0;
  for (double x : st.view().state.stress) smax = std::max(smax, std::abs(x));
  EXPECT_LT(smax, 1e-3) << "Pa: a falling body carries no stress";
  const auto eff = run_effects(st.view());
  EXPECT_EQ(eff, (std::vector<std::string>{"elasticity", "inertia", "gravity"}));
}

TEST(SolverPhysics, FormHoldsOnlyTheTermsTheSceneCallsFor) {
  // The form (form.h) is built once from the model with the integrators the scene calls for,
  // and its assembly at rest is the body's weight: Σ_a ∫ρ b φ_a dA = ρ b A (the shape functions
  // are a partition of unity), with no inertia or spring force while nothing has moved.
  SceneDef s = beam(2, 1, 0.4);
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::equilibrium;
  clamp_left_end(s, 1, 0.4);
  const Mesh m = pre::build_mesh(s, "form");
  EXPECT_EQ(Form(Model(m, s, "form")).names(),
            (std::vector<std::string>{"elasticity", "initial_stress", "fixed_points"}));
  s.solver.dynamic = true;
  s.has_gravity = true;
  s.gravity = {0.5, -9.81};
  s.loads.push_back({{2, 0.5}, {0, -1e3}});
  const Model model(m, s, "form");
  EXPECT_EQ(Form(model).names(), (std::vector<std::string>{"elasticity", "initial_stress", "body_force",
                                                          "inertia", "fixed_points", "point_loads"}));
  s.loads.clear();
  TimeStepper st(m, s, "form");
  const Eigen::VectorXd& r = TimeStepperProbe::assemble_rhs(st, 0.01);
  double fx = 0, fy = 0;
  for (Eigen::Index i = 0; i < r.size(); i += 2) {
    fx += r[i];
    fy += r[i + 1];
  }
  const double weight = s.materials[0].density * 2 * 1;  // kg per m of thickness
  EXPECT_NEAR(fx, weight * 0.5, 1e-9 * weight * 9.81);
  EXPECT_NEAR(fy, -weight * 9.81, 1e-9 * weight * 9.81);
}

TEST(SolverPhysics, CantileverFirstPeriodMatchesBeamTheory) {
  // Tip load applied suddenly: the tip oscillates about its static deflection in (mostly) the
  // first mode. Euler–Bernoulli: ω1 = (1.8751)²·√(EI / (ρ A L⁴)).
  const double L = 10, H = 1, h = 0.125;
  SceneDef s = beam(L, H, h);
  clamp_left_end(s, H, h);
  s.loads.push_back({{L, H / 2}, {0, -1e5}});
  s.measure_points.push_back({L, H / 2});
  const MaterialDef& mat = s.materials[0];
  const double omega = 1.8751 * 1.8751 * std::sqrt(mat.young * H * H * H / 12 / (mat.density * H * L * L * L * L));
  const double T = 2 * std::acos(-1.0) / omega;
  const Mesh m = pre::build_mesh(s, "vibration");
  TimeStepper st(m, s, "vibration");
  const double dt = T / 400;
  std::vector<double> uy;
  for (int i = 0; i < 1000; ++i) {
    st.step(dt);
    uy.push_back(st.view().state.measure[0].displacement()[1]);
  }
  // Period from the times of the successive maxima of the tip's upward displacement.
  std::vector<double> peaks;
  for (std::size_t i = 1; i + 1 < uy.size(); ++i)
    if (uy[i] > uy[i - 1] && uy[i] >= uy[i + 1]) {
      // Parabola through the three samples for a sub-step peak time.
      const double a = uy[i - 1], b = uy[i], c = uy[i + 1];
      const double off = 0.5 * (a - c) / (a - 2 * b + c);
      peaks.push_back((static_cast<double>(i) + 1 + off) * dt);
    }
  ASSERT_GE(peaks.size(), 2u);
  const double measured = (peaks.back() - peaks.front()) / static_cast<double>(peaks.size() - 1);
  std::printf("first period: beam theory %.5f s, NMM %.5f s (%+.2f %%)\n", T, measured,
              100 * (measured - T) / T);
  // −0.5 % at h = H/8, Δt = T/400; a lumped or doubled mass would be off by far more.
  EXPECT_NEAR(measured, T, 0.02 * T);
}

TEST(SolverPhysics, StaticRunWithoutSupportStopsWithReason) {
  SceneDef s = beam(2, 1, 0.4);
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::equilibrium;  // K d = F: no mass term to hold it
  s.fixed_points.push_back({0, 0});
  const Mesh m = pre::build_mesh(s, "free");
  TimeStepper st(m, s, "free");
  const Outcome o = st.attempt(1.0);
  EXPECT_EQ(o.code, StopCode::unconstrained) << o;
  EXPECT_EQ(st.view().state.step, 0) << "the state stays as it was";
  // The reason names the block a user must hold.
  EXPECT_NE(o.reason.find("block 0"), std::string::npos) << o;
  EXPECT_THROW(st.step(1.0), RunError);
}

TEST(SolverPhysics, PointOutsideTheBodyIsBadInput) {
  SceneDef s = beam(2, 1, 0.4);
  s.fixed_points.push_back({5, 5});
  const Mesh m = pre::build_mesh(s, "t");
  try {
    TimeStepper st(m, s, "scene");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "/fixed_points/0");
  }
}

TEST(SolverPhysics, SymbolicAnalysisOnlyOnce) {
  SceneDef s = beam(2, 1, 0.4);
  s.has_gravity = true;
  s.gravity = {0, -9.81};
  const Mesh m = pre::build_mesh(s, "t");
  TimeStepper st(m, s, "t");
  for (int i = 0; i < 5; ++i) st.step(1e-3);
  EXPECT_EQ(st.view().system.analyses(), 1u);
  EXPECT_GT(st.view().timings.factorisation, 0.0);
}

}  // namespace
}  // namespace nmm::solve
