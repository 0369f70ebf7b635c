// Static analysis (docs/solver.md, "Static analysis"): `"dynamic": false` is DDA's static
// analysis — every step from rest with the inertia term kept — so block systems held only by
// contacts settle; the pure equilibrium solve K d = F is static_mode "equilibrium".
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/ended_ok.h"
#include "preprocess/cover_cutter.h"
#include "reference/brick_wall.h"
#include "reference/scene_pieces.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {
namespace {

TEST(StaticAnalysis, BrickWallSettlesInDdaStaticMode) {
  // 10 × 10 staggered bricks on a held base, static: every step from rest. Before, the first
  // step stopped with "not positive definite" (bricks held only by contacts, no mass term).
  // The wall settles onto its contacts within the first steps; afterwards its top barely
  // moves, and no bed joint opens.
  SceneDef s = reference::brick_wall(10, false);
  s.measure_points = {{5.0, 4.75}, {1.25, 4.75}, {9.25, 4.75}};
  const Mesh m = pre::build_mesh(s, "wall");
  TimeStepper st(m, s, "wall");
  EXPECT_EQ(run_effects(st.view())[1], "static_inertia");
  ASSERT_PRED1(test::ended_ok, st.run_until(0.05, [](std::int64_t) {}));
  std::vector<std::array<double, 2>> at50;
  for (const TrackedPoint& p : st.view().state.measure) at50.push_back(p.displacement());
  const std::size_t it50 = st.view().state.iterations;
  ASSERT_PRED1(test::ended_ok, st.run_until(0.1, [](std::int64_t) {}));
  double more = 0;
  for (std::size_t i = 0; i < at50.size(); ++i) {
    const auto u = st.view().state.measure[i].displacement();
    more = std::max(more, std::hypot(u[0] - at50[i][0], u[1] - at50[i][1]));
  }
  // Bed joints: contacts on a row boundary y = 0.5·k, away from the wall's ends (the end brick
  // of every other row overhangs by half its length and may tip by a few µm).
  double max_bed_gap = -1;
  std::size_t bed = 0, bed_open = 0;
  for (const Contact& c : st.view().contacts.contacts()) {
    const double y = st.view().state.loop_xy[2 * c.at.vertex + 1];
    const double x = st.view().state.loop_xy[2 * c.at.vertex];
    if (std::abs(2 * y - std::round(2 * y)) > 2e-3 || y < 0.25 || y > 4.75 || x < 1 || x > 9)
      continue;
    ++bed;
    if (c.state == ContactState::open) ++bed_open;
    max_bed_gap = std::max(max_bed_gap, c.gap);
  }
  const auto top = st.view().state.measure[0].displacement();
  std::printf("static wall 10x10: top settled by %.3e m; moved %.3e m more in steps 51-100; "
              "largest bed-joint gap %.3e m over %zu contacts (%zu open); %.2f iterations per step after "
              "step 50, %zu cuts\n",
              top[1], more, max_bed_gap, bed, bed_open, (st.view().state.iterations - it50) / 50.0,
              st.view().state.cuts);
  EXPECT_LT(top[1], 0) << "the wall settles under its weight";
  EXPECT_LT(more, 1e-3) << "m: the wall has settled";
  // No bed joint opens: no gap reaches 10 µm. (About 1 µm is reached: faces resting at zero
  // force sit within the opening tolerance f0·w0 = 2e-7·6 m = 1.2 µm of each other, and some of
  // those contacts are judged "open" at zero force; that is the contact model's tolerance, not
  // a separation.)
  EXPECT_LT(max_bed_gap, 1e-5) << "m: no bed joint opens";
  EXPECT_GT(bed, 100u);
}

TEST(StaticAnalysis, EquilibriumModeStillNeedsFixedPoints) {
  // K d = F has no mass term: a brick held by nothing (1 m above the base, no contact) is free,
  // and the solve says so instead of returning garbage.
  SceneDef s = reference::brick_wall(1, false);
  s.bodies[1] = reference::box(0, 1, 1, 1.5);
  s.solver.static_mode = StaticMode::equilibrium;
  const Mesh m = pre::build_mesh(s, "drop");
  TimeStepper st(m, s, "drop");
  const Outcome why = st.run_until(1e-3, [](std::int64_t) {});
  EXPECT_EQ(why.code, StopCode::unconstrained) << why;
  EXPECT_NE(why.reason.find("not positive definite"), std::string::npos) << why;
}

TEST(StaticAnalysis, EquilibriumModeHoldsBricksOnTheirTouchingContacts) {
  // Bricks resting on touching contacts with friction are held by them: in the first inner solve
  // their contacts stick (the elastic predictor, contact_problem.h set_elastic_predictor), then friction
  // takes its strength from the normal force. Before, no contact was closed at the start, the
  // shear springs had no strength, and this wall stopped with "not positive definite".
  SceneDef s = reference::brick_wall(2, false);
  s.solver.static_mode = StaticMode::equilibrium;
  s.measure_points = {{1.0, 0.99}};
  const Mesh m = pre::build_mesh(s, "wall");
  TimeStepper st(m, s, "wall");
  // One step: the equilibrium. (Later steps start from its states; a brick whose contacts all
  // slid into the step has no shear tangent at the kink and no mass to hold it, and such a step
  // can still be singular: a mechanism, which equilibrium mode reports rather than solves.)
  ASSERT_PRED1(test::ended_ok, st.run_until(1e-3, [](std::int64_t) {}));
  std::size_t sliding = 0;
  for (const Contact& c : st.view().contacts.contacts()) sliding += c.state == ContactState::sliding;
  std::printf("2 x 2 wall, equilibrium: %zu contacts, %zu sliding\n", st.view().contacts.contacts().size(), sliding);
  const auto u = st.view().state.measure[0].displacement();
  EXPECT_LT(std::hypot(u[0], u[1]), 1e-5) << "m: the wall stands on its springs";
  std::size_t open = 0;
  for (const Contact& c : st.view().contacts.contacts())
    if (c.state == ContactState::open && c.gap < 0) ++open;
  EXPECT_EQ(open, 0u) << "no overlapping contact is left open";
}

TEST(StaticAnalysis, FreeBlockFallsAtMostHalfGDtSquaredPerStep) {
  // A brick alone above the base, static DDA: each step starts from rest, so under gravity it
  // moves by exactly ½·g·Δt² per step (the inertia term, no velocity carried) until it lands.
  SceneDef s = reference::brick_wall(1, false);
  s.bodies[1] = reference::box(0, 1, 1, 1.5);  // 1 m above the base
  s.measure_points = {{0.5, 1.25}};
  const Mesh m = pre::build_mesh(s, "drop");
  TimeStepper st(m, s, "drop");
  ASSERT_PRED1(test::ended_ok, st.run_until(0.01, [](std::int64_t) {}));
  const double uy = st.view().state.measure[0].displacement()[1];
  const double per_step = 0.5 * 9.81 * 1e-3 * 1e-3;
  EXPECT_NEAR(uy, -10 * per_step, 1e-3 * 10 * per_step) << "m after 10 static steps";
}

}  // namespace
}  // namespace nmm::solve
