// Contact against known answers (issue 4): a block sliding on a 30° slope with friction, one held
// by friction, a block dropped onto a base, a stack of blocks, a crack opening only where it is.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cover_cutter.h"
#include "scene_builders.h"
#include "time_stepper.h"

namespace nmm::solve {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

// Penalty 20·E (Shi recommends 10 to 100·E): kn = 2e11 N/m, ks = kn/2.5 with E = 10 GPa.
SceneDef contact_scene(double h, double friction_deg) {
  SceneDef s;
  s.materials.push_back({"rock", 2650, 1e10, 0.25});
  JointSetDef js;
  js.name = "interface";
  js.friction_deg = friction_deg;
  js.normal.kn = 2e11;
  js.shear.ks = 8e10;
  s.joint_sets.push_back(js);
  s.interface_set = 0;
  s.mesh_size = h;
  s.has_gravity = true;
  s.gravity = {0, -kG};
  s.solver.time_step = 1e-3;
  return s;
}

using test::box;

using test::held_along;

// Runs to time t; returns the status.
std::string run_to(TimeStepper& st, double t) {
  return st.run_until(t, [](std::int64_t) {});
}

double slide_distance(double alpha_deg, double phi_deg, double t) {
  const double a = alpha_deg * kPi / 180, p = phi_deg * kPi / 180;
  return std::max(0.0, 0.5 * kG * (std::sin(a) - std::cos(a) * std::tan(p)) * t * t);
}

TEST(Contact, BlockSlidesUnderTiltedGravityAsCoulombSays) {
  // Flat base, gravity tilted by 30°: the block slides along +x.
  SceneDef s = contact_scene(0.5, 20);
  s.gravity = {kG * std::sin(30 * kPi / 180), -kG * std::cos(30 * kPi / 180)};
  s.bodies = {box(0, 0, 12, 1), box(1, 1, 3, 2)};
  s.fixed_points = held_along(0.1, 11.9, 0.1);
  s.measure_points = {{2, 1.5}};
  const Mesh m = pre::build_mesh(s, "tilted");
  TimeStepper st(m, s, "tilted");
  ASSERT_EQ(run_to(st, 1.0), "ok");
  const auto u = st.displacement_at(st.measure_points()[0]);
  const double want = slide_distance(30, 20, 1.0);
  std::printf("tilted gravity: slid %.6f m, Coulomb %.6f m (%+.4f %%), %zu iterations, %zu cuts\n",
              u[0], want, 100 * (u[0] - want) / want, st.open_close_iterations(), st.time_step_cuts());
  EXPECT_NEAR(u[0], want, 1e-3 * want);
  EXPECT_NEAR(u[1], 0, 1e-4) << "the block stays on the base";
}

TEST(Contact, BlockSlidesDownARealIncline) {
  // The base's top is a 30° incline cut by the mesh at an angle (data/block_on_incline.json).
  SceneDef s = contact_scene(0.5, 20);
  const double c = std::cos(30 * kPi / 180), sn = std::sin(30 * kPi / 180), y0 = 0.144338;
  const Vec2 p0{10 * c, 10 * sn + y0}, p1{12 * c, 12 * sn + y0};
  BodyDef base;
  base.material = 0;
  base.outer = {{0, 0}, {19.9, 0}, {19.9, 19.9 * sn / c + y0}, p1, p0, {0, y0}};
  BodyDef block;
  block.material = 0;
  block.outer = {p0, p1, {p1.x - sn, p1.y + c}, {p0.x - sn, p0.y + c}};
  s.bodies = {base, block};
  s.fixed_points = held_along(0.1, 19.8, 0.05);
  const Vec2 mid{0.5 * (p0.x + p1.x) - 0.5 * sn, 0.5 * (p0.y + p1.y) + 0.5 * c};
  s.measure_points = {mid};
  const Mesh m = pre::build_mesh(s, "incline");
  TimeStepper st(m, s, "incline");
  ASSERT_EQ(run_to(st, 1.0), "ok");
  const auto u = st.displacement_at(st.measure_points()[0]);
  const double along = -(u[0] * c + u[1] * sn), across = -u[0] * sn + u[1] * c;
  const double want = slide_distance(30, 20, 1.0);
  std::printf("real incline: slid %.6f m, Coulomb %.6f m (%+.4f %%), %zu iterations, %zu cuts\n",
              along, want, 100 * (along - want) / want, st.open_close_iterations(), st.time_step_cuts());
  EXPECT_NEAR(along, want, 1e-3 * want);
  EXPECT_NEAR(across, 0, 1e-4);
}

TEST(Contact, FrictionHoldsTheBlockWhenPhiExceedsTheSlope) {
  SceneDef s = contact_scene(0.5, 35);
  s.gravity = {kG * std::sin(30 * kPi / 180), -kG * std::cos(30 * kPi / 180)};
  s.bodies = {box(0, 0, 12, 1), box(1, 1, 3, 2)};
  s.fixed_points = held_along(0.1, 11.9, 0.1);
  s.measure_points = {{2, 1.5}};
  const Mesh m = pre::build_mesh(s, "held");
  TimeStepper st(m, s, "held");
  ASSERT_EQ(run_to(st, 1.0), "ok");
  const auto u = st.displacement_at(st.measure_points()[0]);
  std::printf("phi 35 > 30: moved %.3e m along, %.3e m across\n", u[0], u[1]);
  EXPECT_LT(std::hypot(u[0], u[1]), 1e-4);
}

TEST(Contact, DroppedBlockComesToRestOnTheBase) {
  SceneDef s = contact_scene(0.25, 30);
  s.bodies = {box(0, 0, 4, 1), box(1.5, 1.2, 2.5, 2.2)};
  s.fixed_points = {{0.2, 0.2}, {3.8, 0.2}, {2, 0.2}};
  s.measure_points = {{2, 1.7}};
  const Mesh m = pre::build_mesh(s, "drop");
  TimeStepper st(m, s, "drop");
  ASSERT_EQ(run_to(st, 1.0), "ok");
  const double y1 = st.displacement_at(st.measure_points()[0])[1];
  ASSERT_EQ(run_to(st, 1.2), "ok");
  const double y2 = st.displacement_at(st.measure_points()[0])[1];
  std::printf("dropped block: fell %.6f m, then moved %.2e m in 0.2 s; max penetration %.2e m\n",
              -y2, y2 - y1, st.max_penetration());
  EXPECT_NEAR(y2, -0.2, 1e-3) << "it lands on the base";
  EXPECT_LT(std::abs(y2 - y1), 1e-4) << "and stays there";
  EXPECT_LT(st.max_penetration(), 1e-3) << "less than 1/1000 of its size";
  double vmax = 0;
  for (double v : st.velocity()) vmax = std::max(vmax, std::abs(v));
  EXPECT_LT(vmax, 1e-2) << "m/s";
}

void stack_stands(double dynamic_factor) {
  SceneDef s = contact_scene(0.25, 30);
  s.solver.dynamic_factor = dynamic_factor;
  s.bodies = {box(0, 0, 4, 0.5)};
  for (int i = 0; i < 6; ++i) s.bodies.push_back(box(1.5, 0.5 + 0.5 * i, 2.5, 1.0 + 0.5 * i));
  s.fixed_points = {{0.2, 0.2}, {3.8, 0.2}, {2, 0.2}};
  s.measure_points = {{2, 3.25}};
  const Mesh m = pre::build_mesh(s, "stack");
  TimeStepper st(m, s, "stack");
  ASSERT_EQ(run_to(st, 1.0), "ok");
  const auto u = st.displacement_at(st.measure_points()[0]);
  std::printf("stack of 6 (dynamic factor %g): top moved %.3e, %.3e m; %zu cuts\n", dynamic_factor,
              u[0], u[1], st.time_step_cuts());
  EXPECT_LT(std::abs(u[0]), 1e-5);
  EXPECT_LT(std::abs(u[1]), 1e-4);
}

TEST(Contact, StackOfBlocksStandsDynamic) { stack_stands(1.0); }
TEST(Contact, StackOfBlocksStandsQuasiStatic) { stack_stands(0.0); }

TEST(Contact, CrackOpensOnlyWhereTheJointIs) {
  // A cantilever clamped at x = 0 with a crack from its top face down to mid-depth at x = 1,
  // static. A downward tip load puts the top in tension: the crack opens, while below its tip
  // the body stays whole (the two points 6 cm apart there differ by the material's strain only).
  // An upward load closes the crack: its faces press on each other and barely overlap.
  for (double sign : {-1.0, 1.0}) {
    SceneDef s = contact_scene(0.125, 30);
    s.has_gravity = false;
    s.bodies = {box(0, 0, 4, 1)};
    s.joints.push_back({0, {{1, 1.2}, {1, 0.5}}});
    s.solver.dynamic = false;
    s.solver.static_mode = StaticMode::equilibrium;  // a continuum held by fixed points
    for (int i = 0; i <= 8; ++i) s.fixed_points.push_back({0, i / 8.0});
    s.loads.push_back({{4, 0.5}, {0, sign * 1e5}});
    s.measure_points = {{0.97, 0.95}, {1.03, 0.95}, {0.97, 0.2}, {1.03, 0.2}};
    const Mesh m = pre::build_mesh(s, "crack");
    TimeStepper st(m, s, "crack");
    ASSERT_EQ(run_to(st, 3e-3), "ok");
    const auto& mp = st.measure_points();
    const double open_top = st.displacement_at(mp[1])[0] - st.displacement_at(mp[0])[0];
    const double open_low = st.displacement_at(mp[3])[0] - st.displacement_at(mp[2])[0];
    std::printf("crack, load %+g: top opens by %.3e m, below the tip %.3e m, penetration %.2e m\n",
                sign, open_top, open_low, st.max_penetration());
    if (sign < 0) {
      EXPECT_GT(open_top, 1e-4) << "the crack opens at the top";
      EXPECT_GT(open_top, 20 * std::abs(open_low)) << "and only where it is";
    } else {
      EXPECT_LT(st.max_penetration(), 1e-6) << "the closed crack's faces must not overlap";
      EXPECT_LT(std::abs(open_top), 1e-4) << "without contact they would pass through each other";
    }
  }
}

}  // namespace
}  // namespace nmm::solve
