// Fracturing together with bolts and absorbing boundaries (docs/fracture.md "Bolts and absorbing
// boundaries"): a re-cut ties each bolt again to the pieces of rock its points lie in and lays
// the dashpots on the re-cut boundary edges, the absorbing boundaries' carried reaction following
// its covers.
//   - a bar with an anchored bolt along its axis, pulled apart until it cracks across between the
//     bolt's ends: the bolt holds the two pieces, its ends tied to different blocks, and its force
//     is then the closed form of the bolt in series with the rock on either side of it,
//         F = δ / (1/k + (x_a + L − x_b)·s/(E·H))                               N per bolt
//     (δ the pulled end's travel, k the bolt's stiffness, x_a and x_b its ends, s its spacing, H
//     the bar's height, plane stress, the crack open), within 1 %;
//   - a bolted bar and a grouted cable restarted from checkpoints before and after the re-cut
//     continue bit for bit;
//   - a P pulse down a column with an absorbing base, whose rock cracks near its top while the
//     pulse leaves through the base: the reflection stays as low as in the column that does not
//     crack, energy.csv's absorbed column runs on across each re-cut without a jump, and a restart
//     across the re-cut continues bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/math_constants.h"
#include "common/mesh_file.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "preprocess/recut.h"
#include "solver/discretisation/absorbing_boundary.h"
#include "solver/discretisation/point_location.h"
#include "solver/reinforcement/bolt_layout.h"
#include "solver/stepping/fracture_effect.h"
#include "solver/stepping/mesh_bound.h"
#include "solver/stepping/run_view.h"
#include "solver/stepping/restart.h"
#include "solver/stepping/time_stepper.h"
#include "tests/ended_ok.h"
#include "tests/rock_stress.h"

namespace nmm {
namespace {

using nlohmann::json;
using solve::TimeStepper;

/// A mesh of `doc` with its scene text recorded, as nmm-preprocess writes it (a cracked run's
/// checkpoint checks its MESH section against it).
Mesh mesh_of(const json& doc, const SceneDef& s, const std::string& name) {
  Mesh m = pre::build_mesh(s, name);
  m.scene_text = doc.dump();
  m.scene_sha256 = sha256(m.scene_text);
  return m;
}

// ---- a bolted bar ------------------------------------------------------------------------------

constexpr double kBarL = 4, kBarH = 1, kSpeed = 1e-3, kBoltK = 2e8;

/// The 4 m × 1 m bar of test_fracture.cpp (E 10 GPa, ν 0.2, plane stress, static, Δt 1 ms, h
/// 0.25 m, σt 1 MPa), its ends on rollers (x held), the end x = 4 m pulled at 1 mm/s. The bolt
/// runs from end to end along the axis, so that every section of the bar carries the same and the
/// crack, wherever it forms, crosses it: an anchored bolt of stiffness 200 MN/m, or a grouted cable
/// (EA 200 MN, bond 1 GPa, 32 segments: a point every 0.125 m, on the lines the mesh's cracks
/// follow); spacing 1 m.
json bolted_bar(bool grouted) {
  json d;
  d["plane"] = "stress";
  d["materials"]["rock"] = {{"density", 2500}, {"young", 1e10}, {"poisson", 0.2},
                            {"strength", {{"tensile", 1e6}, {"cohesion", 4e6}, {"friction_deg", 35}}}};
  d["joint_sets"]["crack"] = {{"friction_deg", 30},
                              {"normal", {{"model", "constant"}, {"kn", 1e11}}},
                              {"shear", {{"model", "constant"}, {"ks", 4e10}}}};
  d["bodies"] = {{{"material", "rock"}, {"outer", {{0, 0}, {kBarL, 0}, {kBarL, kBarH}, {0, kBarH}}}}};
  d["fracture"] = {{"crack_set", "crack"}};
  d["mesh"]["size"] = 0.25;
  d["supports"] = {{{"points", {{0, 0}, {0, kBarH}}}, {"fix", "x"}},
                   {{"points", {{kBarL, 0}, {kBarL, kBarH}}}, {"fix", "x"}, {"velocity", {kSpeed, 0}}}};
  d["fixed_points"] = {{0, kBarH / 2}};
  d["solver"] = {{"time_step", 1e-3}, {"steps", 1}, {"dynamic", false}};
  const json points = {{0, kBarH / 2}, {kBarL, kBarH / 2}};
  if (grouted)
    d["bolts"] = {{{"points", points}, {"type", "grouted"}, {"ea", 2e8}, {"bond_stiffness", 1e9}, {"spacing", 1.0},
                   {"segments", 32}}};
  else
    d["bolts"] = {{{"points", points}, {"type", "anchored"}, {"stiffness", kBoltK}, {"spacing", 1.0}}};
  return d;
}

// Mean σxx of the rock (Pa): in equilibrium without body force, the force the rock carries
// across a section per m of height (∫σ dA = ∮ t⊗x ds over the bar, /A).
double rock_pull(const solve::RunView& v) { return test::rock_mean_stress(v, 0); }

// The bar cracks across, and the bolt, whose ends are tied to the two pieces, holds them: its
// force is its stiffness times the pieces' parting, the pulled end's travel δ,
//     F = k·δ                                                         N per bolt
// (each end moves with the end of the bar it is tied to: the rock between carries nothing), as in
// the bar before it cracked — the same force before and after the re-cut — while the rock,
// cracked through, carries nothing.
TEST(FractureWithBolts, ABoltHoldsTheTwoPiecesOfACrackedBar) {
  const json doc = bolted_bar(false);
  const SceneDef s = scene_from_json(doc, "bolted_bar");
  const Mesh m = mesh_of(doc, s, "bolted_bar");
  TimeStepper st(m, s, "bolted_bar");
  double before = 0, rock_before = 0;  // N and Pa, the bolt's force and the rock's pull the step before the crack
  std::int64_t crack_step = -1;
  const Outcome o = st.run_until(0.6, [&](std::int64_t n) {
    const solve::RunView v = st.view();
    const bool cracked = !fracture_of(v).segments().empty();
    if (!cracked) before = v.state.bolts[0].axial[0], rock_before = rock_pull(v);
    if (cracked && crack_step < 0) crack_step = n;
  });
  ASSERT_PRED1(test::ended_ok, o);
  const solve::RunView v = st.view();
  ASSERT_GT(crack_step, 0) << "the bar must crack";
  double length = 0;
  for (const solve::CrackSegment& c : fracture_of(v).segments()) length += std::hypot(c.b.x - c.a.x, c.b.y - c.a.y);
  const solve::BoltState& b = v.state.bolts[0];
  const std::int32_t block_a = v.mesh.element_block[static_cast<std::size_t>(b.nodes[0].element)];
  const std::int32_t block_b = v.mesh.element_block[static_cast<std::size_t>(b.nodes[1].element)];
  const double closed = kBoltK * v.state.time * kSpeed, closed_before = kBoltK * (crack_step - 1) * 1e-3 * kSpeed;
  const double rock = rock_pull(v);
  std::printf("bolted bar: cracked at step %lld, the bolt carrying %.7g N the step before (k·δ %.7g N), the rock "
              "%.4g Pa; %zu segments, %.3f m of crack; at t %.3g s the bolt carries %.7g N, k·δ %.7g N (%+.2e), "
              "the rock %.3g Pa; its ends in blocks %d and %d of %zu\n",
              static_cast<long long>(crack_step), before, closed_before, rock_before, fracture_of(v).segments().size(),
              length, v.state.time, b.axial[0], closed, b.axial[0] / closed - 1, rock, block_a, block_b,
              v.mesh.block_count());
  EXPECT_GE(length, 0.98 * kBarH);  // across
  EXPECT_NE(block_a, block_b) << "the bolt's ends must be tied to the two pieces";
  EXPECT_NEAR(b.axial[0], closed, 1e-3 * closed);
  EXPECT_NEAR(before, closed_before, 2e-3 * closed_before);
  EXPECT_GT(rock_before, 0.9e6);
  EXPECT_LT(std::abs(rock), 0.02e6);  // cracked through: it carries nothing
}

// A crack cut exactly through a bolt's point: the point is tied to the piece the bolt runs into
// from it, whichever side of the crack rounding puts it (within 1e-9·h), and a point clearly on
// one side to the piece on that side.
TEST(FractureWithBolts, APointOnACrackIsTiedToTheRockTheBoltRunsInto) {
  json doc = bolted_bar(false);
  doc.erase("bolts");
  const SceneDef before = scene_from_json(doc, "bar");
  const Mesh old = pre::build_mesh(before, "bar");
  SceneDef cracked = before;
  cracked.joints.push_back({cracked.fracture.crack_set, {{2, 0}, {2, kBarH}}});
  pre::RecutMap map;
  const Mesh now = pre::recut(old, cracked, before.joints.size(), "bar", map);
  // x of the middle of the piece a point was tied to (its loop's mean vertex, as cut).
  const auto side = [&](std::int32_t e) {
    double x = 0;
    const auto b = now.element_loop_offset[static_cast<std::size_t>(e)], end = now.element_loop_offset[static_cast<std::size_t>(e) + 1];
    for (auto v = b; v < end; ++v) x += now.loop_xy[2 * static_cast<std::size_t>(v)];
    return x / (end - b) < 2 ? -1 : 1;
  };
  const auto point = [&](double x, double y) {
    const solve::PointLocation at = solve::locate_point(old, old.loop_xy, {x, y});
    return solve::TrackedPoint{at.element, x, y, x, y};
  };
  int checked = 0;
  for (const double y : {0.5, 0.3})
    for (const double off : {0.0, 1e-12, -1e-12, 0.01, -0.01})
      for (const int towards : {-1, 1}) {  // the bolt runs from the point to x = 2 + 0.5·towards
        solve::BoltState b;
        b.type = 0;
        b.nodes = {point(2 + off, y), point(2 + 0.5 * towards, y)};
        std::vector<solve::BoltState> bolts{b};
        solve::retie_bolts(old, now, map.element_parent, map.vertex_parent, bolts);
        const int expected = std::abs(off) > 1e-6 ? (off < 0 ? -1 : 1) : towards;
        EXPECT_EQ(side(bolts[0].nodes[0].element), expected) << "point x = 2 + " << off << ", y " << y;
        EXPECT_EQ(side(bolts[0].nodes[1].element), towards);
        // The same point as a bolt's last point: towards the one before.
        b.nodes = {point(2 + 0.5 * towards, y), point(2 + off, y)};
        bolts = {b};
        solve::retie_bolts(old, now, map.element_parent, map.vertex_parent, bolts);
        EXPECT_EQ(side(bolts[0].nodes[1].element), expected) << "last point x = 2 + " << off << ", y " << y;
        ++checked;
      }
  std::printf("%d bolt points on, next to and off a crack tied to the rock their bolts run into (%zu → %zu "
              "elements)\n", checked, old.element_count(), now.element_count());
}

/// Runs `doc` straight to t_end, and again through a checkpoint written at each of `t_stops`
/// (a fresh stepper restarted from it); every restarted run must end on the straight run's state
/// hash. Returns the segments at each stop.
std::vector<std::size_t> restarts_bit_for_bit(const json& doc, const std::string& name, double t_end,
                                              const std::vector<double>& t_stops) {
  const SceneDef s = scene_from_json(doc, name);
  const Mesh m = mesh_of(doc, s, name);
  TimeStepper straight(m, s, name);
  EXPECT_PRED1(test::ended_ok, straight.run_until(t_end, [](std::int64_t) {}));
  std::vector<std::size_t> at;
  for (const double t : t_stops) {
    TimeStepper first(m, s, name), second(m, s, name);
    EXPECT_PRED1(test::ended_ok, first.run_until(t, [](std::int64_t) {}));
    at.push_back(fracture_of(first.view()).segments().size());
    const std::string path = ::testing::TempDir() + "/" + name + ".nmmstate";
    solve::write_checkpoint(first.view(), path);
    second.restart_from(path);
    EXPECT_EQ(solve::state_hash(second.view()), solve::state_hash(first.view())) << name << " at t = " << t;
    EXPECT_PRED1(test::ended_ok, second.run_until(t_end, [](std::int64_t) {}));
    EXPECT_EQ(fracture_of(second.view()).segments().size(), fracture_of(straight.view()).segments().size());
    EXPECT_EQ(solve::state_hash(second.view()), solve::state_hash(straight.view())) << name << " from t = " << t;
  }
  EXPECT_FALSE(fracture_of(straight.view()).segments().empty()) << name << " must crack";
  return at;
}

TEST(FractureWithBolts, RestartsBeforeAndAfterTheReCutContinueBitForBit) {
  for (const bool grouted : {false, true}) {
    const std::vector<std::size_t> at =
        restarts_bit_for_bit(bolted_bar(grouted), grouted ? "cabled_bar" : "bolted_bar", 0.5, {0.1, 0.45});
    std::printf("%s bar: %zu and %zu crack segments at the checkpoints\n", grouted ? "cabled" : "bolted", at[0],
                at[1]);
    EXPECT_EQ(at[0], 0u);  // before the re-cut: the restarted run cracks
    EXPECT_GT(at[1], 0u);  // after it: the checkpoint holds the cracked mesh and the bolts on it
  }
}

// ---- a P pulse through a column with an absorbing base ----------------------------------------

constexpr double kCp = 1000, kHeight = 60, kDepth = 20, kPulse = 0.04, kDt = 1e-4, kSide = 0.005;

/// A Hann pulse of duration t_pulse and peak `peak`, as a time table of 41 rows (then 0).
json hann(double t_pulse, double peak) {
  json rows = json::array();
  for (int i = 0; i <= 40; ++i) {
    const double t = t_pulse * i / 40, s = std::sin(kPi * t / t_pulse);
    rows.push_back({t, peak * s * s});
  }
  return rows;
}

/// test_absorbing.cpp's column for a P pulse: 1 m × 60 m, ρ 2000 kg/m³, E 1.667 GPa, ν 0.25, plane
/// strain (cp 1000 m/s), h 0.5 m, its sides on rollers (x held), a 0.04 s Hann pulse of 100 kPa
/// pressing on its top, an absorbing base, a measure point 20 m below the top. With `fracture`
/// its rock has a strength (σt 50 kPa, c 1 MPa, φ 30°, far above what the pulse loads it with),
/// and a short stretch of its right side near the top, 50 m ≤ y ≤ 52 m, is pulled out sideways
/// from t = 0.05 s at 2 cm/s, which cracks the rock there while the pulse leaves through the
/// base (it reaches the base at 0.06 s); without, the same stretch is pulled and nothing cracks.
json column(bool fracture, bool absorbing = true, double pulse = 1e5) {
  json doc = json::parse(R"({"plane": "strain", "mesh": {"size": 0.5}, "solver": {"time_step": 1e-4, "dynamic": true}})");
  doc["materials"]["rock"] = {{"density", 2000}, {"young", 1.0 / 0.6 * 1e9}, {"poisson", 0.25}};
  if (fracture) {
    doc["materials"]["rock"]["strength"] = {{"tensile", 5e4}, {"cohesion", 1e6}, {"friction_deg", 30}};
    doc["joint_sets"]["crack"] = {{"friction_deg", 30},
                                  {"normal", {{"model", "constant"}, {"kn", 1e11}}},
                                  {"shear", {{"model", "constant"}, {"ks", 4e10}}}};
    doc["fracture"] = {{"crack_set", "crack"}};
  }
  doc["bodies"] = json::array({{{"material", "rock"}, {"outer", {{0, 0}, {1, 0}, {1, kHeight}, {0, kHeight}}}}});
  doc["supports"] = json::array({{{"points", {{0, 0}, {0, kHeight}}}, {"fix", "x"}},
                                 {{"points", {{1, 0}, {1, 50}}}, {"fix", "x"}},
                                 {{"points", {{1, 50}, {1, 52}}}, {"fix", "x"}, {"velocity", {kSide, 0}},
                                  {"table", {{0, 0}, {0.05, 0}, {0.0501, 1}, {0.06, 1}, {0.0601, 0}}}},
                                 {{"points", {{1, 52}, {1, kHeight}}}, {"fix", "x"}}});
  doc["measure_points"] = json::array({{0.5, kHeight - kDepth}});
  doc["tractions"] = json::array({{{"points", {{0, kHeight}, {1, kHeight}}}, {"normal", -pulse}, {"table", hann(kPulse, 1)}}});
  if (absorbing)
    doc["absorbing"] = json::array({{{"points", {{0, 0}, {1, 0}}}}});
  else
    doc["supports"].push_back({{"points", {{0, 0}, {1, 0}}}, {"fix", "y"}});
  return doc;
}

struct ColumnRun {
  std::vector<double> t, v;         ///< s, and the measure point's vertical velocity (m/s)
  std::vector<double> absorbed;     ///< J/m, RunState::absorbed_work after each step
  std::vector<std::size_t> segments;  ///< crack segments after each step
  double y_min = 1e9, y_max = -1e9;   ///< m, how far the cracks reach
  double incident = 0, reflected = 0;  ///< m/s
  double reflected_at = 0;             ///< s, when the reflected peak passes
};

ColumnRun run_column(const json& doc, const std::string& name) {
  const SceneDef s = scene_from_json(doc, name);
  const Mesh m = mesh_of(doc, s, name);
  TimeStepper st(m, s, name);
  ColumnRun r;
  const double arrive = kDepth / kCp, back = (2 * kHeight - kDepth) / kCp, end = back + 1.2 * kPulse;
  double before = 0;
  const Outcome o = st.run_until(end, [&](std::int64_t) {
    const solve::RunView v = st.view();
    const double u = v.state.measure[0].displacement()[1];
    r.t.push_back(v.state.time);
    r.v.push_back((u - before) / kDt);
    before = u;
    r.absorbed.push_back(v.state.absorbed_work);
    r.segments.push_back(v.model.scene().fracture.present ? fracture_of(v).segments().size() : 0);
  });
  EXPECT_PRED1(test::ended_ok, o);
  if (s.fracture.present)
    for (const solve::CrackSegment& c : fracture_of(st.view()).segments())
      r.y_min = std::min({r.y_min, c.a.y, c.b.y}), r.y_max = std::max({r.y_max, c.a.y, c.b.y});
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    if (r.t[i] >= arrive && r.t[i] < arrive + 1.5 * kPulse) r.incident = std::max(r.incident, std::abs(r.v[i]));
    if (r.t[i] >= back - 0.1 * kPulse && r.t[i] < back + 1.2 * kPulse && std::abs(r.v[i]) > r.reflected)
      r.reflected = std::abs(r.v[i]), r.reflected_at = r.t[i];
  }
  return r;
}

TEST(FractureWithAbsorbing, AColumnThatCracksReflectsAsLittleAsOneThatDoesNot) {
  const ColumnRun cracked = run_column(column(true), "cracking_column");
  const ColumnRun intact = run_column(column(false), "intact_column");
  const ColumnRun roller = run_column(column(false, false), "roller_column");
  // The cracking alone, without the pulse: what its own waves bring to the measure point.
  const ColumnRun alone = run_column(column(true, true, 1e-3), "cracks_alone");
  ASSERT_EQ(cracked.t.size(), intact.t.size());
  std::size_t first = 0, last = 0, recuts = 0;
  double worst_recut = 0, worst = 0, largest = 0;  // J/m: the absorbed column's steps against the intact run's
  for (std::size_t i = 1; i < cracked.segments.size(); ++i) {
    const double dc = cracked.absorbed[i] - cracked.absorbed[i - 1], di = intact.absorbed[i] - intact.absorbed[i - 1];
    largest = std::max(largest, di);
    worst = std::max(worst, std::abs(dc - di));
    if (cracked.segments[i] != cracked.segments[i - 1]) {
      if (!first) first = i;
      last = i;
      ++recuts;
      worst_recut = std::max(worst_recut, std::abs(dc - di));
    }
  }
  const double ratio = cracked.reflected / cracked.incident, ratio_intact = intact.reflected / intact.incident;
  std::printf("column: %zu crack segments in y %.2f..%.2f m, re-cut in %zu steps from t %.4g to %.4g s; "
              "reflected/incident %.4f (cracking), %.4f (not cracking), %.4f (roller base), the cracks' own waves "
              "alone %.4f; absorbed %.6g J/m (cracking), %.6g J/m (not); a step's absorbed work differs from the "
              "intact run's by at most %.3g J/m at a re-cut, %.3g J/m at any step (largest step %.3g J/m)\n",
              cracked.segments.back(), cracked.y_min, cracked.y_max, recuts, cracked.t[first], cracked.t[last], ratio,
              ratio_intact, roller.reflected / roller.incident, alone.reflected / cracked.incident,
              cracked.absorbed.back(), intact.absorbed.back(), worst_recut, worst, largest);
  std::printf("reflected peaks at %.4g s (cracking), %.4g s (alone), %.4g (intact); cracks alone: %zu segments\n",
              cracked.reflected_at, alone.reflected_at, intact.reflected_at, alone.segments.back());
  ASSERT_GT(recuts, 0u);
  EXPECT_LT(cracked.t[first], 0.1);  // the rock cracks while the pulse leaves through the base (0.06 to 0.1 s)
  EXPECT_GT(cracked.t[last], kHeight / kCp);
  EXPECT_GT(cracked.y_min, 45);  // away from the base and the measure point
  EXPECT_GT(roller.reflected / roller.incident, 0.9);
  EXPECT_LT(ratio_intact, 0.03);
  // As low as the absorbing boundaries' own bound (test_absorbing.cpp); what it has above the
  // intact column's arrives with the waves of the cracking (its peak within 1 ms of theirs).
  EXPECT_LT(ratio, 0.03);
  EXPECT_NEAR(cracked.reflected_at, alone.reflected_at, 1e-3);
  EXPECT_NEAR(cracked.absorbed.back(), intact.absorbed.back(), 0.01 * intact.absorbed.back());
  EXPECT_LT(worst_recut, 0.05 * largest);  // no jump in the absorbed column at a re-cut
}

// The carried reaction over a re-cut whose crack reaches the absorbing base and parts covers
// there: the reaction of a uniform traction on the base (its nodal forces ∫φ_c·t ds) comes out
// as the same traction's nodal forces on the new mesh, and a cover not parted keeps its part
// bit for bit.
TEST(FractureWithAbsorbing, TheCarriedReactionFollowsItsCoversOntoTheReCutMesh) {
  const json doc = json::parse(R"({
    "materials": {"rock": {"density": 2500, "young": 1e10, "poisson": 0.25,
                           "strength": {"tensile": 1e6, "cohesion": 4e6, "friction_deg": 35}}},
    "joint_sets": {"crack": {"friction_deg": 30, "normal": {"model": "constant", "kn": 1e11},
                             "shear": {"model": "constant", "ks": 4e10}}},
    "bodies": [{"material": "rock", "outer": [[0,0],[4,0],[4,4],[0,4]]}], "mesh": {"size": 0.5},
    "fracture": {"crack_set": "crack"},
    "absorbing": [{"points": [[0,0],[4,0]]}] })");
  const SceneDef before = scene_from_json(doc, "box");
  const Mesh old = pre::build_mesh(before, "box");
  SceneDef cracked = before;
  cracked.joints.push_back({cracked.fracture.crack_set, {{2.1, 0}, {2.1, 1.3}}});
  pre::RecutMap map;
  const Mesh now = pre::recut(old, cracked, before.joints.size(), "box", map);
  const solve::MeshBound was(old, before, "box"), is(now, cracked, "box", 1);
  // N/m per unknown: the nodal forces of a uniform traction t = (0.3, −1) MPa on the base.
  const auto nodal = [](const solve::MeshBound& b) {
    const Mesh& mesh = b.model.mesh();
    std::vector<double> r(static_cast<std::size_t>(b.space.unknowns()), 0.0);
    for (const auto& be : b.model.absorbing_edges()[0]) {
      const auto e = static_cast<std::size_t>(be.element);
      const double* p = &mesh.loop_xy[2 * static_cast<std::size_t>(be.vertex)];
      const double* q = &mesh.loop_xy[2 * static_cast<std::size_t>(be.next)];
      const double len = std::hypot(q[0] - p[0], q[1] - p[1]), mx = 0.5 * (p[0] + q[0]), my = 0.5 * (p[1] + q[1]);
      double nx[3], ny[3];
      for (int i = 0; i < 3; ++i) {
        const auto node = static_cast<std::size_t>(mesh.cover_node[static_cast<std::size_t>(mesh.element_covers[3 * e + i])]);
        nx[i] = mesh.node_xy[2 * node];
        ny[i] = mesh.node_xy[2 * node + 1];
      }
      const double twice = (nx[1] - nx[0]) * (ny[2] - ny[0]) - (nx[2] - nx[0]) * (ny[1] - ny[0]);
      for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        const double phi = ((nx[i] - mx) * (ny[j] - my) - (nx[j] - mx) * (ny[i] - my)) / twice;
        const auto u = static_cast<std::size_t>(b.space.first_unknown(static_cast<std::size_t>(mesh.element_covers[3 * e + k])));
        r[u] += 0.3e6 * len * phi;
        r[u + 1] -= 1e6 * len * phi;
      }
    }
    return r;
  };
  const std::vector<double> r_old = nodal(was), r_new = nodal(is);
  const std::vector<double> carried =
      solve::absorbing_reaction_onto(r_old, was.space, map.cover_parent, is.model, is.space);
  ASSERT_EQ(carried.size(), r_new.size());
  double worst = 0, sum_old[2] = {0, 0}, sum_new[2] = {0, 0};
  std::size_t parted = 0, kept = 0, bitwise = 0;
  std::vector<int> pieces(old.cover_count(), 0);
  for (const std::int32_t p : map.cover_parent) ++pieces[static_cast<std::size_t>(p)];
  for (std::size_t c = 0; c < now.cover_count(); ++c) {
    const auto u = static_cast<std::size_t>(is.space.first_unknown(c));
    const auto U = static_cast<std::size_t>(was.space.first_unknown(static_cast<std::size_t>(map.cover_parent[c])));
    if (r_old[U] == 0 && r_old[U + 1] == 0) continue;
    if (pieces[static_cast<std::size_t>(map.cover_parent[c])] > 1) {
      ++parted;
    } else {
      ++kept;
      bitwise += carried[u] == r_old[U] && carried[u + 1] == r_old[U + 1];
    }
  }
  for (std::size_t i = 0; i < carried.size(); ++i) worst = std::max(worst, std::abs(carried[i] - r_new[i]));
  for (std::size_t i = 0; i + 1 < r_old.size(); i += 2) sum_old[0] += r_old[i], sum_old[1] += r_old[i + 1];
  for (std::size_t i = 0; i + 1 < carried.size(); i += 2) sum_new[0] += carried[i], sum_new[1] += carried[i + 1];
  std::printf("reaction over a re-cut: %zu base covers parted, %zu kept (%zu bit for bit); largest difference from "
              "the new mesh's nodal forces %.3g N/m (of 4 MN/m); resultant (%.9g, %.9g) → (%.9g, %.9g) N/m\n",
              parted, kept, bitwise, worst, sum_old[0], sum_old[1], sum_new[0], sum_new[1]);
  EXPECT_GT(parted, 0u);
  EXPECT_EQ(bitwise, kept);
  EXPECT_LT(worst, 1e-9 * 4e6);
  EXPECT_NEAR(sum_new[1], -4e6, 1e-9 * 4e6);
  EXPECT_NEAR(sum_new[0], 1.2e6, 1e-9 * 4e6);
}

TEST(FractureWithAbsorbing, RestartsBeforeAndAfterTheReCutContinueBitForBit) {
  const std::vector<std::size_t> at = restarts_bit_for_bit(column(true), "cracking_column", 0.075, {0.053, 0.065});
  std::printf("cracking column: %zu and %zu crack segments at the checkpoints\n", at[0], at[1]);
  EXPECT_EQ(at[0], 0u);
  EXPECT_GT(at[1], 0u);
}

}  // namespace
}  // namespace nmm
