// The contact solve's force tolerance (solver.contact_tolerance, docs/contact.md "Tolerance and
// error"): a looser tolerance costs fewer Newton iterations and leaves the sliding block on
// Coulomb's answer; what the tolerance allowed is reported in forces and in gap. The residual a
// dynamic step leaves is handed on to its blocks (block_momentum.h). What the tolerance lets the
// solve skip: CG stops once every unknown is within it, and a few touching contacts outside the
// sparse pattern are left to CG rather than grown into it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tests/ended_ok.h"
#include "preprocess/cover_cutter.h"
#include "common/math_constants.h"
#include "reference/brick_wall.h"
#include "reference/joint_specimen.h"
#include "reference/scene_pieces.h"
#include "reference/sliding_block.h"
#include "solver/stepping/block_momentum.h"
#include "solver/contact/contact_solve.h"
#include "solver/stepping/equilibrium_indicator.h"
#include "solver/stepping/restart.h"
#include "solver/stepping/time_stepper.h"
#include "solver/stepping/time_stepper_probe.h"

namespace nmm::solve {
namespace {

struct Slide {
  double along = 0;         ///< m, slide of the block's centre after 1 s
  long newton = 0;          ///< Newton iterations of the run
  double force_tol = 0;     ///< N, largest F_tol used
  double gap_error = 0;     ///< m, largest F_tol/kn
  double max_force = 0;     ///< N, largest contact force at the end
  double u_error = 0;       ///< m, largest estimated displacement error of an accepted step
  long checks = 0;          ///< displacement estimates made
};

Slide slide(double tau) {
  // The sliding block of the contact tests: gravity tilted 30°, φ = 20°, kn = 2e11 N/m.
  SceneDef s = reference::sliding_block_tilted(30, 20);
  s.solver.contact_tolerance = tau;
  const Mesh m = pre::build_mesh(s, "tilted");
  TimeStepper st(m, s, "tilted");
  EXPECT_PRED1(test::ended_ok, st.run_until(1.0, [](std::int64_t) {}));
  Slide r;
  r.along = st.view().state.measure[0].displacement()[0];
  r.newton = st.view().contact_solve.newton;
  r.force_tol = st.view().contact_solve.max_force_tolerance;
  r.gap_error = st.view().contact_solve.max_gap_error;
  r.u_error = st.view().contact_solve.max_displacement_error;
  r.checks = st.view().contact_solve.displacement_checks;
  for (const Contact& c : st.view().contacts.contacts())
    r.max_force = std::max({r.max_force, std::abs(c.normal_force), std::abs(c.shear_force)});
  return r;
}

TEST(ContactTolerance, LooserIsCheaperAndStaysOnCoulomb) {
  const double want = reference::sliding_distance(30, 20, 1.0);
  const Slide tight = slide(1e-8), loose = slide(1e-3);
  std::printf("tau 1e-8: slid %.6f m (%+.4f %%), %ld Newton; tau 1e-3: slid %.6f m (%+.4f %%), %ld Newton\n",
              tight.along, 100 * (tight.along - want) / want, tight.newton, loose.along,
              100 * (loose.along - want) / want, loose.newton);
  // Both on Coulomb's answer within the contact tests' 0.1 %, and on each other within 0.01 %.
  EXPECT_NEAR(tight.along, want, 1e-3 * want);
  EXPECT_NEAR(loose.along, want, 1e-3 * want);
  EXPECT_NEAR(loose.along, tight.along, 1e-4 * want);
  // The tolerance is what the loop stops on: the loose run needs clearly fewer iterations.
  EXPECT_LT(loose.newton, 0.8 * tight.newton);
  // Reported: F_tol = τ × the largest contact force (the block's weight share on a corner, a few
  // 10 kN), and F_tol/kn with kn = 2e11 N/m.
  EXPECT_GT(loose.force_tol, 0.5e-3 * loose.max_force);
  EXPECT_LT(loose.force_tol, 2e-3 * loose.max_force);
  EXPECT_NEAR(loose.gap_error, loose.force_tol / 2e11, 1e-3 * loose.force_tol / 2e11);
  // A constant spring's error is bounded by F_tol/kn (above): no displacement test is made.
  EXPECT_EQ(loose.checks, 0);
  EXPECT_EQ(loose.u_error, 0);
  // τ = 1e-8 is 1e-5 of the loose one, but the tolerance has a round-off floor (1e-12 of the
  // largest load, here the inertia term): still far below.
  EXPECT_LT(tight.force_tol, 1e-4 * loose.force_tol);
}

TEST(ContactTolerance, ASofteningJointIsCheckedInDisplacement) {
  // The joint of the seed paper's direct shear (hyperbolic shear, Rf = 0.9) loaded to 90 % of
  // its strength: its tangent is (1 − 0.9·0.9)² = 3.6 % of Ksi, so F_tol moves it 28 times as far
  // as on its initial stiffness. The solve must check the displacement, refuse iterates over
  // 3e-4·τ·w0, and accept none over it.
  SceneDef s = reference::joint_specimen_scene(reference::seed_shear_joint(), 5e11, 0.25);
  reference::load_joint_specimen(s, 5e6, 0.9 * 5e6 * std::tan(30 * kPi / 180));
  s.solver.contact_tolerance = 1e-3;
  const Mesh m = pre::build_mesh(s, "joint");
  TimeStepper st(m, s, "joint");
  ASSERT_PRED1(test::ended_ok, st.run_until(0.1, [](std::int64_t) {}));
  const ContactSolveStats& cs = st.view().contact_solve;
  const double u_tol = displacement_tolerance(1e-3, st.view().model.w0());
  std::printf("checks %ld, refused %ld, largest accepted %.3e m, tolerance %.3e m\n", cs.displacement_checks,
              cs.displacement_refusals, cs.max_displacement_error, u_tol);
  EXPECT_GT(cs.displacement_checks, 0);
  EXPECT_GT(cs.displacement_refusals, 0) << "the force test alone would have stopped short here";
  EXPECT_GT(cs.max_displacement_error, 0);
  EXPECT_LE(cs.max_displacement_error, u_tol);
}

// The DDA code's brick wall (bricks 1 m × 0.5 m, φ = 30°, Δt = 1 ms), n × n bricks meshed at
// h = 2 m, coarser than its bricks, and a stepper on one thread.
struct PeerWall {
  PeerWall(int n, bool dynamic)
      : scene(reference::peer_wall(n, n, dynamic, 2.0)), mesh(pre::build_mesh(scene, "wall")),
        st(mesh, scene, "wall") {
    st.set_threads(1);
  }
  const SceneDef scene;
  const Mesh mesh;
  TimeStepper st;
};

// The friction fixed point settles: a barely touching contact's strength falls to zero along a
// ramp below F_tol (contact_problem.cpp update_strengths), not in one jump at F_tol. With the jump,
// contacts whose normal force hovered around the cut cycled — zero strength lets a brick slide,
// which lifts N above the cut, whose strength holds the brick, which drops N below it — and 4 of
// the first 100 steps of this wall (11 of the 20 × 20 one's) used all 12 strength rounds and
// were taken with friction still moving; up to 19 Newton iterations in a step.
TEST(ContactTolerance, FrictionSettlesInEveryStepOfAVibratingWall) {
  // The dynamic 10 × 10 wall, its first 100 steps.
  PeerWall w(10, true);
  TimeStepper& st = w.st;
  ASSERT_PRED1(test::ended_ok, st.run_until(100 * w.scene.solver.time_step, [](std::int64_t) {}));
  const auto& state = st.view().state;
  std::printf("dynamic 10 x 10 wall: %llu steps, %llu Newton iterations, %llu with friction unsettled\n",
              static_cast<unsigned long long>(state.step), static_cast<unsigned long long>(state.iterations),
              static_cast<unsigned long long>(state.friction_unsettled));
  EXPECT_EQ(state.friction_unsettled, 0u) << "steps taken with friction strengths still moving";
  EXPECT_EQ(st.view().contact_solve.unsettled, 0L);
}

TEST(ContactTolerance, SparsePatternLeavesOnlyAFewTouchingContactsToCg) {
  // The dynamic 10 × 10 wall again: its vibrating bricks reach new pairs of elements in most
  // steps. The pattern waits to grow while at most 5 (and at most 1 %) of the touching contacts
  // lie outside it (time_stepper.cpp update_pattern); their springs are taken by CG. Every step
  // keeps to that bound, some steps do leave contacts to CG, and the wall's symbolic analyses
  // are fewer than its steps that met a new pair.
  PeerWall w(10, true);
  TimeStepper& st = w.st;
  std::size_t worst_excess = 0, steps_leaving = 0;
  ASSERT_PRED1(test::ended_ok, st.run_until(100 * w.scene.solver.time_step,
                         [&](std::int64_t) {
                           const ContactSet& c = st.view().contacts;
                           const std::size_t outside =
                               TimeStepperProbe::contact_problem(st).outside_pattern().touching;
                           const auto allowed = static_cast<std::size_t>(
                               std::min(5.0, 0.01 * static_cast<double>(c.touching_at_start())));
                           worst_excess = std::max(worst_excess, outside > allowed ? outside - allowed : 0);
                           steps_leaving += outside > 0;
                         }));
  std::printf("dynamic 10 x 10 wall: %zu of 100 steps left touching contacts to CG, %zu analyses\n",
              steps_leaving, st.view().system.analyses());
  EXPECT_EQ(worst_excess, 0u) << "a step left more touching contacts outside the pattern than allowed";
  EXPECT_GT(steps_leaving, 0u) << "the pattern grew at every new pair";
  EXPECT_LT(st.view().system.analyses(), 60u);  // 88 in 100 steps with growth at every new pair
  EXPECT_EQ(st.view().state.friction_unsettled, 0u);
}

TEST(ContactTolerance, RestartWithContactsOutsideThePatternIsBitwise) {
  // The same wall, 40 steps straight against 20 + checkpoint + 20 from a fresh stepper, with
  // the checkpoint taken while touching contacts lie outside the pattern: the restarted run
  // rebuilds the same pattern from the checkpoint and leaves the same contacts to CG.
  PeerWall w(10, true);
  const SceneDef& s = w.scene;
  const Mesh& m = w.mesh;
  const double dt = s.solver.time_step;
  const auto advance = [dt](TimeStepper& st, int steps) {
    for (int i = 0; i < steps; ++i) ASSERT_PRED1(test::ended_ok, st.attempt(dt)) << "step " << i;
  };
  TimeStepper& straight = w.st;
  advance(straight, 40);
  TimeStepper first(m, s, "wall");
  first.set_threads(1);
  int at = 0;  // the first step after 20 that ends with touching contacts outside the pattern
  for (advance(first, 20), at = 20; TimeStepperProbe::contact_problem(first).outside_pattern().touching == 0 && at < 35; ++at)
    advance(first, 1);
  ASSERT_GT(TimeStepperProbe::contact_problem(first).outside_pattern().touching, 0u) << "no step left contacts to CG";
  const std::string path = ::testing::TempDir() + "/wall_outside_pattern.nmmstate";
  write_checkpoint(first.view(), path);
  TimeStepper second(m, s, "wall");
  second.set_threads(1);
  second.restart_from(path);
  advance(second, 40 - at);
  std::printf("wall restart at step %d with %zu touching contacts outside the pattern\n", at,
              TimeStepperProbe::contact_problem(first).outside_pattern().touching);
  EXPECT_EQ(state_hash(second.view()), state_hash(straight.view()));
  EXPECT_EQ(second.view().state.step, 40);
}

TEST(ContactTolerance, SettlingWallKeepsItsFactorisation) {
  // The DDA code's 20 × 20 wall in static analysis, meshed coarser than its bricks, its first
  // 100 steps. A step near balance needs a direction that leaves every unknown within F_tol, the
  // accepted step's own test; CG on the kept factorisation gives that in a few iterations. When
  // CG had to bring the residual's 2-norm over all unknowns below 0.3·F_tol instead, it spent its
  // budget there and a factorisation followed: 0.39 per step against 0.20 (kDirectionBalance).
  PeerWall w(20, false);
  TimeStepper& st = w.st;
  ASSERT_PRED1(test::ended_ok, st.run_until(100 * w.scene.solver.time_step, [](std::int64_t) {}));
  const ContactSolveStats& cs = st.view().contact_solve;
  const double steps = static_cast<double>(st.view().state.step);
  std::printf("static 20 x 20 wall: %.0f steps, %.2f solves, %.2f factorisations, %.2f CG iterations per step\n",
              steps, static_cast<double>(cs.newton) / steps, static_cast<double>(cs.factorisations) / steps,
              static_cast<double>(cs.cg_iterations) / steps);
  EXPECT_EQ(steps, 100.0);
  EXPECT_LE(static_cast<double>(cs.factorisations) / steps, 0.3);
}

TEST(ContactTolerance, ASinglePrecisionFactorGivesItsDirectionsByCgAndTheSameWall) {
  // The static 10 × 10 wall, its first 30 steps, with its factor in double and in single
  // precision (which the largest runs keep: system_matrix.h). After a factorisation the single
  // factor's direction is CG's on it, to the forcing term as every other direction, not a solve
  // refined to round-off (contact_solve.cpp): no refinement pass (7 before), and every brick
  // where the double run puts it.
  PeerWall dbl(10, false), sgl(10, false);
  TimeStepperProbe::set_single_precision(sgl.st, 1);
  const double t = 30 * dbl.scene.solver.time_step;
  ASSERT_PRED1(test::ended_ok, dbl.st.run_until(t, [](std::int64_t) {}));
  ASSERT_PRED1(test::ended_ok, sgl.st.run_until(t, [](std::int64_t) {}));
  const SystemMatrix& k = sgl.st.view().system;
  ASSERT_TRUE(k.single_precision());
  EXPECT_FALSE(dbl.st.view().system.single_precision());
  const ContactSolveStats &a = dbl.st.view().contact_solve, &b = sgl.st.view().contact_solve;
  std::printf("static 10 x 10 wall, 30 steps: double %ld Newton, %ld CG, %ld factorisations; single %ld, %ld, %ld, "
              "%zu refinement passes\n",
              a.newton, a.cg_iterations, a.factorisations, b.newton, b.cg_iterations, b.factorisations,
              k.single_refinements());
  EXPECT_GT(b.factorisations, 0);
  EXPECT_EQ(k.single_refinements(), 0u);
  // Where the covers are: the largest difference against the largest displacement of the run.
  const std::vector<double>&x0 = dbl.st.view().state.cover_xy, &x1 = sgl.st.view().state.cover_xy;
  const TimeStepper fresh(dbl.mesh, dbl.scene, "wall");
  const std::vector<double>& start = fresh.view().state.cover_xy;
  ASSERT_EQ(x0.size(), x1.size());
  double off = 0, moved = 0;
  for (std::size_t i = 0; i < x0.size(); ++i) {
    off = std::max(off, std::abs(x1[i] - x0[i]));
    moved = std::max(moved, std::abs(x0[i] - start[i]));
  }
  // The paths part by round-off and the friction fixed point lands elsewhere within its
  // tolerance: 0.9 % of the largest displacement (1.1 % with the refined directions before).
  std::printf("largest displacement %.3e m, largest difference %.3e m\n", moved, off);
  EXPECT_GT(moved, 1e-4);
  EXPECT_LT(off, 2e-2 * moved);
}

TEST(BlockMomentum, SpreadsEachBlocksForceAndMomentByMassAndGetsThemBack) {
  // The sliding block's mesh at cover order 1: the block and its base, each of many covers.
  const SceneDef s = reference::sliding_block_tilted(30, 20, 0.5, 1);
  const Mesh m = pre::build_mesh(s, "tilted");
  const TimeStepper st(m, s, "tilted");
  const CoverSpace& space = st.view().space;
  const std::vector<double>& xy = st.view().state.cover_xy;
  const EquilibriumIndicator indicator(m, s, space);
  const BlockMomentum momentum(m, space, indicator.group_mass());
  ASSERT_EQ(m.block_count(), 2u);
  const std::vector<double>& mass = indicator.group_mass();
  const auto dpc = static_cast<std::size_t>(space.dofs_per_cover());
  // A cover of each group, and the whole model's centre of mass (both blocks together).
  std::vector<std::size_t> cover(mass.size());
  for (std::size_t c = 0; c < m.cover_count(); ++c)
    cover[static_cast<std::size_t>(space.first_unknown(c)) / dpc] = c;
  double total = 0, cx = 0, cy = 0;
  for (std::size_t g = 0; g < mass.size(); ++g) {
    total += mass[g];
    cx += mass[g] * xy[2 * cover[g]];
    cy += mass[g] * xy[2 * cover[g] + 1];
  }
  cx /= total;
  cy /= total;
  // A body force g on every cover's constant coefficients: each block's net force is its mass × g
  // and its moment about its own centre of mass 0.
  Eigen::VectorXd r = Eigen::VectorXd::Zero(space.unknowns());
  for (std::size_t g = 0; g < mass.size(); ++g) {
    r[static_cast<Eigen::Index>(g * dpc)] = 3 * mass[g];
    r[static_cast<Eigen::Index>(g * dpc + 1)] = -2 * mass[g];
    r[static_cast<Eigen::Index>(g * dpc + 2)] = 1e3;  // a linear term: not a rigid motion
  }
  std::vector<double> f;
  momentum.net_forces(r, 0.5, xy, f);
  ASSERT_EQ(f.size(), 6u);
  EXPECT_NEAR(f[0] + f[3], 0.5 * 3 * total, 1e-12 * total);
  EXPECT_NEAR(f[1] + f[4], -0.5 * 2 * total, 1e-12 * total);
  EXPECT_NEAR(f[0] / f[1], -1.5, 1e-12);
  EXPECT_NEAR(f[2], 0.0, 1e-9 * total);
  EXPECT_NEAR(f[5], 0.0, 1e-9 * total);
  // Spread back by mass: the same body force, and the same net forces once summed again.
  Eigen::VectorXd back = Eigen::VectorXd::Zero(space.unknowns());
  momentum.add_forces(f, xy, back);
  std::vector<double> again;
  momentum.net_forces(back, 1.0, xy, again);
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_NEAR(again[i], f[i], 1e-9 * total);
  for (std::size_t g = 0; g < mass.size(); ++g) {
    EXPECT_NEAR(back[static_cast<Eigen::Index>(g * dpc)], 0.5 * 3 * mass[g], 1e-9 * mass[g]);
    EXPECT_EQ(back[static_cast<Eigen::Index>(g * dpc + 2)], 0.0);
  }
  // An angular acceleration ω about the model's centre: forces m_g·ω ẑ × (x_g − c). Each block
  // gets the moment ω·Σ m_g·(x_g − c)·(x_g − x_b) and the force of its centre's acceleration;
  // spread back and summed again, both return.
  r.setZero();
  for (std::size_t g = 0; g < mass.size(); ++g) {
    r[static_cast<Eigen::Index>(g * dpc)] = -7 * mass[g] * (xy[2 * cover[g] + 1] - cy);
    r[static_cast<Eigen::Index>(g * dpc + 1)] = 7 * mass[g] * (xy[2 * cover[g]] - cx);
  }
  momentum.net_forces(r, 1.0, xy, f);
  EXPECT_GT(std::abs(f[2]) + std::abs(f[5]), 0.0);
  back.setZero();
  momentum.add_forces(f, xy, back);
  momentum.net_forces(back, 1.0, xy, again);
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_NEAR(again[i], f[i], 1e-9 * (std::abs(f[i]) + total));
  // The rotation is spread as a rigid angular acceleration: the same forces as r where r is one.
  const double scale = r.cwiseAbs().maxCoeff();
  for (std::size_t g = 0; g < mass.size(); ++g)
    for (std::size_t d = 0; d < 2; ++d) {
      const auto i = static_cast<Eigen::Index>(g * dpc + d);
      EXPECT_NEAR(back[i], r[i], 1e-6 * scale);
    }
}

TEST(BlockMomentum, OnlyADynamicStepThatIteratedHandsAForceOn) {
  SceneDef s = reference::sliding_block_tilted(30, 20);
  const Mesh m = pre::build_mesh(s, "tilted");
  {
    TimeStepper st(m, s, "tilted");
    ASSERT_PRED1(test::ended_ok, st.run_until(0.02, [](std::int64_t) {}));
    const std::vector<double>& f = st.view().state.block_force;
    ASSERT_EQ(f.size(), 3 * m.block_count());
    double largest = 0;
    for (std::size_t b = 0; b < m.block_count(); ++b) largest = std::max({largest, std::abs(f[3 * b]), std::abs(f[3 * b + 1])});
    // Within the tolerance: at most F_tol on each of the block's unknowns, summed.
    const double f_tol = st.view().contact_solve.max_force_tolerance;
    std::printf("largest handed-on force %.3e N/m, F_tol %.3e N/m\n", largest, f_tol);
    EXPECT_GT(largest, 0.0);
    EXPECT_LT(largest, static_cast<double>(st.view().space.unknowns()) * f_tol);
  }
  s.solver.dynamic = false;  // DDA static: the next step starts at rest, nothing to hand on
  TimeStepper st(m, s, "tilted");
  ASSERT_PRED1(test::ended_ok, st.run_until(0.02, [](std::int64_t) {}));
  EXPECT_TRUE(st.view().state.block_force.empty());
}

}  // namespace
}  // namespace nmm::solve
