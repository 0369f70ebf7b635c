// Rock bolts and cables (solver/reinforcement/, docs/reinforcement.md) against closed forms:
//   - a grouted cable pulled at its head: the axial force along it follows the shear-lag
//     solution N(x) = P0·sinh(λ(L − x))/sinh(λL), λ = √(k_bond/EA), while the grout is elastic;
//   - pulled out by a moving support, it carries at most min(bond_strength·L, yield);
//   - an anchored bolt across a sliding joint adds P·(sinθ + cosθ·tanφ) to its shear
//     resistance; one whose force reaches its strength breaks, and the block slides;
//   - a pretensioned bolt in a block turned through 120° keeps its force and turns with it;
//   - a restart continues bolts bitwise, and bolts can be added at a restart.
// Every scene is a pair of blocks held or loaded as the closed form assumes: the cable's rock
// 5 × stiffer than needed for its displacement to matter (E = 50 GPa against EA = 1.8e7 N).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "common/math_constants.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "solver/contact/contact_history.h"
#include "solver/stepping/restart.h"
#include "solver/stepping/time_stepper.h"
#include "tests/ended_ok.h"

namespace nmm::solve {
namespace {

using nlohmann::json;

double rad(double deg) { return deg * kPi / 180; }

// Two blocks along x: the rock B = [0, 2] × [0, 1], held on its left side and base, and the
// plate A = [2, 5] × [0, 1] on rollers along its top (y held), touching B along x = 2 (the
// default interface: frictionless, no tension, so pulled away it opens). A grouted cable from
// (4.55, 0.5) in A to (0.45, 0.5) in B, 41 segments of 0.1 m: the face x = 2 lies mid-segment, so
// the grout's tributary lengths tile B's length L = 1.55 m exactly. Static (K d = F).
json pull_out_scene() {
  return json::parse(R"({
    "materials": { "rock": { "density": 2500, "young": 5e10, "poisson": 0.25 } },
    "bodies": [ { "material": "rock", "outer": [[0,0],[2,0],[2,1],[0,1]] },
                { "material": "rock", "outer": [[2,0],[5,0],[5,1],[2,1]] } ],
    "mesh": { "size": 0.25 },
    "supports": [ { "points": [[0,1],[0,0],[2,0]], "fix": "xy" },
                  { "points": [[2,1],[5,1]], "fix": "y" } ],
    "bolts": [ { "points": [[4.55, 0.5], [0.45, 0.5]], "type": "grouted", "ea": 1.8e7,
                 "bond_stiffness": 1.1e8, "bond_strength": 1.75e5, "yield": 5e5, "segments": 41 } ],
    "solver": { "time_step": 1, "steps": 1, "dynamic": false, "static_mode": "equilibrium" } })");
}

constexpr double kEmbedded = 1.55;  // m, the cable's length in B
constexpr double kFace = 2.55;      // m, along the cable from its head to the face x = 2

struct Built {
  SceneDef scene;
  Mesh mesh;
};

Built make(const json& doc, const char* name) {
  Built r{scene_from_json(doc, name), {}};
  r.mesh = pre::build_mesh(r.scene, name);
  return r;
}

TEST(Bolts, GroutedCablePulledAtItsHeadFollowsTheShearLagSolution) {
  // P0 = 50 kN on the plate: the cable's force falls along B as sinh(λ(L − x))/sinh(λL)
  // (λL = 3.83: not yet a plain exponential), the grout elastic (k·slip < 1.75e5 N/m at the face,
  // where it is largest: P0·λ·coth(λL) = 1.24e5 N/m). Each segment carries one force, the
  // solution's at its middle to second order: compared there, every segment in B within 3 % of P0.
  json doc = pull_out_scene();
  doc["loads"] = json::parse(R"([{ "point": [4.5, 0.5], "force": [5e4, 0] }])");
  const Built r = make(doc, "shear_lag");
  TimeStepper st(r.mesh, r.scene, "shear_lag");
  ASSERT_PRED1(test::ended_ok, st.attempt(1.0));
  const BoltState& b = st.view().state.bolts.at(0);
  const double lambda = std::sqrt(1.1e8 / 1.8e7), p0 = 5e4;
  double worst = 0, at_face = 0;
  for (std::size_t j = 0; j < b.axial.size(); ++j) {
    const double x = (j + 0.5) * 0.1 - kFace;  // the segment's middle, from the face into B
    if (x < 0) continue;
    const double exact = p0 * std::sinh(lambda * (kEmbedded - x)) / std::sinh(lambda * kEmbedded);
    worst = std::max(worst, std::abs(b.axial[j] - exact) / p0);
    if (j == 26) at_face = b.axial[j];
  }
  // The segment across the face carries P0 itself (the plate's balance: nothing else holds it).
  std::printf("shear lag: λ = %.3f 1/m, λL = %.2f; largest error over B's segments %.2f %% of P0; "
              "across the face %.1f N of %.0f\n", lambda, lambda * kEmbedded, 100 * worst, b.axial[25], p0);
  EXPECT_LT(worst, 0.03);
  EXPECT_NEAR(b.axial[25], p0, 1e-6 * p0);
  EXPECT_GT(at_face, 0.5 * p0);
  EXPECT_FALSE(b.yielded);
  // A wrong λ (grout per node instead of per metre: √10 larger here) would be off by ~40 % of P0.
}

// Pulled out by the plate's far side, moved 1 mm per static step for 120 steps: the largest axial
// force the cable reaches.
double pull_out_capacity(double yield, bool* yielded) {
  json doc = pull_out_scene();
  doc["bolts"][0]["yield"] = yield;
  doc["supports"].push_back(json::parse(R"({ "points": [[5,0],[5,1]], "fix": "x", "velocity": [1e-3, 0] })"));
  const Built r = make(doc, "pull_out");
  TimeStepper st(r.mesh, r.scene, "pull_out");
  EXPECT_PRED1(test::ended_ok, st.run_until(120.0, [](std::int64_t) {}));
  *yielded = st.view().state.bolts[0].yielded != 0;
  return st.view().state.bolts[0].max_axial;
}

TEST(Bolts, GroutedCablePullsOutAtItsBondOrYieldCapacity) {
  // Bond: the whole embedded length slips, 1.75e5 N/m × 1.55 m = 271.25 kN (the plate's 2.55 m
  // holds more); yield 150 kN: the steel at the face yields first.
  bool yielded = true;
  const double bond = pull_out_capacity(5e5, &yielded);
  std::printf("pull-out: bond-limited %.1f N (closed form %.1f), ", bond, 1.75e5 * kEmbedded);
  EXPECT_NEAR(bond, 1.75e5 * kEmbedded, 0.02 * 1.75e5 * kEmbedded);
  EXPECT_FALSE(yielded);
  const double steel = pull_out_capacity(1.5e5, &yielded);
  std::printf("yield-limited %.1f N (yield 150000)\n", steel);
  EXPECT_NEAR(steel, 1.5e5, 0.02 * 1.5e5);
  EXPECT_TRUE(yielded);
}

// A 2 m × 1 m block on a 4 m × 1 m base held along its bottom, joint friction 30° (constant
// springs, Pa/m), gravity; dynamic, Δt = 2 ms.
json block_on_base() {
  return json::parse(R"({
    "gravity": [0, -9.81],
    "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 } },
    "joint_sets": { "base": { "friction_deg": 30, "normal": { "model": "constant", "kn": 4e11 },
                              "shear": { "model": "constant", "ks": 1.6e11 } } },
    "interface_set": "base",
    "bodies": [ { "material": "rock", "outer": [[0,0],[4,0],[4,1],[0,1]] },
                { "material": "rock", "outer": [[1,1],[3,1],[3,2],[1,2]] } ],
    "mesh": { "size": 0.25 },
    "supports": [ { "points": [[0,0],[4,0]], "fix": "xy" } ],
    "solver": { "time_step": 2e-3 } })");
}

// A 2 m × 1 m block on a base, friction 30°, gravity; a horizontal force H on it ramped up over
// 0.1 s from t = 0.05 s and then held; an anchored bolt from the block into the base at θ = 30°
// to the joint's normal, pretensioned to P (its tension pulls the block down and back: against
// sliding in +x), soft (1e4 N/m: the force stays P within 0.1 % over a centimetre of slide).
// Returns how far the block moved by t = 0.4 s (m), and the bolt's state.
struct Slide {
  double moved = 0;
  BoltState bolt;
};
Slide bolted_block(double h_force, double pretension, double strength, double stiffness = 1e4) {
  const double theta = rad(30), l = 1.2;
  const double hx = 2.3, hy = 1.6;  // the bolt's head in the block
  json doc = block_on_base();
  doc["measure_points"] = {{2, 1.5}};
  doc["loads"] = json::array({{{"point", {2, 1.5}}, {"force", {h_force, 0}},
                               {"table", {{0, 0}, {0.05, 0}, {0.15, 1}}}}});
  json bolt = {{"points", {{hx, hy}, {hx - l * std::sin(theta), hy - l * std::cos(theta)}}},
               {"type", "anchored"}, {"stiffness", stiffness}, {"pretension", pretension}};
  if (strength > 0) bolt["strength"] = strength;
  doc["bolts"] = json::array({bolt});
  const Built r = make(doc, "bolted_block");
  TimeStepper st(r.mesh, r.scene, "bolted_block");
  EXPECT_PRED1(test::ended_ok, st.run_until(0.4, [](std::int64_t) {}));
  const auto u = st.view().state.measure[0].displacement();
  return {std::hypot(u[0], u[1]), st.view().state.bolts[0]};
}

TEST(Bolts, BoltAcrossASlidingJointAddsItsForceToTheShearResistance) {
  // R = W·tanφ + P·(sinθ + cosθ·tanφ): W = 52.0 kN/m, P = 20 kN → 30.0 + 20.0 = 50.0 kN/m. At
  // 0.98·R the block holds (moves elastically, micrometres), at 1.02·R it slides (millimetres).
  // Had the bolt added only P·sinθ (no normal share) or only P·cosθ·tanφ, R would be 40.0 kN/m
  // and the block would slide at 0.98·R.
  const double w = 2650 * 9.81 * 2, tan_phi = std::tan(rad(30)), p = 2e4, theta = rad(30);
  const double r = w * tan_phi + p * (std::sin(theta) + std::cos(theta) * tan_phi);
  const Slide below = bolted_block(0.98 * r, p, 0), above = bolted_block(1.02 * r, p, 0);
  std::printf("bolted joint: R = %.0f N/m (W tanφ %.0f, bolt %.0f); at 0.98 R moved %.3e m, at 1.02 R %.3e m; "
              "bolt force %.1f / %.1f N\n", r, w * tan_phi, r - w * tan_phi, below.moved, above.moved,
              below.bolt.axial[0], above.bolt.axial[0]);
  EXPECT_LT(below.moved, 2e-4);
  EXPECT_GT(above.moved, 2e-3);
  EXPECT_NEAR(below.bolt.axial[0], p, 0.01 * p);
}

TEST(Bolts, AnchoredBoltBreaksAtItsStrength) {
  // The same block at 1.02·R with a bolt of strength P + 200 N and stiffness 1e6 N/m: as the
  // block starts to slide the bolt stretches, reaches its strength within 0.2 mm, breaks (force
  // 0 from then on), and the block, held by friction alone, slides away.
  const double w = 2650 * 9.81 * 2, tan_phi = std::tan(rad(30)), p = 2e4, theta = rad(30);
  const double r = w * tan_phi + p * (std::sin(theta) + std::cos(theta) * tan_phi);
  const Slide s = bolted_block(1.02 * r, p, p + 200, 1e6);
  std::printf("bolt broken: %d, its largest force %.1f N (strength %.1f), now %.1f N; the block moved %.3f m\n",
              s.bolt.broken, s.bolt.max_axial, p + 200, s.bolt.axial[0], s.moved);
  EXPECT_TRUE(s.bolt.broken);
  EXPECT_EQ(s.bolt.axial[0], 0.0);
  EXPECT_DOUBLE_EQ(s.bolt.max_axial, p + 200);
  const Slide held = bolted_block(1.02 * r, p, 0);
  EXPECT_GT(s.moved, 5 * held.moved);  // no bolt to hold it: it slides faster
}

TEST(Bolts, APretensionedBoltTurnsWithItsBlockAndKeepsItsForce) {
  // A free 1 m × 1 m block (no gravity) spun by a couple for 0.1 s, then turning freely at about
  // 5 rad/s through 120°. Its bolt, pretensioned to 100 kN between (0.1, 0.3) and (0.9, 0.7), is
  // a self-balanced pair of forces on the block: it must keep 100 kN — less what the rock's
  // elastic shortening under it takes off (the lock-off loss: 3.5 % with a bolt of 1e8 N/m,
  // 0.04 % with this 1e6 N/m one) — and turn with the block. A bolt linearised in its installed
  // direction would stretch by |r|·sin(turn)·Δθ every step: 10⁵ N within the turn.
  json doc = json::parse(R"({
    "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 } },
    "bodies": [ { "material": "rock", "outer": [[0,0],[1,0],[1,1],[0,1]] } ],
    "mesh": { "size": 0.2 },
    "loads": [ { "point": [0.5, 1], "force": [-2.2e4, 0], "table": [[0, 1], [0.1, 1], [0.1001, 0]] },
               { "point": [0.5, 0], "force": [2.2e4, 0], "table": [[0, 1], [0.1, 1], [0.1001, 0]] } ],
    "measure_points": [[0.2, 0.2], [0.8, 0.8]],
    "bolts": [ { "points": [[0.1, 0.3], [0.9, 0.7]], "type": "anchored", "stiffness": 1e6, "pretension": 1e5 } ],
    "solver": { "time_step": 1e-3 } })");
  const Built r = make(doc, "turning");
  TimeStepper st(r.mesh, r.scene, "turning");
  ASSERT_PRED1(test::ended_ok, st.run_until(0.5, [](std::int64_t) {}));
  const RunState& s = st.view().state;
  const auto angle = [](double ax, double ay, double bx, double by) { return std::atan2(by - ay, bx - ax); };
  const double block_turn = angle(s.measure[0].x, s.measure[0].y, s.measure[1].x, s.measure[1].y) - rad(45);
  const BoltState& b = s.bolts[0];
  const double bolt_turn = angle(b.nodes[0].x, b.nodes[0].y, b.nodes[1].x, b.nodes[1].y) -
                           angle(b.nodes[0].x0, b.nodes[0].y0, b.nodes[1].x0, b.nodes[1].y0);
  std::printf("turning block: turned %.2f°, its bolt %.2f°; bolt force %.3f kN (pretension 100)\n",
              block_turn * 180 / kPi, bolt_turn * 180 / kPi, b.axial[0] / 1e3);
  EXPECT_GT(block_turn, rad(100));
  EXPECT_NEAR(bolt_turn, block_turn, rad(0.5));
  EXPECT_NEAR(b.axial[0], 1e5, 2e-3 * 1e5);
}

TEST(Bolts, RestartContinuesBoltsBitwiseAndAddsThemAtARestart) {
  // The bolted block of the sliding test at 1.02·R, with a grouted cable beside the anchored
  // bolt. Run 1: 30 steps without bolts. Then bolts added at a restart, installed at step 30
  // with their own pretension only: 2 × 40 steps through a checkpoint in memory, against 80
  // straight: bitwise equal states.
  const double w = 2650 * 9.81 * 2, tan_phi = std::tan(rad(30));
  json doc = block_on_base();
  doc["loads"] = json::array({{{"point", {2, 1.5}}, {"force", {1.3 * w * tan_phi, 0}}}});
  const Built plain = make(doc, "plain");
  json bolted = doc;
  bolted["bolts"] = json::parse(R"([
      { "points": [[2.3, 1.6], [1.7, 0.56]], "type": "anchored", "stiffness": 1e7, "pretension": 2e4 },
      { "points": [[1.5, 1.8], [1.5, 0.3]], "type": "grouted", "ea": 1.8e7, "bond_stiffness": 1.1e8,
        "bond_strength": 1e5, "yield": 2e5 } ])");
  const SceneDef bolted_scene = scene_from_json(bolted, "bolted");
  TimeStepper first(plain.mesh, plain.scene, "plain");
  ASSERT_PRED1(test::ended_ok, first.run_until(0.06, [](std::int64_t) {}));
  const std::string history = save_contact_history(first.view().contacts);
  TimeStepper straight(plain.mesh, bolted_scene, "bolted");
  straight.restore(first.view().state, history, "memory");
  ASSERT_EQ(straight.view().state.bolts.size(), 2u);
  EXPECT_EQ(straight.view().state.bolts[0].installed_step, 30);
  EXPECT_EQ(straight.view().state.bolts[0].axial[0], 2e4);  // its pretension, nothing of the 30 steps
  ASSERT_PRED1(test::ended_ok, straight.run_until(0.06 + 0.16, [](std::int64_t) {}));
  TimeStepper half(plain.mesh, bolted_scene, "bolted");
  half.restore(first.view().state, history, "memory");
  ASSERT_PRED1(test::ended_ok, half.run_until(0.06 + 0.08, [](std::int64_t) {}));
  // Through a checkpoint file: the state, the contact history and the factorisation the contact
  // solve goes on from (restart.h), as nmm-solve --restart reads it.
  const std::string path = std::string(NMM_TEST_WORK) + "/bolts_restart.nmmstate";
  write_checkpoint(half.view(), path);
  TimeStepper second(plain.mesh, bolted_scene, "bolted");
  second.restart_from(path);
  ASSERT_PRED1(test::ended_ok, second.run_until(0.06 + 0.16, [](std::int64_t) {}));
  const BoltState& a = straight.view().state.bolts[0];
  const BoltState& c = straight.view().state.bolts[1];
  std::printf("restart: anchored bolt %.1f N, cable's largest force %.1f N, its largest slip %.3e m\n", a.axial[0],
              c.max_axial, *std::max_element(c.slip.begin(), c.slip.end(), [](double x, double y) {
                return std::abs(x) < std::abs(y);
              }));
  EXPECT_GT(c.max_axial, 1e3);  // the sliding block loads the cable across the joint
  EXPECT_EQ(state_hash(second.view()), state_hash(straight.view()));
}

}  // namespace
}  // namespace nmm::solve
