// Rock-engineering set-ups against known answers (issue 12): a plate on rollers under uniform
// tractions carries exactly the uniform stress; an in-situ stressed model whose boundary
// tractions match the field does not move; a circular opening excavated in elastic rock under
// hydrostatic and K0 = 0.5 in-situ stress against Kirsch (errors fall with refinement); restart
// from a state in memory is bitwise exact; a gradual excavation releases its traction in steps.
#include <gtest/gtest.h>

#include <cmath>
#include <chrono>
#include <cstdio>

#include "tests/ended_ok.h"
#include "preprocess/cover_cutter.h"
#include "solver/contact/contact_history.h"
#include "common/error.h"
#include "studies/kirsch_opening.h"
#include "reference/kirsch.h"
#include "reference/scene_pieces.h"
#include "solver/stepping/time_stepper.h"
#include "common/time_table.h"
#include "common/math_constants.h"

#include <fstream>

namespace nmm::solve {
namespace {

using reference::kirsch_radial_displacement;
using reference::KirschSetup;
using reference::kKirschPoisson;
using reference::kKirschPressure;
using reference::kKirschYoung;
using studies::kirsch_wall;
using studies::KirschWall;

SceneDef rock_scene(double h) {
  SceneDef s;
  s.materials.push_back({"rock", 2500, 1e10, 0.25, {}});
  s.mesh_size = h;
  s.plane = PlaneKind::strain;
  return s;
}

TractionDef traction(std::vector<Vec2> pts, double normal, double shear) {
  TractionDef t;
  t.points = std::move(pts);
  t.normal = normal;
  t.shear = shear;
  return t;
}

SupportDef support(std::vector<Vec2> pts, bool x, bool y) {
  SupportDef d;
  d.points = std::move(pts);
  d.fix_x = x;
  d.fix_y = y;
  return d;
}

TEST(RockSetups, PlateOnRollersUnderTractionCarriesTheUniformStressExactly) {
  // 3 m × 2 m plate on rollers along its left side (x held) and its base (y held), −4 MPa on
  // the top and −1.5 MPa on the right side: every element, cut or not, must carry σxx = −1.5 MPa,
  // σyy = −4 MPa, τ = 0 to round-off (the rollers' penalty gives way uniformly: a rigid shift).
  SceneDef s = rock_scene(0.37);
  s.bodies = {reference::box(0, 0, 3, 2)};
  s.supports = {support({{0, 2}, {0, 0}}, true, false), support({{0, 0}, {3, 0}}, false, true)};
  s.tractions = {traction({{0, 2}, {3, 2}}, -4e6, 0), traction({{3, 0}, {3, 2}}, -1.5e6, 0)};
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::equilibrium;  // K d = F: the elastic answer in one step
  const Mesh m = pre::build_mesh(s, "plate");
  TimeStepper st(m, s, "plate");
  st.step(1.0);
  double err = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    err = std::max(err, std::abs(st.view().state.stress[3 * e] + 1.5e6));
    err = std::max(err, std::abs(st.view().state.stress[3 * e + 1] + 4e6));
    err = std::max(err, std::abs(st.view().state.stress[3 * e + 2]));
  }
  std::printf("plate on rollers: largest stress error %.3e Pa of 4e6 Pa (%zu elements)\n", err,
              m.element_count());
  EXPECT_LT(err, 1e-8 * 4e6);
}

// The in-situ field of a 10 m × 8 m model under gravity: σ0 at the top plus the overburden
// gradient and K0 = 0.5, tractions from the field all round.
SceneDef insitu_box(double h) {
  SceneDef s = rock_scene(h);
  s.bodies = {reference::box(0, 0, 10, 8)};
  s.has_gravity = true;
  s.gravity = {0, -9.81};
  s.insitu_stress.present = true;
  s.insitu_stress.sxx = -3e6;
  s.insitu_stress.syy = -5e6;
  s.insitu_stress.sxy = 1e6;
  s.insitu_stress.y_ref = 8;
  s.insitu_stress.gyy = -2500 * 9.81;
  s.insitu_stress.gxx = 0.5 * s.insitu_stress.gyy;
  TractionDef t;
  t.points = {{0, 0}, {10, 0}, {10, 8}, {0, 8}, {0, 0}};
  t.from_insitu = true;
  s.tractions = {t};
  return s;
}

// Largest displacement of any point of the rock (loop vertices) in one step, over `steps` steps,
// m. The displacement field, not the cover coefficients: at cover order n ≥ 1 the coefficients
// have a null space that moves no point (docs/higher-order-covers.md).
double largest_step_motion(TimeStepper& st, int steps) {
  double worst = 0;
  for (int i = 0; i < steps; ++i) {
    const std::vector<double> before = st.view().state.loop_u;
    st.step(1e-3);
    for (std::size_t k = 0; k < before.size(); ++k)
      worst = std::max(worst, std::abs(st.view().state.loop_u[k] - before[k]));
  }
  return worst;
}

TEST(RockSetups, InsituStressWithMatchingTractionsStaysStill) {
  // At every cover order: n = 0 takes the field at each element's centroid, n ≥ 1 holds the
  // linear field exactly in its stress polynomials (insitu_stress.h); either way the internal
  // forces balance the boundary tractions and gravity to round-off. The elastic displacement
  // scale of the field is σ·L/E = 5e6·10/1e10 = 5e-3 m.
  SceneDef s = insitu_box(0.45);
  s.solver.time_step = 1e-3;
  const Mesh m = pre::build_mesh(s, "insitu");
  for (int order : {0, 1, 2}) {
    s.solver.cover_order = order;
    s.tractions[0].from_insitu = true;
    TimeStepper st(m, s, "insitu");
    const double worst = largest_step_motion(st, order == 0 ? 20 : 5);
    std::printf("in-situ box, n = %d: largest displacement in one step %.3e m\n", order, worst);
    EXPECT_LT(worst, 1e-12) << "order " << order;
    // A wrong traction (the field without its gradient) does move it: the test can fail.
    s.tractions[0].from_insitu = false;
    s.tractions[0].normal = -5e6;
    TimeStepper moved(m, s, "insitu");
    EXPECT_GT(largest_step_motion(moved, 1), 1e-7) << "order " << order;
  }
}

TEST(RockSetups, InsituStressOnRollersStaysStill) {
  // The same field without shear (rollers take none) on rollers along the left side and the
  // base, the field's traction on the top and the right side: the supports start carrying the
  // in-situ reaction, so nothing moves (without that the rollers would first give way by
  // σ/k_s ≈ 2e-6 m). At every cover order.
  SceneDef s = insitu_box(0.45);
  s.insitu_stress.sxy = 0;
  s.tractions[0].points = {{0, 8}, {10, 8}, {10, 0}};
  s.supports = {support({{0, 0}, {0, 8}}, true, false), support({{0, 0}, {10, 0}}, false, true)};
  const Mesh m = pre::build_mesh(s, "rollers");
  for (int order : {0, 1, 2}) {
    s.solver.cover_order = order;
    TimeStepper st(m, s, "rollers");
    const double worst = largest_step_motion(st, order == 0 ? 20 : 5);
    std::printf("in-situ box on rollers, n = %d: largest displacement in one step %.3e m\n", order, worst);
    EXPECT_LT(worst, 1e-12) << "order " << order;
  }
}

// Kirsch (reference/kirsch.h: the scene and the closed form; studies/kirsch_opening.h: the
// wall read-off), quarter model with rollers, outer sides at b = 20a loaded by the in-situ traction, the core a second
// body excavated at the start of a static run and released at once.
struct KirschErrors {
  double hoop = 0;    ///< RMS error of σθ at the centroids of the wall elements / max |σθ(a)|
  double radial = 0;  ///< RMS error of u_r at the wall vertices / max |u_r(a)|
  std::size_t elements = 0;
};

SceneDef kirsch_scene(double h, double k0, double b_over_a) {
  KirschSetup k;
  k.h = h;
  k.k0 = k0;
  k.b_over_a = b_over_a;
  return reference::kirsch_scene(k);
}

KirschErrors kirsch_case(double h, double k0, double b_over_a) {
  KirschSetup k;
  k.h = h;
  k.k0 = k0;
  k.b_over_a = b_over_a;
  const SceneDef s = reference::kirsch_scene(k);
  const Mesh m = pre::build_mesh(s, "kirsch");
  TimeStepper st(m, s, "kirsch");
  st.step(1.0);
  const KirschWall w = kirsch_wall(k, m, st);
  return {w.hoop_centroid, w.radial, m.element_count()};
}

void kirsch_convergence(double k0) {
  std::vector<KirschErrors> errs;
  for (double h : {0.4, 0.2, 0.1}) {
    errs.push_back(kirsch_case(h, k0, 20));
    std::printf("Kirsch K0 = %.2f, h = a·%.2f: %zu elements, hoop stress RMS error %.2f %%, radial "
                "displacement RMS error %.2f %%\n",
                k0, h, errs.back().elements, 100 * errs.back().hoop, 100 * errs.back().radial);
  }
  for (std::size_t i = 1; i < errs.size(); ++i) {
    EXPECT_LT(errs[i].hoop, errs[i - 1].hoop) << "hoop stress error must fall with refinement";
    EXPECT_LT(errs[i].radial, errs[i - 1].radial) << "displacement error must fall with refinement";
  }
  // Measured (b = 20a): hoop 30 → 13 → 5.2 % (K0 = 1), 23 → 10 → 4.4 % (K0 = 0.5): first order,
  // as constant-stress elements beside a wall with a 1/r² gradient must be; radial displacement
  // 4.2 → 0.9 → 0.09 % and 3.0 → 0.6 → 0.23 % (the model's finite size, b = 20a, adds ~0.1 %).
  EXPECT_LT(errs.back().hoop, 0.06);
  EXPECT_LT(errs.back().radial, 0.005);
}

TEST(RockSetups, ExcavatedOpeningMatchesKirschHydrostatic) { kirsch_convergence(1.0); }
TEST(RockSetups, ExcavatedOpeningMatchesKirschK0Half) { kirsch_convergence(0.5); }

TEST(RockSetups, GradualExcavationReleasesItsTractionInEqualParts) {
  // Static, linear: with excavation_steps = 4 each of the first four steps adds a quarter of the
  // release, and nothing moves after. At cover orders 0 and 1.
  SceneDef s = kirsch_scene(0.4, 0.5, 8);
  const Mesh m = pre::build_mesh(s, "gradual");
  auto wall_u = [&](const TimeStepper& st) {  // largest displacement of any point of the rock, m
    double d = 0;
    for (double u : st.view().state.loop_u) d = std::max(d, std::abs(u));
    return d;
  };
  for (int order : {0, 1}) {
    s.solver.cover_order = order;
    s.solver.excavation_steps = 1;
    TimeStepper once(m, s, "gradual");
    once.step(1.0);
    s.solver.excavation_steps = 4;
    TimeStepper gradual(m, s, "gradual");
    const double full = wall_u(once);
    std::vector<double> seen;
    for (int i = 0; i < 6; ++i) {
      gradual.step(1.0);
      seen.push_back(wall_u(gradual));
    }
    std::printf("gradual release, n = %d: %.4f %.4f %.4f %.4f %.4f %.4f of the release at once\n", order,
                seen[0] / full, seen[1] / full, seen[2] / full, seen[3] / full, seen[4] / full, seen[5] / full);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(seen[i] / full, 0.25 * (i + 1), 1e-3) << "order " << order;
    EXPECT_NEAR(seen[5] / full, 1.0, 1e-3) << "order " << order;
  }
}

// Excavation at cover order 1 against two known answers: the opening that a free hole under
// the same initial stress gives (the same K d = F: the released in-situ traction on the wall is
// what the hole's free face leaves unbalanced), and Kirsch. Points just inside the rock
// (r = 1.05 a) at 15°, 45°, 75°.
TEST(RockSetups, ExcavationAtOrderOneMatchesAFreeOpeningAndKirsch) {
  KirschSetup k;
  k.h = 0.4;
  k.k0 = 0.5;
  k.order = 1;
  const double r = 1.05, px = k.k0 * kKirschPressure, py = kKirschPressure;
  const double G = kKirschYoung / (2 * (1 + kKirschPoisson));
  std::vector<double> th;
  for (double deg : {15.0, 45.0, 75.0}) th.push_back(deg * kPi / 180);
  auto run = [&](bool core) {
    k.with_core = core;
    SceneDef s = kirsch_scene(k);
    for (double t : th) s.measure_points.push_back({r * std::cos(t), r * std::sin(t)});
    const Mesh m = pre::build_mesh(s, core ? "excavated" : "free");
    TimeStepper st(m, s, "kirsch");
    st.step(1.0);
    std::vector<double> ur;  // inward
    for (std::size_t i = 0; i < th.size(); ++i) {
      const auto u = st.view().state.measure[i].displacement();
      ur.push_back(-(u[0] * std::cos(th[i]) + u[1] * std::sin(th[i])));
    }
    return ur;
  };
  const std::vector<double> excavated = run(true), free = run(false);
  for (std::size_t i = 0; i < th.size(); ++i) {
    const double want = kirsch_radial_displacement(px, py, G, kKirschPoisson, r, th[i]);
    std::printf("n = 1, θ = %.0f°: u_r excavated %.6e m, free opening %.6e m, Kirsch %.6e m (%+.2f %%)\n",
                th[i] * 180 / kPi, excavated[i], free[i], want, 100 * (excavated[i] - want) / want);
    EXPECT_NEAR(excavated[i], free[i], 1e-6 * std::abs(free[i]));
    EXPECT_NEAR(excavated[i], want, 0.02 * std::abs(want));
  }
}

// Issue 15's target: Kirsch's hoop stress at the wall within 5 % at a mesh where n = 0 is off by
// more than 15 %. Read off fairly for every order: each wall element's stress field evaluated at
// the ends of its wall edges (what the VTU frames show as vertex_stress; at n = 0 the element's
// constant stress), RMS against Kirsch there, relative to the largest wall hoop stress (25 MPa
// at the side wall for K0 = 0.5). Measured (h = 0.4a, b = 20a): n = 0 16.3 %, n = 1 2.9 %,
// n = 2 0.68 %; radial displacement 3.0 / 0.40 / 0.44 % (n ≥ 1 sit on the model's own ~0.4 %:
// b = 20a and the rollers).
TEST(RockSetups, KirschHoopStressAtTheWallAcrossOrders) {
  KirschSetup k;
  k.h = 0.4;
  k.k0 = 0.5;
  std::vector<KirschWall> w;
  for (int order : {0, 1, 2}) {
    k.order = order;
    const SceneDef s = kirsch_scene(k);
    const Mesh m = pre::build_mesh(s, "kirsch");
    TimeStepper st(m, s, "kirsch");
    st.step(1.0);
    w.push_back(kirsch_wall(k, m, st));
    std::printf("Kirsch K0 = 0.5, h = 0.4a, n = %d: hoop at the wall RMS %.2f %% (%zu points), at the "
                "centroids %.2f %%, side wall %.3f MPa (Kirsch %.3f), radial %.3f %%\n",
                order, 100 * w.back().hoop_wall, w.back().wall_points, 100 * w.back().hoop_centroid,
                w.back().side_wall_hoop / 1e6, w.back().side_wall_exact / 1e6, 100 * w.back().radial);
  }
  EXPECT_GT(w[0].hoop_wall, 0.15);
  EXPECT_LT(w[1].hoop_wall, 0.05);
  EXPECT_LT(w[2].hoop_wall, 0.05);
  EXPECT_LT(w[2].hoop_wall, w[1].hoop_wall);
  for (int n : {1, 2}) {
    EXPECT_LT(w[n].radial, 0.01) << "order " << n;
    EXPECT_NEAR(w[n].side_wall_hoop, w[n].side_wall_exact, 0.06 * w[n].side_wall_exact) << "order " << n;
  }
}

TEST(RockSetups, RestartFromStateInMemoryIsBitwiseExact) {
  SceneDef s = insitu_box(0.6);
  s.tractions[0].from_insitu = false;  // out of balance: the model moves
  s.tractions[0].normal = -4e6;
  const Mesh m = pre::build_mesh(s, "restart");
  TimeStepper straight(m, s, "restart");
  for (int i = 0; i < 30; ++i) straight.step(1e-3);
  TimeStepper first(m, s, "restart");
  for (int i = 0; i < 15; ++i) first.step(1e-3);
  TimeStepper second(m, s, "restart");
  second.restore(first.view().state, save_contact_history(first.view().contacts), "memory");
  for (int i = 0; i < 15; ++i) second.step(1e-3);
  EXPECT_EQ(state_hash(second.view()), state_hash(straight.view()));
  EXPECT_NE(state_hash(first.view()), state_hash(straight.view()));
  EXPECT_EQ(second.view().state.step, 30);
}

// Internal pressure on a hole face (Lamé): a quarter of a thick cylinder, inner radius a = 1,
// outer b = 3, rollers on the symmetry lines, pressure p on the inner face (normal = −p pushes
// into the body). Plane strain, outer face free:
//   u_r(r) = p a² / (E (b² − a²)) · [(1 + ν)(1 − 2ν) r + (1 + ν) b² / r]
TEST(RockSetups, PressureOnAHoleFaceMatchesLame) {
  const double a = 1, b = 3, p = 5e6, E = 1e10, nu = 0.25;
  const int n = 64;
  SceneDef s = rock_scene(0.1);
  BodyDef ring;
  ring.material = 0;
  std::vector<Vec2> inner;
  for (int i = 0; i <= n; ++i) {
    const double t = 0.5 * kPi * i / n;
    ring.outer.push_back({b * std::cos(t), b * std::sin(t)});
  }
  ring.outer.back() = {0, b};
  ring.outer.front() = {b, 0};
  for (int i = n; i >= 0; --i) {
    const double t = 0.5 * kPi * i / n;
    inner.push_back({a * std::cos(t), a * std::sin(t)});
  }
  inner.front() = {0, a};
  inner.back() = {a, 0};
  for (const Vec2& q : inner) ring.outer.push_back(q);
  s.bodies = {ring};
  s.supports = {support({{0, a}, {0, b}}, true, false), support({{a, 0}, {b, 0}}, false, true)};
  s.solver.support_stiffness = 1e4 * E / 0.1;
  s.tractions = {traction(inner, -p, 0)};
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::equilibrium;  // K d = F: the elastic answer in one step
  const Mesh m = pre::build_mesh(s, "lame");
  TimeStepper st(m, s, "lame");
  st.step(1.0);
  const double want = p * a * a / (E * (b * b - a * a)) * ((1 + nu) * (1 - 2 * nu) * a + (1 + nu) * b * b / a);
  double err = 0;
  int count = 0;
  for (std::size_t v = 0; v < m.loop_vertex_count(); ++v) {
    const double x = m.loop_xy[2 * v], y = m.loop_xy[2 * v + 1], r = std::hypot(x, y);
    if (std::abs(r - a) > 1e-9 || x < 1e-6 || y < 1e-6) continue;
    const double ur = (st.view().state.loop_u[2 * v] * x + st.view().state.loop_u[2 * v + 1] * y) / r;
    err = std::max(err, std::abs(ur - want));
    ++count;
  }
  std::printf("Lamé: inner wall u_r %.6e m expected, largest error %.2f %% over %d vertices\n", want,
              100 * err / want, count);
  ASSERT_GT(count, 10);
  EXPECT_LT(err, 0.01 * want);  // outward: a sign error would be off by 200 %
}

TEST(RockSetups, TimeTableFromCsvInterpolatesLinearly) {
  const std::string path = ::testing::TempDir() + "/nmm_table.csv";
  std::ofstream(path) << "time,factor\n# ramp then hold\n0,0\n2;4\n\n3,1\n";
  const std::string scene =
      R"({"materials": {"r": {"density": 1, "young": 1, "poisson": 0}}, "mesh": {"size": 1},
          "bodies": [{"material": "r", "outer": [[0,0],[1,0],[1,1]]}],
          "base_acceleration": {"x": ")" + path + R"("}})";
  const SceneDef s = parse_scene(scene, "table.json");
  ASSERT_EQ(s.base_acceleration_x.time.size(), 3u);
  EXPECT_DOUBLE_EQ(table_value(s.base_acceleration_x, -1, 0), 0);
  EXPECT_DOUBLE_EQ(table_value(s.base_acceleration_x, 1, 0), 2);
  EXPECT_DOUBLE_EQ(table_value(s.base_acceleration_x, 2.5, 0), 2.5);
  EXPECT_DOUBLE_EQ(table_value(s.base_acceleration_x, 9, 0), 1);
  EXPECT_DOUBLE_EQ(table_value(TimeTable{}, 9), 1);
  std::ofstream(path) << "0,0\n1,x\n";
  try {
    parse_scene(scene, "table.json");
    FAIL() << "a bad row must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/base_acceleration/x"), std::string::npos) << e.what();
  }
}

// Newmark's sliding block (docs/physics.md §5): a block resting on a plane inclined at α (gravity
// tilted by α, the base held by fixed points) with friction φ > α, shaken along the plane by a
// one-cycle sine base acceleration a_b(t). Relative to the base the block feels g·sinα − a_b(t)
// along the plane; it slides (downslope only: upslope needs a_b > g(sinα + cosα·tanφ), not
// reached here) while the relative velocity is positive or the driving exceeds the yield
// acceleration k_y·g = g(cosα·tanφ − sinα):
//   v' = g sinα − a_b(t) − g cosα tanφ   (v > 0),   v = 0 otherwise
// integrated here with the same piecewise-linear table the solver reads (1 µs steps).
TEST(RockSetups, BlockOnInclineUnderSineBaseAccelerationFollowsNewmark) {
  const double g = 9.81, alpha = 20 * kPi / 180, phi = 30 * kPi / 180;
  const double amp = 5.0, period = 0.5, t0 = 0.05, t_end = 0.8;
  TimeTable table;
  table.time.push_back(0);
  table.value.push_back(0);
  for (int i = 0; i <= 200; ++i) {
    const double t = t0 + period * i / 200;
    table.time.push_back(t);
    table.value.push_back(-amp * std::sin(2 * kPi * i / 200));  // first half drives downslope
  }
  // Reference: the rigid-block relative motion.
  double v = 0, x = 0;
  const double dt = 1e-6, mu = std::tan(phi);
  for (double t = 0; t < t_end; t += dt) {
    const double drive = g * std::sin(alpha) - table_value(table, t + 0.5 * dt, 0.0);
    const double acc = drive - g * std::cos(alpha) * mu;
    if (v > 0 || acc > 0) {
      v = std::max(0.0, v + acc * dt);
      x += v * dt;
    }
  }
  SceneDef s = rock_scene(0.5);
  s.materials[0].density = 2650;
  JointSetDef js;
  js.name = "interface";
  js.friction_deg = 30;
  js.normal.model = NormalModel::penalty;  // DDA's 20·E point penalty, as the sliding-block problems
  js.shear.model = ShearModel::penalty;
  js.normal.kn = 2e11;
  js.shear.ks = 8e10;
  s.joint_sets = {js};
  s.interface_set = 0;
  s.has_gravity = true;
  s.gravity = {g * std::sin(alpha), -g * std::cos(alpha)};  // downslope is +x
  s.bodies = {reference::box(0, 0, 12, 1), reference::box(1, 1, 3, 2)};
  s.fixed_points = reference::held_along(0.1, 11.9, 0.1);
  s.measure_points = {{2, 1.5}, {2, 0.5}};
  s.base_acceleration_x = table;
  s.solver.time_step = 1e-3;
  const Mesh m = pre::build_mesh(s, "newmark");
  TimeStepper st(m, s, "newmark");
  ASSERT_PRED1(test::ended_ok, st.run_until(t_end, [](std::int64_t) {}));
  const auto ub = st.view().state.measure[0].displacement();
  const auto ug = st.view().state.measure[1].displacement();
  const double slid = ub[0] - ug[0];
  std::printf("Newmark block: slid %.5f m relative to the base, rigid-block Newmark %.5f m (%+.2f %%)\n",
              slid, x, 100 * (slid - x) / x);
  EXPECT_GT(x, 0.01);
  EXPECT_NEAR(slid, x, 0.01 * x);  // measured +0.06 %
  // Without the shaking it stays put: the sliding is the base acceleration's doing.
  SceneDef still = s;
  still.base_acceleration_x = TimeTable{};
  TimeStepper st2(m, still, "newmark");
  ASSERT_PRED1(test::ended_ok, st2.run_until(t_end, [](std::int64_t) {}));
  const double rest = st2.view().state.measure[0].displacement()[0] -
                      st2.view().state.measure[1].displacement()[0];
  EXPECT_LT(std::abs(rest), 0.02 * x);
}

}  // namespace
}  // namespace nmm::solve

