// Step control (solver/stepping/step_control.h): a step that would fold an element's triangle
// over is rejected before it is accepted and cut like one that moved too far, and the run goes
// on. Before 2026-11-30 the fold was found only at the next attempt's start, in the accepted
// state, and stopped the run (element_folded, cured by no shorter step).
//
// The strip below (10 m × 0.1 m, pinned at both ends' mid-depth, P = 0.01·E·H at mid-span) in
// DDA static steps: a step of 1 s is nearly the linear static answer, whose bending strain at
// mid-span, ε = 1.5·(P/EH)·(L/H) = 1.5, folds triangles there; a step of 0.3 s is held back by
// the inertia term 2M/Δt² and folds none. (Its sag is no answer to check: steps this long
// carry the strip tens of metres in linearised increments. What is checked is step control.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/outcome.h"
#include "preprocess/cover_cutter.h"
#include "reference/cantilever.h"
#include "solver/discretisation/configuration.h"
#include "solver/stepping/step_control.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {
namespace {

constexpr double kL = 10, kH = 0.1, kMesh = 0.05, kYoung = 1e9;  // m, m, m, Pa

SceneDef strip() {
  SceneDef s = reference::beam(kL, kH, kMesh);
  s.materials[0].young = kYoung;
  s.fixed_points.push_back({0, kH / 2});
  s.fixed_points.push_back({kL, kH / 2});
  s.loads.push_back({{kL / 2, kH / 2}, {0, -0.01 * kYoung * kH}});
  s.measure_points.push_back({kL / 2, kH / 2});
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::dda;
  s.solver.time_step = 1;
  return s;
}

// m², twice the signed area of element e's triangle of cover nodes xy.
double twice_area(const Mesh& m, std::size_t e, const std::vector<double>& xy) {
  const std::int32_t* c = &m.element_covers[3 * e];
  const double ax = xy[2 * c[1]] - xy[2 * c[0]], ay = xy[2 * c[1] + 1] - xy[2 * c[0] + 1];
  const double bx = xy[2 * c[2]] - xy[2 * c[0]], by = xy[2 * c[2] + 1] - xy[2 * c[0] + 1];
  return ax * by - ay * bx;
}

TEST(StepControl, FoldedByFindsTheTriangleANodeIsMovedAcross) {
  // One cover's node moved along the normal of its opposite edge: at 0.999 of its distance to
  // that edge no triangle folds, at 1.001 that triangle does. A rigid translation of 10 h and a
  // linearised rotation of 0.5 rad (the triangle maps by I + θJ, det 1 + θ²) fold none.
  const SceneDef s = strip();
  const Mesh m = pre::build_mesh(s, "strip");
  TimeStepper st(m, s, "strip");
  const std::vector<double>& xy = st.view().state.cover_xy;
  Configuration config(m, &st.view().space);
  ASSERT_EQ(config.place(xy), -1);
  const int n = st.view().space.unknowns();
  ASSERT_EQ(static_cast<std::size_t>(n), xy.size()) << "order 0: two unknowns per cover, its node's motion";
  // An element inside the strip with three distinct covers.
  const std::size_t e = m.element_count() / 2;
  const std::int32_t* c = &m.element_covers[3 * e];
  const double ex = xy[2 * c[2]] - xy[2 * c[1]], ey = xy[2 * c[2] + 1] - xy[2 * c[1] + 1];
  const double len = std::hypot(ex, ey);
  const double dist = twice_area(m, e, xy) / len;  // m, from node c0 to the line c1–c2
  ASSERT_GT(dist, 0);
  const double nx = ey / len, ny = -ex / len;  // towards the edge c1–c2 from c0's side
  for (const double f : {0.999, 1.001}) {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
    d[2 * c[0]] = f * dist * nx;
    d[2 * c[0] + 1] = f * dist * ny;
    const std::int64_t folded = config.folded_by(d);
    if (f < 1)
      EXPECT_EQ(folded, -1) << "moved " << f << " of the way";
    else
      EXPECT_EQ(folded, static_cast<std::int64_t>(e)) << "moved " << f << " of the way";
  }
  Eigen::VectorXd shift(n), turn(n);
  for (int i = 0; i < n; i += 2) {
    shift[i] = 10 * kMesh;
    shift[i + 1] = -10 * kMesh;
    turn[i] = -0.5 * (xy[i + 1] - kH / 2);
    turn[i + 1] = 0.5 * (xy[i] - kL / 2);
  }
  EXPECT_EQ(config.folded_by(shift), -1);
  EXPECT_EQ(config.folded_by(turn), -1);
}

TEST(StepControl, StepThatFoldsAnElementIsCutAndTheRunGoesOn) {
  const SceneDef s = strip();
  const Mesh m = pre::build_mesh(s, "strip");
  {
    // The attempt of a full step is rejected, the state left as it was, and a shorter step
    // may cure it.
    TimeStepper st(m, s, "strip");
    const std::vector<double> xy = st.view().state.cover_xy;
    const Outcome o = st.attempt(1.0);
    EXPECT_EQ(o.code, StopCode::element_folded) << o;
    EXPECT_TRUE(cured_by_shorter_step(o.code));
    EXPECT_NE(o.reason.find("would fold element"), std::string::npos) << o;
    EXPECT_EQ(st.view().state.step, 0);
    EXPECT_EQ(st.view().state.cover_xy, xy) << "a rejected attempt moves nothing";
  }
  // The run: its first step is cut to 0.3 s and the run reaches its end, every accepted state
  // with every triangle the right way round.
  TimeStepper st(m, s, "strip");
  std::int64_t steps = 0;
  bool unfolded = true;
  const Outcome o = st.run_until(2.0, [&](std::int64_t k) {
    steps = k;
    for (std::size_t e = 0; e < m.element_count(); ++e)
      unfolded = unfolded && twice_area(m, e, st.view().state.cover_xy) > 0;
  });
  ASSERT_TRUE(o.ok()) << o;
  EXPECT_NEAR(st.view().state.time, 2.0, 1e-12);
  EXPECT_GE(st.view().state.cuts, 1u);
  EXPECT_GT(steps, 2);
  EXPECT_TRUE(unfolded);
  // Mid-span moved down, and not sideways: the strip, its pins and its load are symmetric.
  const auto u = st.view().state.measure[0].displacement();
  EXPECT_LT(u[1], 0);
  EXPECT_NEAR(u[0], 0, 1e-6);
}

// The penetration rule on the numbers alone (g2 = 1e-3, w0 = 1 m: g2·w0 = 1 mm, cap 2 mm, a
// contact at or past it may sink 0.01 mm, detection's reach 2.5 mm). A contact carried past the
// cap that sinks by round-off is no reason to cut (before 2026-11-30 it stopped uniaxial h
// 0.0625 m dynamic at the step floor: "a contact penetrated 0.00201 m, more than the 0.002 m
// allowed"); one that sinks in earnest past the cap is, and so is any that reaches the reach.
StepPenetration deepened(double start, double end) { return {end - std::max(start, 0.0), end, start, end}; }

TEST(StepControl, AContactPastTheCapIsJudgedByHowFarTheStepSinksIt) {
  SolverDef solver;
  solver.time_step = 1e-3;
  solver.max_displacement_ratio = 1e-3;
  const StepControl control(solver, 1.0, solver.time_step);
  const double g2w0 = 1e-3;
  ASSERT_DOUBLE_EQ(control.penetration_cap(), 2 * g2w0);
  const auto judge = [&](double start, double end) { return control.rejection(0, deepened(start, end), true); };
  // Within the cap: Shi's rule on what the step adds.
  EXPECT_TRUE(judge(0, 0.9 * g2w0).ok());
  EXPECT_EQ(judge(0, 1.1 * g2w0).code, StopCode::penetration);
  EXPECT_TRUE(judge(1.5 * g2w0, 1.99 * g2w0).ok());
  // Deepened past the cap from well under it: cut, as before.
  const Outcome crossed = judge(1.5 * g2w0, 2.1 * g2w0);
  EXPECT_EQ(crossed.code, StopCode::penetration);
  EXPECT_NE(crossed.reason.find("a contact penetrated 0.0021 m, more than the 0.002 m allowed"), std::string::npos)
      << crossed;
  // Started past the cap (the stopping case's 2.01 mm) and sank by round-off, or by less than
  // 0.01·g2·w0: accepted. With the cap alone (p ≤ 2·g2·w0) both were rejected at every Δt.
  EXPECT_TRUE(judge(2.01e-3, 2.01e-3 + 1e-15).ok());
  EXPECT_TRUE(judge(2.01e-3, 2.01e-3 + 0.9e-5).ok());
  // Started just under the cap: it may end 0.01·g2·w0 below its start, not more.
  EXPECT_TRUE(judge(1.999e-3, 2.005e-3).ok());
  EXPECT_EQ(judge(1.999e-3, 2.011e-3).code, StopCode::penetration);
  // Sinking in earnest past the cap: cut (a shorter step sinks it less).
  const Outcome sinking = judge(2.1e-3, 2.13e-3);
  EXPECT_EQ(sinking.code, StopCode::penetration);
  EXPECT_TRUE(cured_by_shorter_step(sinking.code));
  EXPECT_NE(sinking.reason.find("sank 3e-05 m in it, more than the 1e-05 m allowed"), std::string::npos) << sinking;
  // However slowly, not past contact detection's reach 2.5·g2·w0: a contact sunk that far stops
  // the run at the floor instead of being lost.
  const Outcome lost = judge(2.4995e-3, 2.5005e-3);
  EXPECT_EQ(lost.code, StopCode::penetration);
  EXPECT_NE(lost.reason.find("past the 0.0025 m contact detection follows"), std::string::npos) << lost;
  // A contact the step lets come up is judged by nothing, however deep.
  EXPECT_TRUE(control.rejection(0, {0, 0, 0, 0}, true).ok());
}

}  // namespace
}  // namespace nmm::solve
