// Absorbing (viscous) boundaries (solver/discretisation/absorbing_boundary.h,
// docs/absorbing-boundaries.md) against what Lysmer and Kuhlemeyer's dashpots do to body waves:
//   - a P pulse and an S pulse travelling down a column leave through an absorbing base, the
//     reflected amplitude below 3 % of the incident one (a roller base sends back nearly all);
//   - a vertically incident S wave brought in through a compliant base (input velocity v_in,
//     traction 2ρc·v_in) doubles at the free surface: 2·v_in, within 3 %;
//   - the energy the dashpots take out is what the pulse brought in (energy.csv's absorbed);
//   - a model in in-situ equilibrium held by absorbing boundaries alone stays still, static or
//     dynamic: they carry the static reaction;
//   - a restart continues an absorbing run bitwise.
// The column: ρ = 2000 kg/m³, E = 1.667 GPa, ν = 0.25, plane strain, so cp = √((λ + 2G)/ρ) =
// 1000 m/s and cs = √(G/ρ) = 577.4 m/s; its sides on rollers that leave the wave one-dimensional
// (x held for P, y held for S). The pulse: a Hann pulse of duration T, sin²(πt/T).
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
#include "solver/contact/contact_history.h"
#include "solver/output/energy.h"
#include "solver/stepping/time_stepper.h"
#include "tests/ended_ok.h"

namespace nmm::solve {
namespace {

using nlohmann::json;

constexpr double kRho = 2000, kYoung = 1.0 / 0.6 * 1e9, kCp = 1000, kCs = 577.35026918962575;

/// A Hann pulse of duration t_pulse and peak `peak`, as a time table of 41 rows (then 0).
json hann(double t_pulse, double peak, double start = 0) {
  json rows = json::array();
  for (int i = 0; i <= 40; ++i) {
    const double t = t_pulse * i / 40, s = std::sin(kPi * t / t_pulse);
    rows.push_back({start + t, peak * s * s});
  }
  return rows;
}

/// A column [0, width] × [0, height] of the material above, mesh h = 0.5 m, its sides on
/// rollers holding `held` ("x" for P, "y" for S), a measure point at (width/2, y_point).
json column(double width, double height, const char* held, double y_point) {
  json doc = json::parse(R"({
    "materials": { "rock": { "density": 2000, "young": 1.6666666666666667e9, "poisson": 0.25 } },
    "mesh": { "size": 0.5 } })");
  doc["bodies"] = json::array({{{"material", "rock"}, {"outer", {{0, 0}, {width, 0}, {width, height}, {0, height}}}}});
  doc["supports"] = json::array({{{"points", {{0, 0}, {0, height}}}, {"fix", held}},
                                 {{"points", {{width, 0}, {width, height}}}, {"fix", held}}});
  doc["measure_points"] = json::array({{width / 2, y_point}});
  return doc;
}

struct Trace {
  std::vector<double> t, v;  ///< s, and the measure point's velocity (m/s) in the wave's direction
  double absorbed = 0, load_work = 0, kinetic_strain = 0;  ///< J/m, energy.csv's at the end
  double damped = 0, residual = 0;                          ///< J/m, energy.csv's at the end
};

/// Runs `doc` for `steps` steps of dt; the measure point's velocity along `axis` (0 x, 1 y),
/// Δu/Δt of each step.
Trace run_column(const json& doc, double dt, int steps, int axis, const char* name) {
  const SceneDef s = scene_from_json(doc, name);
  const Mesh m = pre::build_mesh(s, name);
  TimeStepper st(m, s, name);
  EnergyMeter energy(st.view().model);
  energy.after_step(st.view().state, energy_sources(st.view()), false);
  Trace tr;
  double before = 0;
  for (int i = 0; i < steps; ++i) {
    const Outcome o = st.attempt(dt);
    EXPECT_PRED1(test::ended_ok, o);
    if (!o.ok()) break;
    const double u = st.view().state.measure[0].displacement()[static_cast<std::size_t>(axis)];
    tr.t.push_back(st.view().state.time);
    tr.v.push_back((u - before) / dt);
    before = u;
    energy.after_step(st.view().state, energy_sources(st.view()), false);
  }
  energy.keep_last();
  const EnergyRow& e = energy.rows().back();
  tr.absorbed = e.absorbed;
  tr.load_work = e.load_work;
  tr.kinetic_strain = e.kinetic + e.strain;
  tr.damped = e.damped;
  tr.residual = e.residual;
  return tr;
}

/// Largest |v| over t0 ≤ t < t1.
double peak(const Trace& tr, double t0, double t1) {
  double p = 0;
  for (std::size_t i = 0; i < tr.t.size(); ++i)
    if (tr.t[i] >= t0 && tr.t[i] < t1) p = std::max(p, std::abs(tr.v[i]));
  return p;
}

// The pulse comes in through a traction on the column's top; the measure point sees it pass,
// and then what the base sends back, after the wave has gone down to the base and up again.
struct Reflection {
  double incident = 0, reflected = 0;  ///< m/s
  double absorbed = 0, input = 0, left = 0, damped = 0, residual = 0;  ///< J/m
};
Reflection reflection(bool p_wave, bool absorbing) {
  const double c = p_wave ? kCp : kCs, t_pulse = 0.04, height = 60, depth = 20;  // point 20 m below the top
  json doc = column(1, height, p_wave ? "x" : "y", height - depth);
  doc["tractions"] = json::array({{{"points", {{0, height}, {1, height}}}, {p_wave ? "normal" : "shear", -1e5},
                                   {"table", hann(t_pulse, 1)}}});
  if (absorbing)
    doc["absorbing"] = json::array({{{"points", {{0, 0}, {1, 0}}}}});
  else
    doc["supports"].push_back({{"points", {{0, 0}, {1, 0}}}, {"fix", p_wave ? "y" : "x"}});
  const double dt = 1e-4, arrive = depth / c, back = (2 * height - depth) / c;
  const Trace tr = run_column(doc, dt, static_cast<int>((back + 1.2 * t_pulse) / dt), p_wave ? 1 : 0,
                              p_wave ? "p_column" : "s_column");
  Reflection r;
  r.incident = peak(tr, arrive, arrive + 1.5 * t_pulse);
  r.reflected = peak(tr, back - 0.1 * t_pulse, back + 1.2 * t_pulse);
  r.absorbed = tr.absorbed;
  r.input = tr.load_work;
  r.left = tr.kinetic_strain;
  r.damped = tr.damped;
  r.residual = tr.residual;
  return r;
}

TEST(Absorbing, APPulseLeavesThroughAnAbsorbingBase) {
  const Reflection a = reflection(true, true), fixed = reflection(true, false);
  std::printf("P pulse: incident %.4f m/s (σ/ρcp = %.4f); reflected by the absorbing base %.5f m/s (%.2f %%), "
              "by a roller base %.4f m/s (%.1f %%)\n", a.incident, 1e5 / (kRho * kCp), a.reflected,
              100 * a.reflected / a.incident, fixed.reflected, 100 * fixed.reflected / fixed.incident);
  std::printf("  energy: the traction's work %.3f J/m, absorbed %.3f J/m, left in the column %.4f J/m, damped by "
              "the scheme %.3f J/m, residual %.3f J/m\n", a.input, a.absorbed, a.left, a.damped, a.residual);
  EXPECT_NEAR(a.incident, 1e5 / (kRho * kCp), 0.03 * 1e5 / (kRho * kCp));
  EXPECT_LT(a.reflected, 0.03 * a.incident);
  EXPECT_GT(fixed.reflected, 0.9 * fixed.incident);
  // What came in left through the base: the dashpots took it (the scheme's damping the rest).
  EXPECT_NEAR(a.absorbed, a.input, 0.05 * a.input);
  EXPECT_LT(a.left, 0.01 * a.input);
}

TEST(Absorbing, AnSPulseLeavesThroughAnAbsorbingBase) {
  const Reflection a = reflection(false, true), fixed = reflection(false, false);
  std::printf("S pulse: incident %.4f m/s (τ/ρcs = %.4f); reflected by the absorbing base %.5f m/s (%.2f %%), "
              "by a roller base %.4f m/s (%.1f %%)\n", a.incident, 1e5 / (kRho * kCs), a.reflected,
              100 * a.reflected / a.incident, fixed.reflected, 100 * fixed.reflected / fixed.incident);
  EXPECT_NEAR(a.incident, 1e5 / (kRho * kCs), 0.03 * 1e5 / (kRho * kCs));
  EXPECT_LT(a.reflected, 0.03 * a.incident);
  EXPECT_GT(fixed.reflected, 0.9 * fixed.incident);
  EXPECT_NEAR(a.absorbed, a.input, 0.05 * a.input);
}

TEST(Absorbing, AnSWaveBroughtInThroughACompliantBaseDoublesAtTheFreeSurface) {
  // v_in = 0.05 m/s peak, a Hann pulse of 0.1 s, up a 30 m column to its free top: the surface
  // moves at 2·v_in. Then the wave goes down again and leaves through the base it came in by.
  const double v_in = 0.05, t_pulse = 0.1, height = 30;
  json doc = column(1, height, "y", height);
  doc["absorbing"] = json::array({{{"points", {{0, 0}, {1, 0}}}, {"input_velocity", {{"x", hann(t_pulse, v_in)}}}}});
  const double dt = 2e-4, up = height / kCs;
  const Trace tr = run_column(doc, dt, static_cast<int>((3 * up + t_pulse) / dt), 0, "compliant");
  const double surface = peak(tr, 0, up + t_pulse + 0.01);
  std::printf("compliant base: surface velocity %.5f m/s, 2·v_in = %.5f (%.2f %%); left in the column %.3e J/m "
              "of %.3f brought in\n", surface, 2 * v_in, 100 * (surface / (2 * v_in) - 1), tr.kinetic_strain, tr.load_work);
  EXPECT_NEAR(surface, 2 * v_in, 0.03 * 2 * v_in);
  EXPECT_LT(tr.kinetic_strain, 0.01 * tr.load_work);
}

// The in-situ stressed box of test_rock_setups (σ0 with shear, overburden gradient, K0 = 0.5,
// gravity), held by absorbing boundaries on all four sides and nothing else: they carry the
// field's reaction from the first step, so it does not move (1e-18 m, round-off, where the
// tractions of the field itself hold it), in a dynamic and in a static (DDA) run.
TEST(Absorbing, AModelInInsituEquilibriumOnAbsorbingBoundariesStaysStill) {
  for (bool dynamic : {true, false}) {
    json doc = json::parse(R"({
      "gravity": [0, -9.81],
      "materials": { "rock": { "density": 2500, "young": 1e10, "poisson": 0.25 } },
      "bodies": [ { "material": "rock", "outer": [[0,0],[10,0],[10,8],[0,8]] } ],
      "mesh": { "size": 1 },
      "insitu_stress": { "sxx": -3e6, "syy": -5e6, "sxy": 1e6, "y_ref": 8, "gradient": [-12262.5, -24525, 0] },
      "absorbing": [ { "points": [[0,0],[10,0],[10,8],[0,8],[0,0]] } ],
      "solver": { "time_step": 1e-3 } })");
    doc["solver"]["dynamic"] = dynamic;
    const SceneDef s = scene_from_json(doc, "insitu");
    const Mesh m = pre::build_mesh(s, "insitu");
    TimeStepper st(m, s, "insitu");
    double worst = 0;
    for (int i = 0; i < 50; ++i) {
      const std::vector<double> before = st.view().state.loop_u;
      ASSERT_PRED1(test::ended_ok, st.attempt(1e-3));
      for (std::size_t k = 0; k < before.size(); ++k)
        worst = std::max(worst, std::abs(st.view().state.loop_u[k] - before[k]));
    }
    std::printf("in-situ box on absorbing boundaries, %s: largest motion in a step %.2e m\n",
                dynamic ? "dynamic" : "static", worst);
    EXPECT_LT(worst, 1e-12);
  }
}

TEST(Absorbing, RestartContinuesBitwise) {
  // The compliant column of the doubling test: 2 × 150 steps through a checkpoint in memory
  // against 300 straight (no contact: no factorisation to carry).
  json doc = column(1, 30, "y", 30);
  doc["absorbing"] = json::array({{{"points", {{0, 0}, {1, 0}}}, {"input_velocity", {{"x", hann(0.1, 0.05)}}}}});
  doc["solver"] = {{"time_step", 2e-4}};
  const SceneDef s = scene_from_json(doc, "restart");
  const Mesh m = pre::build_mesh(s, "restart");
  TimeStepper straight(m, s, "restart"), first(m, s, "restart"), second(m, s, "restart");
  ASSERT_PRED1(test::ended_ok, straight.run_until(0.06, [](std::int64_t) {}));
  ASSERT_PRED1(test::ended_ok, first.run_until(0.03, [](std::int64_t) {}));
  second.restore(first.view().state, save_contact_history(first.view().contacts), "memory");
  ASSERT_PRED1(test::ended_ok, second.run_until(0.06, [](std::int64_t) {}));
  EXPECT_GT(straight.view().state.absorbed_work, 0);
  EXPECT_EQ(state_hash(second.view()), state_hash(straight.view()));
}

}  // namespace
}  // namespace nmm::solve
