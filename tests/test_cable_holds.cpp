// A grouted cable holds what it runs through (solver/reinforcement/bolt_system.cpp: forces from
// the segments' exact lengths, their geometric stiffness in the step's matrix; docs/reinforcement.md
// "A cable across an opening joint"). None of these scenes holds a block sideways: the blocks are
// free to sway, and only the cable (and, on the slope, the joint's contact) keeps them.
//
// Pull-out under a load. A rock block R = [−2.5, 0] × [−0.5, 0.5] held on its far side, and a
// head block H = [0, 3.2] × [−0.5, 0.5], free, touching R along the frictionless joint x = 0
// (no tension: pulled away, it opens); both E = 1e12 Pa (rigid against the cable). One grouted
// cable on the axis y = 0 from (3.025, 0) in H to (−1.975, 0) in R, 100 segments of 0.05 m: the
// joint lies mid-segment, so the grout's tributary lengths tile L_H = 3.025 m and L_R = 1.975 m
// exactly. EA = 1.785e7 N, k_bond = 1.12e8 N/m per m, s_bond = 1.75e5 N/m (the issue's cable).
// A load P along the axis pulls H away from R.
//   Shear-lag stiffness K. In a rigid rock, a cable pulled at the rock's face by P carries
//   N(x) = P·sinh(λ(L − x))/sinh(λL) at depth x (EA·N'' = k_bond·N, N(0) = P, N'(L) = 0 at its
//   free end), λ = √(k_bond/EA), and its slip at the face is δ = P/(EA·λ·tanh λL) (the
//   integral of N/EA: its elongation relative to the rock). Across the joint the cable is pulled
//   out of both blocks by the same P, so the joint opens by the two slips:
//       w = P/K,   K = EA·λ / (coth λL_R + coth λL_H)
//   λ = 2.5049 1/m, λL_R = 4.947, λL_H = 7.577: K = 2.2355e7 N/m; P = 40 kN opens 1.7893 mm.
//   The grout is elastic while its largest force per metre, P·λ·coth λL_R, stays below s_bond:
//   P ≤ 69.8 kN.
//   Sideways, H is held only by the segment across the joint: its far end sways by v, its force
//   N turns by v/ℓ — a stiffness N/ℓ ≈ 40 kN / 0.0518 m = 7.7e5 N/m, which must be in the
//   step's matrix (with it outside, re-pointed at each step's start, the sway of a static step
//   grows |1 − (N/ℓ)·Δt²/(2m)| a step, m = 8000 kg/m: 2 at Δt = 0.25 s; and every dynamic step
//   treats it explicitly, growing at any Δt). A sideways kick of 1 % of P for 1 s, after the
//   load is on, sways H by a few tenths of a millimetre; it must come back and stay.
//   The load acts at (0.3, 0), 0.275 m from the segment's end in H, about which H is free to
//   turn. A dead load's moment about that point, P·a, holds H like a pendulum, but it enters a
//   step only through the geometry update (the rock's field is linear in the step: no load
//   stiffness), an explicit stiffness, which grows (ωΔt)²/4 a dynamic step (ω² = P·a/I):
//   ω = 0.64 1/s here, negligible at the Δt below; at a = 3 m, 2.1 1/s: 6 % a step at Δt = 0.25 s
//   (docs/reinforcement.md says so).
//
// The axial-force profile at P = 10, 30, 60 kN: each segment's force within 3 % of P of N(x)
// at its middle, on both sides of the joint.
//
// A block on a slope held by a grouted cable across its sliding joint: a 2 m × 1 m block on a
// base (the joint's springs constant, friction φ), gravity tilted by ψ = 35° (the slope),
// so that it slides (ψ > φ) unless the cable holds it.
//   (a) The cable at θ = 45° to the joint's normal, against the slide, φ = 20°: its force T at
//       the joint adds T·(sin θ + cos θ·tan φ) to the resistance, and the block stops where
//       W·(sin ψ − cos ψ·tan φ) = T·(sin θ + cos θ·tan φ) (W = 52.0 kN/m: T = 14.85 kN), having
//       slid s = T/(K·sin θ) (K as above with L = 1.131 m on each side: 2.219e7 N/m; s = 0.946 mm).
//   (b) The cable across the joint at θ = 0, the joint frictionless: the slide only turns the
//       segment across the joint, whose length grows as √(ℓ² + s²) and whose force's turn holds
//       the block: the geometric stiffness alone, no closed form (it depends on the segment's
//       length, a cable having no bending stiffness here; the grout next to the joint slips at
//       its strength). Its static slide the same at Δt = 0.01 s and 0.05 s within 1 %: the
//       block is loaded once, monotonically, so the steps it is taken in must not change where
//       it stops (forces carried as increments made it 5.2 %); and it stays, static or dynamic
//       (there the overshoot slips the grout further, and it stops farther down).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/math_constants.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "solver/stepping/time_stepper.h"
#include "tests/ended_ok.h"

namespace nmm::solve {
namespace {

using nlohmann::json;

constexpr double kEA = 1.785e7, kBond = 1.12e8;  // N, N/m per m
const double kLambda = std::sqrt(kBond / kEA);    // 1/m

/// N/m, the shear-lag stiffness of a cable pulled out of two rigid blocks at their joint.
double pull_out_stiffness(double l_one, double l_other) {
  return kEA * kLambda / (1 / std::tanh(kLambda * l_one) + 1 / std::tanh(kLambda * l_other));
}

constexpr double kLengthRock = 1.975, kLengthHead = 3.025;  // m, the cable in R and in H
constexpr int kJointSegment = 60;                            // the segment across x = 0

json pull_out_scene(double p, bool dynamic, double dt, double t_end, bool kick) {
  json doc = json::parse(R"({
    "materials": { "rigid": { "density": 2500, "young": 1e12, "poisson": 0.25 } },
    "bodies": [ { "material": "rigid", "outer": [[-2.5,-0.5],[0,-0.5],[0,0.5],[-2.5,0.5]] },
                { "material": "rigid", "outer": [[0,-0.5],[3.2,-0.5],[3.2,0.5],[0,0.5]] } ],
    "mesh": { "size": 0.25 },
    "supports": [ { "points": [[-2.5,0.5],[-2.5,-0.5]], "fix": "xy" } ],
    "measure_points": [[0.1, 0], [-0.1, 0], [3.1, 0.4]],
    "bolts": [ { "points": [[3.025, 0], [-1.975, 0]], "type": "grouted", "ea": 1.785e7,
                 "bond_stiffness": 1.12e8, "bond_strength": 1.75e5, "segments": 100 } ] })");
  doc["loads"] = json::array({{{"point", {0.3, 0}}, {"force", {p, 0}}, {"table", {{0, 0}, {1, 1}}}}});
  if (kick)  // 1 % of P sideways from t = 2 s to 3 s
    doc["loads"].push_back({{"point", {0.3, 0}}, {"force", {0, 0.01 * p}},
                            {"table", {{0, 0}, {2, 0}, {2.0001, 1}, {3, 1}, {3.0001, 0}}}});
  doc["solver"] = {{"time_step", dt}, {"steps", static_cast<int>(std::lround(t_end / dt))}, {"dynamic", dynamic}};
  return doc;
}

struct PullOut {
  double opening = 0;      // m, at the end: H's point less R's, along x
  double off = 0;          // m, the largest |opening − P/K| over the last 20 s
  double sway_peak = 0;    // m, the largest |u_y| of H at the joint (0.1, 0)
  double sway_mid = 0;     // m, the largest from t = 5 s to 30 s
  double sway_late = 0;    // m, from 30 s to 50 s
  double turn_mid = 0;     // rad, H's largest |turn| from 5 s to 30 s
  double turn_late = 0;    // rad, from 30 s to 50 s
  double joint_force = 0;  // N, the segment across the joint, at the end
  BoltState bolt;
};

PullOut pull_out(double p, bool dynamic, double dt, double t_end, bool kick) {
  const SceneDef scene = scene_from_json(pull_out_scene(p, dynamic, dt, t_end, kick), "pull_out");
  const Mesh mesh = pre::build_mesh(scene, "pull_out");
  TimeStepper st(mesh, scene, "pull_out");
  const double w = p / pull_out_stiffness(kLengthRock, kLengthHead);
  PullOut r;
  const auto opening = [&] {
    const auto& m = st.view().state.measure;
    return m[0].displacement()[0] - m[1].displacement()[0];
  };
  EXPECT_PRED1(test::ended_ok, st.run_until(t_end, [&](std::int64_t) {
    const auto& m = st.view().state.measure;
    const double t = st.view().state.time, uy = std::abs(m[0].displacement()[1]);
    const double turn = std::abs(std::atan2(m[2].y - m[0].y, m[2].x - m[0].x) - std::atan2(0.4, 3.0));
    r.sway_peak = std::max(r.sway_peak, uy);
    if (t >= 5 && t < 0.6 * t_end) {
      r.sway_mid = std::max(r.sway_mid, uy);
      r.turn_mid = std::max(r.turn_mid, turn);
    } else if (t >= 0.6 * t_end) {
      r.sway_late = std::max(r.sway_late, uy);
      r.turn_late = std::max(r.turn_late, turn);
      r.off = std::max(r.off, std::abs(opening() - w));
    }
  }));
  r.opening = opening();
  r.bolt = st.view().state.bolts.at(0);
  r.joint_force = r.bolt.axial.at(kJointSegment);
  return r;
}

TEST(BoltsHold, APulledOutCableOpensItsJointByPOverKAndHoldsTheFreeBlock) {
  // Static and dynamic, Δt from 0.01 s to 0.5 s; 50 s each. It holds: the opening stays within
  // 3 % of P/K over the last 20 s (no creep), the sway at the joint is bounded and does not grow
  // (static: it dies away; dynamic: H swings on as the pendulum the load makes it, undamped but
  // for Newmark's numerical damping, no wider than before), and the cable carries P across.
  const double p = 4e4, k = pull_out_stiffness(kLengthRock, kLengthHead), w = p / k;
  std::printf("pull-out: K = %.5g N/m, P/K = %.5g m\n", k, w);
  struct Case {
    bool dynamic;
    double dt;
  };
  for (const Case c : {Case{false, 0.05}, Case{false, 0.25}, Case{false, 0.5}, Case{true, 0.01}, Case{true, 0.05},
                       Case{true, 0.25}}) {
    const PullOut r = pull_out(p, c.dynamic, c.dt, 50.0, true);
    std::printf("  %s Δt = %.2f s: opening %.5g m (%+.2f %% of P/K; within %.2f %% over the last 20 s); sway at the "
                "joint %.2e m at most, %.2e m in 5–30 s, %.2e m in 30–50 s; H's turn %.2e / %.2e rad; joint "
                "segment %.1f N\n", c.dynamic ? "dynamic" : "static ", c.dt, r.opening, 100 * (r.opening / w - 1),
                100 * r.off / w, r.sway_peak, r.sway_mid, r.sway_late, r.turn_mid, r.turn_late, r.joint_force);
    EXPECT_LT(r.off, 0.03 * w);
    EXPECT_GT(r.sway_peak, 1e-4);  // the kick swayed it: it is free to sway
    EXPECT_LT(r.sway_peak, 2e-3);  // held: bounded
    EXPECT_LE(r.sway_late, 1.05 * r.sway_mid);
    EXPECT_LE(r.turn_late, 1.05 * r.turn_mid);
    if (!c.dynamic) {
      EXPECT_LT(r.sway_late, 0.05 * r.sway_peak);
    }
    EXPECT_NEAR(r.joint_force, p, 0.005 * p);  // H's balance along the axis: the cable carries P
    EXPECT_FALSE(r.bolt.yielded);
  }
}

TEST(BoltsHold, APulledOutCableCarriesTheShearLagProfileOnBothSides) {
  // Segment j's middle lies at 3.025 − 0.05·(j + ½) m: in H (x > 0) at depth x from the joint,
  // in R (x < 0) at depth −x.
  for (const double p : {1e4, 3e4, 6e4}) {
    const PullOut r = pull_out(p, false, 0.25, 20.0, false);
    double worst = 0;
    for (std::size_t j = 0; j < r.bolt.axial.size(); ++j) {
      const double x = kLengthHead - 0.05 * (static_cast<double>(j) + 0.5);
      const double l = x > 0 ? kLengthHead : kLengthRock, depth = std::abs(x);
      const double exact = p * std::sinh(kLambda * (l - depth)) / std::sinh(kLambda * l);
      worst = std::max(worst, std::abs(r.bolt.axial[j] - exact) / p);
    }
    const double w = p / pull_out_stiffness(kLengthRock, kLengthHead);
    std::printf("shear-lag profile at P = %.0f N: largest error %.3f %% of P over 100 segments; opening %+.2f %% "
                "of P/K\n", p, 100 * worst, 100 * (r.opening / w - 1));
    EXPECT_LT(worst, 0.03);
    EXPECT_NEAR(r.opening, w, 0.03 * w);
  }
}

// A block on a slope: gravity tilted by ψ = 35° (downslope +x), a 2 m × 1 m block on a 6 m × 1 m
// base held along its bottom, the joint's springs constant, friction φ.
struct Slope {
  double slid = 0;       // m, the block's displacement along the slope at the end
  double peak = 0;       // m, the largest over the run
  double late_move = 0;  // m, its largest change over the last 40 % of the run
  double joint_force = 0;
};
constexpr double kPsi = 35 * kPi / 180;

Slope slope(const json& cable, double friction_deg, bool dynamic, double dt, double t_end) {
  json doc = json::parse(R"({
    "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 } },
    "bodies": [ { "material": "rock", "outer": [[0,0],[6,0],[6,1],[0,1]] },
                { "material": "rock", "outer": [[1.5,1],[3.5,1],[3.5,2],[1.5,2]] } ],
    "mesh": { "size": 0.25 },
    "supports": [ { "points": [[0,0],[6,0]], "fix": "xy" } ],
    "measure_points": [[2.5, 1.5]] })");
  doc["gravity"] = {9.81 * std::sin(kPsi), -9.81 * std::cos(kPsi)};
  doc["joint_sets"] = {{"base", {{"friction_deg", friction_deg}, {"normal", {{"model", "constant"}, {"kn", 4e11}}},
                                 {"shear", {{"model", "constant"}, {"ks", 1.6e11}}}}}};
  doc["interface_set"] = "base";
  if (!cable.is_null()) doc["bolts"] = json::array({cable});
  doc["solver"] = {{"time_step", dt}, {"steps", static_cast<int>(std::lround(t_end / dt))}, {"dynamic", dynamic}};
  const SceneDef scene = scene_from_json(doc, "slope");
  const Mesh mesh = pre::build_mesh(scene, "slope");
  TimeStepper st(mesh, scene, "slope");
  Slope r;
  std::vector<double> late;
  EXPECT_PRED1(test::ended_ok, st.run_until(t_end, [&](std::int64_t) {
    const double u = st.view().state.measure[0].displacement()[0];
    r.peak = std::max(r.peak, std::abs(u));
    if (st.view().state.time >= 0.6 * t_end) late.push_back(u);
  }));
  r.slid = st.view().state.measure[0].displacement()[0];
  for (double u : late) r.late_move = std::max(r.late_move, std::abs(u - r.slid));
  if (!cable.is_null()) {
    const BoltState& b = st.view().state.bolts.at(0);
    r.joint_force = b.axial.at(b.axial.size() / 2);  // 23 segments: the 12th crosses the joint
  }
  return r;
}

json cable(double hx, double hy, double ax, double ay) {
  return {{"points", {{hx, hy}, {ax, ay}}}, {"type", "grouted"}, {"ea", kEA}, {"bond_stiffness", kBond},
          {"bond_strength", 1.75e5}, {"segments", 23}};
}

TEST(BoltsHold, ACableAcrossItsSlidingJointHoldsABlockOnASlope) {
  // (a) θ = 45°: from (3.0, 1.8) in the block to (1.4, 0.2) in the base, crossing the joint
  // y = 1 at its middle (x = 2.2).
  const double phi = 20 * kPi / 180, theta = kPi / 4, w = 2650 * 9.81 * 2;
  const double t = w * (std::sin(kPsi) - std::cos(kPsi) * std::tan(phi)) / (std::sin(theta) + std::cos(theta) * std::tan(phi));
  const double half = 0.5 * std::hypot(1.6, 1.6), s = t / (pull_out_stiffness(half, half) * std::sin(theta));
  const json inclined = cable(3.0, 1.8, 1.4, 0.2);
  // Without the cable it slides, accelerated by g·(sin ψ − cos ψ·tan φ): ½·a·t² in 1 s.
  const double a = 9.81 * (std::sin(kPsi) - std::cos(kPsi) * std::tan(phi));
  const Slope free = slope(nullptr, 20, true, 0.01, 1.0);
  std::printf("slope ψ 35°, φ 20°: without the cable the block slid %.4g m in 1 s (½at² = %.4g m); T = %.1f N, "
              "s = %.4g m\n", free.slid, 0.5 * a, t, s);
  EXPECT_NEAR(free.slid, 0.5 * a, 0.03 * 0.5 * a);
  for (const bool dynamic : {false, true}) {
    const Slope r = slope(inclined, 20, dynamic, 0.01, 3.0);
    std::printf("  θ 45°, %s: slid %.4g m (peak %.4g, %+.2f %% of s), moved %.2e m over the last 1.2 s; "
                "cable at the joint %.1f N (%+.2f %% of T)\n", dynamic ? "dynamic" : "static ", r.slid, r.peak,
                100 * (r.slid / s - 1), r.late_move, r.joint_force, 100 * (r.joint_force / t - 1));
    EXPECT_LT(r.late_move, 1e-3 * s);  // it stays
    if (!dynamic) {  // from rest at every step: it arrives at the balance, friction fully mobilised
      EXPECT_NEAR(r.slid, s, 0.03 * s);
      EXPECT_NEAR(r.joint_force, t, 0.03 * t);
    } else {  // it overshoots (at most twice the static slide under a sudden load) and friction locks it
      EXPECT_GT(r.slid, 0.9 * s);
      EXPECT_LT(r.peak, 2 * s);
    }
  }
  // (b) θ = 0, frictionless: held by the turn of the segment across the joint alone.
  const json across = cable(2.5, 1.8, 2.5, 0.2);
  const Slope fine = slope(across, 0, false, 0.01, 10.0), coarse = slope(across, 0, false, 0.05, 10.0);
  const Slope moving = slope(across, 0, true, 0.01, 10.0);
  std::printf("  θ 0, frictionless: static slid %.5g m at Δt 0.01 s, %.5g m at 0.05 s (%+.2f %%); dynamic %.5g m "
              "(peak %.5g); moved %.2e / %.2e / %.2e m over the last 4 s; cable at the joint %.0f N\n",
              fine.slid, coarse.slid, 100 * (coarse.slid / fine.slid - 1), moving.slid, moving.peak, fine.late_move,
              coarse.late_move, moving.late_move, fine.joint_force);
  EXPECT_NEAR(coarse.slid, fine.slid, 0.01 * fine.slid);
  EXPECT_LT(fine.late_move, 1e-3 * fine.slid);
  EXPECT_LT(coarse.late_move, 1e-3 * fine.slid);
  EXPECT_LT(moving.late_move, 1e-3 * fine.slid);
  EXPECT_LT(moving.peak, 2 * fine.slid);
}

}  // namespace
}  // namespace nmm::solve
