// Support reactions (docs/interface.md "Support reactions"; solver/discretisation/support_reaction.h)
// against what a support must carry: the reactions of a step balance the loads of its solve
// (Σ R + Σ loads = 0 to round-off at cover orders 0, 1, 2), and those of a body at rest its
// weight, point loads and tractions on its geometry now; a support moving at a velocity
// pulls an elastic bar by F = E·A·Δu/L (and, with the penalty springs' give in series, by the
// closed form of the bar and two springs); travel = |v|·∫f dt, also under a velocity history that
// reverses; reactions.csv and summary.json "supports" carry the same numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "preprocess/cover_cutter.h"
#include "reference/scene_pieces.h"
#include "solver/discretisation/support_reaction.h"
#include "solver/output/output_writer.h"
#include "solver/output/run_driver.h"
#include "solver/stepping/time_stepper.h"
#include "tests/temp_dir.h"

namespace nmm::solve {
namespace {

constexpr double kYoung = 1e10, kPoisson = 0.25, kDensity = 2500;

// Steps a static run until it has settled: a step's reactions balance the loads of its solve,
// on the geometry the step started from (a first step from rest moves the edges by the strain,
// 3e-4 of the plate below); once a step no longer moves the body, they balance the loads on the
// state's own geometry, which the checks below integrate.
void settle(TimeStepper& st, int steps) {
  for (int i = 0; i < steps; ++i) st.step(1.0);
}

/// N/m, the force of a traction (normal, Pa along the current outward normal; shear, Pa along +y)
/// on the body's right side that started at x = x0, integrated over the side as it is now.
std::array<double, 2> side_traction(const RunView& v, double x0, double normal, double shear) {
  std::vector<std::pair<double, double>> pts;
  for (std::size_t k = 0; k < v.state.loop_xy.size() / 2; ++k)
    if (std::abs(v.state.loop_xy[2 * k] - v.state.loop_u[2 * k] - x0) < 1e-9)
      pts.push_back({v.state.loop_xy[2 * k + 1] - v.state.loop_u[2 * k + 1], static_cast<double>(k)});
  std::sort(pts.begin(), pts.end());
  std::array<double, 2> f{0, 0};
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const std::size_t a = static_cast<std::size_t>(pts[i].second), b = static_cast<std::size_t>(pts[i + 1].second);
    const double dx = v.state.loop_xy[2 * b] - v.state.loop_xy[2 * a];
    const double dy = v.state.loop_xy[2 * b + 1] - v.state.loop_xy[2 * a + 1];
    const double len = std::hypot(dx, dy);
    if (!(len > 0)) continue;  // the same vertex in two elements
    f[0] += (normal * dy / len) * len;
    f[1] += (normal * -dx / len + shear) * len;
  }
  return f;
}

/// m, the current length of the body's vertical side that started at x = x0 (its loop vertices').
double current_length(const RunView& v, double x0) {
  double lo = 1e300, hi = -1e300;
  for (std::size_t k = 0; k < v.state.loop_xy.size() / 2; ++k)
    if (std::abs(v.state.loop_xy[2 * k] - v.state.loop_u[2 * k] - x0) < 1e-9) {
      lo = std::min(lo, v.state.loop_xy[2 * k + 1]);
      hi = std::max(hi, v.state.loop_xy[2 * k + 1]);
    }
  return hi - lo;
}

SceneDef rock(double h, int order = 0) {
  SceneDef s;
  s.materials.push_back({"rock", kDensity, kYoung, kPoisson, {}});
  s.mesh_size = h;
  s.plane = PlaneKind::stress;
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::equilibrium;  // K d = F: the state at rest in each step
  s.solver.cover_order = order;
  return s;
}

SupportDef support(std::vector<Vec2> pts, bool x, bool y, Vec2 velocity = {0, 0}) {
  SupportDef d;
  d.points = std::move(pts);
  d.fix_x = x;
  d.fix_y = y;
  d.velocity = velocity;
  return d;
}

// A 2 m × 1 m block held along its base, under gravity, a point load on its top and a traction on
// its right side: the base's reaction balances them all.
void check_balance(int order) {
  SceneDef s = rock(0.23, order);
  s.bodies = {reference::box(0, 0, 2, 1)};
  s.has_gravity = true;
  s.gravity = {0, -9.81};
  s.supports = {support({{0, 0}, {2, 0}}, true, true)};
  s.loads = {{{1.3, 0.9}, {3e5, -1e6}}};
  TractionDef t;
  t.points = {{2, 0}, {2, 1}};
  t.normal = -2e5;  // Pa, pushes −x on the right side
  t.shear = 1e5;    // Pa, along the polyline: +y
  s.tractions = {t};
  const Mesh m = pre::build_mesh(s, "balance");
  TimeStepper st(m, s, "balance");
  settle(st, 6);
  const std::vector<SupportReaction> r = support_reactions(st.view());
  ASSERT_EQ(r.size(), 1u);
  // Tractions act on the side as it is now (its length changed by the strain), gravity on the
  // mass, the point load as given.
  const std::array<double, 2> on_side = side_traction(st.view(), 2.0, -2e5, 1e5);
  // The body force acts on the elements as they are now (density times the current area).
  double area = 0;
  const Mesh& mesh = st.view().mesh;
  const std::vector<double>& xy = st.view().state.loop_xy;
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (std::int32_t a = mesh.element_loop_offset[e]; a < mesh.element_loop_offset[e + 1]; ++a) {
      const std::int32_t b = a + 1 < mesh.element_loop_offset[e + 1] ? a + 1 : mesh.element_loop_offset[e];
      area += 0.5 * (xy[2 * a] * xy[2 * b + 1] - xy[2 * b] * xy[2 * a + 1]);
    }
  const double weight = kDensity * 9.81 * area;                                         // N/m
  const double load_x = 3e5 + on_side[0], load_y = -1e6 + on_side[1] - weight;  // N/m
  const double scale = std::abs(load_x) + std::abs(load_y);
  std::printf("order %d: base reaction (%.9g, %.9g) N/m against loads (%.9g, %.9g): imbalance %.2e, %.2e of the loads\n",
              order, r[0].fx, r[0].fy, load_x, load_y, std::abs(r[0].fx + load_x) / scale,
              std::abs(r[0].fy + load_y) / scale);
  EXPECT_LT(std::abs(r[0].fx + load_x), 1e-6 * scale);
  EXPECT_LT(std::abs(r[0].fy + load_y), 1e-6 * scale);
  EXPECT_EQ(r[0].travel, 0);
  EXPECT_EQ(r[0].load(), 0);
}

TEST(Reactions, HeldBaseBalancesWeightLoadAndTraction) { check_balance(0); }
TEST(Reactions, HeldBaseBalancesWeightLoadAndTractionAtOrderOne) { check_balance(1); }

// The first step from rest: its solve balances the loads on the mesh as cut — the weight of its
// area, the traction over the side's length — and so do the reactions at its solution, at every
// cover order (the springs' displacement inside an edge is of degree n + 1: support_reaction.h).
TEST(Reactions, AStepsReactionsBalanceTheLoadsOfItsSolve) {
  for (int order : {0, 1, 2}) {
    SceneDef s = rock(0.23, order);
    s.bodies = {reference::box(0, 0, 2, 1)};
    s.has_gravity = true;
    s.gravity = {0, -9.81};
    s.supports = {support({{0, 0}, {2, 0}}, true, true)};
    TractionDef t;
    t.points = {{2, 0}, {2, 1}};
    t.normal = -2e5;
    t.shear = 1e5;
    s.tractions = {t};
    const Mesh m = pre::build_mesh(s, "step");
    TimeStepper st(m, s, "step");
    st.step(1.0);
    const std::vector<SupportReaction> r = support_reactions(st.view());
    const double load_x = -2e5, load_y = 1e5 - kDensity * 9.81 * 2.0;  // N/m
    std::printf("order %d, one step: base reaction (%.12g, %.12g) N/m against loads (%.12g, %.12g)\n", order,
                r[0].fx, r[0].fy, load_x, load_y);
    EXPECT_NEAR(r[0].fx, -load_x, 1e-9 * 2.5e5);
    EXPECT_NEAR(r[0].fy, -load_y, 1e-9 * 2.5e5);
  }
}

TEST(Reactions, RollersCarryTheTractionsOfAPlate) {
  // A 3 m × 2 m plate on rollers (left side held in x, base in y) under −4 MPa on its top and
  // −1.5 MPa on its right side: the rollers carry +1.5 MPa × 2 m in x and +4 MPa × 3 m in y, and
  // a roller carries nothing along itself.
  SceneDef s = rock(0.37);
  s.plane = PlaneKind::strain;
  s.bodies = {reference::box(0, 0, 3, 2)};
  s.supports = {support({{0, 2}, {0, 0}}, true, false), support({{0, 0}, {3, 0}}, false, true)};
  TractionDef top, side;
  top.points = {{0, 2}, {3, 2}};
  top.normal = -4e6;
  side.points = {{3, 0}, {3, 2}};
  side.normal = -1.5e6;
  s.tractions = {top, side};
  const Mesh m = pre::build_mesh(s, "plate");
  TimeStepper st(m, s, "plate");
  settle(st, 6);
  const std::vector<SupportReaction> r = support_reactions(st.view());
  ASSERT_EQ(r.size(), 2u);
  // The tractions act on the sides as they are now: the right side shortened by ε_yy =
  // ((1 − ν²)σyy − ν(1 + ν)σxx)/E = −3.28e-4 (plane strain), the top by ε_xx.
  const double right = current_length(st.view(), 3.0);
  double lo = 1e300, hi = -1e300;
  for (std::size_t k = 0; k < st.view().state.loop_xy.size() / 2; ++k)
    if (std::abs(st.view().state.loop_xy[2 * k + 1] - st.view().state.loop_u[2 * k + 1] - 2.0) < 1e-9) {
      lo = std::min(lo, st.view().state.loop_xy[2 * k]);
      hi = std::max(hi, st.view().state.loop_xy[2 * k]);
    }
  const double top_now = hi - lo;
  std::printf("plate on rollers: left (%.9g, %.9g), base (%.9g, %.9g) N/m; the tractions' (%.9g, %.9g) on sides of "
              "%.9g m and %.9g m\n",
              r[0].fx, r[0].fy, r[1].fx, r[1].fy, 1.5e6 * right, 4e6 * top_now, right, top_now);
  EXPECT_NEAR(r[0].fx, 1.5e6 * right, 1e-6 * 1.2e7);
  EXPECT_NEAR(r[1].fy, 4e6 * top_now, 1e-6 * 1.2e7);
  EXPECT_EQ(r[0].fy, 0);
  EXPECT_EQ(r[1].fx, 0);
}

// A bar 1 m × 0.2 m in plane stress on rollers (left side held in x, base in y), pulled by its
// right side moving at v in x: uniaxial stress σ = E·Δu/L, so the moving support pulls with
// F = E·A·Δu/L (A = 0.2 m² per m), Δu the bar's elongation. The support's held position is v·t:
// the bar and the two supports' penalty springs (k_s per m of edge over the 0.2 m sides) in series
// give F = v·t / (L/(E·A) + 2/(k_s·A)).
TEST(Reactions, MovingSupportPullsAnElasticBarByEAOverL) {
  const double L = 1.0, H = 0.2, v = 1e-5;  // m, m, m/s
  SceneDef s = rock(0.1);
  s.bodies = {reference::box(0, 0, L, H)};
  s.supports = {support({{0, 0}, {0, H}}, true, false), support({{0, 0}, {L, 0}}, false, true),
                support({{L, 0}, {L, H}}, true, false, {v, 0})};
  const Mesh m = pre::build_mesh(s, "bar");
  TimeStepper st(m, s, "bar");
  for (int i = 0; i < 4; ++i) st.step(1.0);
  const RunView view = st.view();
  const double t = view.state.time;
  const std::vector<SupportReaction> r = support_reactions(view);
  ASSERT_EQ(r.size(), 3u);
  // The bar's elongation: the mean x displacement of the right side less the left side's.
  double right = 0, left = 0;
  int nr = 0, nl = 0;
  for (std::size_t k = 0; k < view.state.loop_u.size() / 2; ++k) {
    const double x0 = view.state.loop_xy[2 * k] - view.state.loop_u[2 * k];
    if (std::abs(x0 - L) < 1e-9) right += view.state.loop_u[2 * k], ++nr;
    if (std::abs(x0) < 1e-9) left += view.state.loop_u[2 * k], ++nl;
  }
  const double du = right / nr - left / nl;
  const double k_s = view.model.support_stiffness();
  const double F_bar = kYoung * H * du / L;
  const double F_series = v * t / (L / (kYoung * H) + 2 / (k_s * H));
  const double F_rigid = kYoung * H * v * t / L;  // supports that do not give
  std::printf("moving support: F = %.9g N/m; E·A·Δu/L = %.9g (%.2e), series form %.9g (%.2e), E·A·v·t/L = %.9g "
              "(%.2e); travel %.9g m, v·t %.9g m\n",
              r[2].fx, F_bar, r[2].fx / F_bar - 1, F_series, r[2].fx / F_series - 1, F_rigid, r[2].fx / F_rigid - 1,
              r[2].travel, v * t);
  EXPECT_NEAR(r[2].fx / F_bar, 1, 1e-4);     // the current side is shorter by ν·ε: 1.25e-5
  EXPECT_NEAR(r[2].fx / F_series, 1, 1e-4);
  EXPECT_NEAR(r[2].fx / F_rigid, 1, 0.005);  // the penalty's give: 2·E/(k_s·L) = 0.2 %
  EXPECT_GT(r[2].fx / F_rigid, 0.99);        // and no more than that
  EXPECT_DOUBLE_EQ(r[2].travel, v * t);
  EXPECT_DOUBLE_EQ(r[2].load(), r[2].fx);    // pulled along its velocity: a positive load
  EXPECT_EQ(r[0].travel, 0);
  // The bar at rest: the held side pulls back by as much.
  EXPECT_NEAR(r[0].fx + r[2].fx, 0, 1e-6 * r[2].fx);
  EXPECT_NEAR(r[1].fy, 0, 1e-6 * r[2].fx);
}

TEST(Reactions, TravelFollowsAVelocityHistoryThatReverses) {
  // f(t) = 1 − t/2 (a platen that slows, stops at t = 2 s and comes back): travel = |v|·(t − t²/4),
  // 0.75·|v| at t = 3 s; the support moves along (0, −1)·|v|.
  const double v = 2e-5;
  SceneDef s = rock(0.25);
  s.bodies = {reference::box(0, 0, 1, 1)};
  SupportDef platen = support({{0, 1}, {1, 1}}, false, true, {0, -v});
  platen.table.time = {0, 4};
  platen.table.value = {1, -1};
  s.supports = {support({{0, 0}, {1, 0}}, true, true), platen};
  const Mesh m = pre::build_mesh(s, "platen");
  TimeStepper st(m, s, "platen");
  for (int i = 0; i < 3; ++i) st.step(1.0);
  const std::vector<SupportReaction> r = support_reactions(st.view());
  ASSERT_EQ(r.size(), 2u);
  EXPECT_NEAR(r[1].travel, 0.75 * v, 1e-15);
  EXPECT_DOUBLE_EQ(r[1].dx, 0);
  EXPECT_DOUBLE_EQ(r[1].dy, -1);
  EXPECT_GT(r[1].load(), 0);  // pushing the block down along its velocity
  EXPECT_NEAR(r[0].fy + r[1].fy, 0, 1e-6 * r[1].load());
}

// reactions.csv: one row per support per output step, the numbers of support_reactions; summary.json
// "supports" the last of them with the direction and the load.
TEST(Reactions, ReactionsCsvAndSummaryCarryTheReactions) {
  const double v = 1e-5;
  SceneDef s = rock(0.25);
  s.bodies = {reference::box(0, 0, 1, 0.5)};
  s.supports = {support({{0, 0}, {0, 0.5}}, true, true), support({{1, 0}, {1, 0.5}}, true, false, {v, 0})};
  s.solver.time_step = 1.0;
  s.solver.steps = 5;
  s.solver.output_every = 2;
  const Mesh m = pre::build_mesh(s, "csv");
  TimeStepper st(m, s, "csv");
  test::TempDir dir;
  OutputWriter out(dir.path().string());
  const nlohmann::json summary = run_to_end(st, out);
  const std::vector<SupportReaction> r = support_reactions(st.view());
  std::ifstream in(dir.path("reactions.csv"));
  ASSERT_TRUE(in.good());
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "step,time,support,fx,fy,travel");
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) row.push_back(std::stod(c));
    rows.push_back(row);
  }
  // Output steps 0, 2, 4 and the last, 5: four, of two supports each.
  ASSERT_EQ(rows.size(), 8u);
  EXPECT_EQ(rows[0][0], 0);
  EXPECT_EQ(rows[0][5], 0);  // nothing has moved yet
  EXPECT_EQ(rows[7][0], 5);
  EXPECT_EQ(rows[7][1], 5.0);
  for (int k = 0; k < 2; ++k) {
    const std::vector<double>& row = rows[6 + k];
    EXPECT_EQ(row[2], k);
    EXPECT_EQ(row[3], r[k].fx);  // shortest round-trip text: the same doubles
    EXPECT_EQ(row[4], r[k].fy);
    EXPECT_EQ(row[5], r[k].travel);
  }
  EXPECT_DOUBLE_EQ(rows[7][5], v * 5.0);
  ASSERT_TRUE(summary.contains("supports"));
  const nlohmann::json& sup = summary["supports"];
  ASSERT_EQ(sup.size(), 2u);
  EXPECT_EQ(sup[1]["fx_n_per_m"].get<double>(), r[1].fx);
  EXPECT_EQ(sup[1]["travel_m"].get<double>(), r[1].travel);
  EXPECT_EQ(sup[1]["direction"][0].get<double>(), 1.0);
  EXPECT_EQ(sup[1]["load_n_per_m"].get<double>(), r[1].fx);
  EXPECT_GT(r[1].fx, 0);
  EXPECT_NEAR(r[0].fx + r[1].fx, 0, 1e-6 * r[1].fx);
}

}  // namespace
}  // namespace nmm::solve
