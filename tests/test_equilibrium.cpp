// Equilibrium indicators (solver/stepping/equilibrium_indicator.cpp, docs/solver.md "Equilibrium
// indicators"): the unbalanced force ratio and largest velocity against the sliding block's
// closed form, the verdict for blocks that slide and blocks that rest, dynamic and static, and
// solver.stop_at_ratio.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/ended_ok.h"
#include "preprocess/cover_cutter.h"
#include "common/math_constants.h"
#include "common/ring_geometry.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {
namespace {

// The block on a 30° incline of friction φ, data/block_on_incline.json (its base 100 times
// stiffer than the block, so that the base does not ring and the block's motion is all there
// is): a = g (sin α − cos α tan φ) down the slope while it slides.
struct Incline {
  SceneDef scene;
  Mesh mesh;
  double accel = 0;          // m/s², the closed form (0: it holds)
  double block_fraction = 0; // –, block mass over the model's (one density)
};

/// The scene of a file under the source tree.
SceneDef scene_file(const std::string& relative) {
  const std::string path = std::string(NMM_SOURCE_DIR) + "/" + relative;
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), path);
}

Incline incline(double friction_deg, bool dynamic) {
  Incline c;
  c.scene = scene_file("data/block_on_incline.json");
  c.scene.joint_sets[0].friction_deg = friction_deg;
  c.scene.solver.dynamic = dynamic;
  c.mesh = pre::build_mesh(c.scene, "incline");
  const double a = 30 * kPi / 180, phi = friction_deg * kPi / 180;
  c.accel = std::max(0.0, 9.81 * (std::sin(a) - std::cos(a) * std::tan(phi)));
  const double block = ring_area(c.scene.bodies[1].outer);
  c.block_fraction = block / (block + ring_area(c.scene.bodies[0].outer));
  EXPECT_NEAR(block, 2.0, 1e-5) << "m², the 2 m × 1 m block";
  return c;
}

/// The sliding block (φ = 20°) after `t` s: its indicators and the closed-form mean ratio.
struct Sliding {
  EquilibriumSample e;
  double mean_expected = 0;  // –
  double accel = 0;          // m/s²
};
Sliding slide(bool dynamic, double t) {
  Incline c = incline(20, dynamic);
  TimeStepper st(c.mesh, c.scene, "incline");
  EXPECT_PRED1(test::ended_ok, st.run_until(t, [](std::int64_t) {}));
  const double expected = c.block_fraction * c.accel / 9.81;
  std::printf("sliding block (%s): mean ratio %.6g (closed form %.6g), max %.4g, velocity %.5g m/s\n",
              dynamic ? "dynamic" : "static", st.view().equilibrium.mean_ratio, expected,
              st.view().equilibrium.max_ratio, st.view().equilibrium.max_velocity);
  return {st.view().equilibrium, expected, c.accel};
}

TEST(Equilibrium, SlidingBlockIsMovingWithTheClosedFormsRatioAndVelocity) {
  // Dynamic, φ = 20° on 30°: a = 1.813 m/s². The out-of-balance force of the block's covers is
  // its mass times a, so Σ_c R_c = m_block·a, while F_ref·N = the weight of the whole model:
  //   mean ratio = (m_block / m_model)·(a / g),   largest velocity = a·t.
  // A ratio taken from the velocity, from the consistent-mass residual of the whole system or
  // against the block's weight alone would miss both by far more than 1 %.
  const Sliding r = slide(true, 0.3);
  EXPECT_NEAR(r.e.mean_ratio, r.mean_expected, 0.01 * r.mean_expected);
  EXPECT_NEAR(r.e.max_velocity, r.accel * 0.3, 0.01 * r.accel * 0.3);
  EXPECT_GT(r.e.max_ratio, 0.1) << "a cover of the block carries about its weight × a/g";
  EXPECT_EQ(equilibrium_verdict(r.e, true)["verdict"], "moving");
}

TEST(Equilibrium, SlidingBlockIsMovingInStaticAnalysisToo) {
  // Static DDA: every step starts from rest and moves the block by ½ a Δt², so 2 M d / Δt² is
  // again m·a: the same mean ratio, and the verdict "moving" although velocities are reset.
  const Sliding r = slide(false, 0.05);
  EXPECT_NEAR(r.e.mean_ratio, r.mean_expected, 0.02 * r.mean_expected);
  EXPECT_EQ(equilibrium_verdict(r.e, false)["verdict"], "moving");
}

TEST(Equilibrium, BlockHeldByFrictionIsAtRestDynamicAndStatic) {
  // φ = 40° > 30°: the block holds. After the first steps settle it onto its contacts, the
  // ratio falls far below UDEC's 1e-5 and no cover moves.
  for (bool dynamic : {true, false}) {
    Incline c = incline(40, dynamic);
    TimeStepper st(c.mesh, c.scene, "incline");
    ASSERT_PRED1(test::ended_ok, st.run_until(0.1, [](std::int64_t) {}));
    const EquilibriumSample& e = st.view().equilibrium;
    std::printf("held block (%s): max ratio %.3g, mean %.3g, velocity %.3g m/s\n",
                dynamic ? "dynamic" : "static", e.max_ratio, e.mean_ratio, e.max_velocity);
    EXPECT_LT(e.max_ratio, 1e-5);
    EXPECT_LT(e.max_velocity, RestCriterion::kVelocity);
    EXPECT_EQ(equilibrium_verdict(e, dynamic)["verdict"], "at_rest");
  }
}

TEST(Equilibrium, StopAtRatioEndsAStaticRunAtTheFirstStepBelowIt) {
  Incline c = incline(40, false);
  c.scene.solver.stop_at_ratio = 1e-6;
  TimeStepper st(c.mesh, c.scene, "incline");
  std::vector<double> ratios;
  ASSERT_PRED1(test::ended_ok, st.run_until(1.0, [&](std::int64_t) { ratios.push_back(st.view().equilibrium.max_ratio); }));
  std::printf("stop_at_ratio 1e-6: stopped after %zu steps at ratio %.3g\n", ratios.size(), ratios.back());
  EXPECT_TRUE(st.view().stopped_at_ratio);
  ASSERT_GE(ratios.size(), 2u);
  EXPECT_LT(ratios.size(), 100u) << "stopped early (the run asked for 1000 steps)";
  EXPECT_LT(ratios.back(), 1e-6);
  for (std::size_t i = 0; i + 1 < ratios.size(); ++i) EXPECT_GE(ratios[i], 1e-6) << "step " << i + 1;
  EXPECT_LT(st.view().state.time, 0.1);
}

TEST(Equilibrium, EquilibriumModeMeasuresTheForceEachSolveBalanced) {
  // static_mode "equilibrium" has no mass: R = K·d, the force the step's solve balanced. The
  // hanging column's first step balances its whole weight from a stress-free start, so
  // Σ_c |R_c| = Σ_c m_c g = N·F_ref: mean ratio 1 (the gravity load ρ g ∫ w_c dA is the lumped
  // mass times g). Later steps only correct for the geometry the first one moved: at rest.
  SceneDef scene = scene_file("tests/cli/hanging_column.json");
  scene.solver.dynamic = false;
  scene.solver.static_mode = StaticMode::equilibrium;
  const Mesh mesh = pre::build_mesh(scene, "column");
  TimeStepper st(mesh, scene, "column");
  std::vector<EquilibriumSample> steps;
  ASSERT_PRED1(test::ended_ok, st.run_until(4 * scene.solver.time_step, [&](std::int64_t) { steps.push_back(st.view().equilibrium); }));
  ASSERT_EQ(steps.size(), 4u);
  std::printf("hanging column, equilibrium mode: mean ratio %.9f at step 1, max ratio %.3g at step 4\n",
              steps[0].mean_ratio, steps[3].max_ratio);
  EXPECT_NEAR(steps[0].mean_ratio, 1.0, 1e-6);
  EXPECT_LT(steps[3].max_ratio, 1e-5);
  EXPECT_EQ(equilibrium_verdict(steps[3], false)["verdict"], "at_rest");
}

TEST(Equilibrium, ADynamicRunIsJudgedByVelocityAStaticOneByRatio) {
  // No unbalanced force but a velocity (sliding at constant speed): moving in a dynamic run, at
  // rest by the static rule (where a velocity d/Δt comes with an unbalanced force).
  EquilibriumSample s;
  s.measured = true;
  s.max_ratio = 0;
  s.max_velocity = 0.3;
  EXPECT_FALSE(at_rest(s, true));
  EXPECT_TRUE(at_rest(s, false));
  // Elastic ringing: inertia forces but covers barely moving (as the jointed slope at 1 s).
  s.max_ratio = 1.3e-4;
  s.max_velocity = 7.7e-5;
  EXPECT_TRUE(at_rest(s, true));
  EXPECT_FALSE(at_rest(s, false));
  EXPECT_EQ(equilibrium_verdict(EquilibriumSample{}, true)["verdict"], "unknown");
}

}  // namespace
}  // namespace nmm::solve
