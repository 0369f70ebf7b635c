// Fluid flow along the joints (solver/flow/, docs/flow.md) against closed forms:
//   - steady flow in a network of three joints (two crossings, three boundaries, gravity heads):
//     Kirchhoff's node balance with the cubic law, a³/(12μL) per joint piece, solved by hand
//     here — the pressures at the crossings and the boundaries' rates within 1 %;
//   - a pressure front along one joint with rigid walls: p = p0·erfc(x / 2√(Dt)),
//     D = a²·K_f/(12μ), within 2 % of p0;
//   - a joint opened by its own pressure between two elastic layers held at their far faces
//     (ν = 0, plane strain: each layer of thickness H gives way by p·H/E, so the joint opens by
//     p/kn with kn = E/(2H)), the flow along it q = [(r + p/kn)⁴]_{p_out}^{p_in}·kn/(48μL)
//     (the cubic law with a = r + p/kn integrated along the joint) within 2 %;
//   - an injection into a joint with rigid walls: stored by the fluid's compressibility,
//     p = K_f·Q·t/(a·L), within 1 % (walls that give way: test_flow_coupled.cpp);
//   - a dry joint filled from one end with a fluid lag (cavitation_pressure): the front
//     x_f = a·√(p0·t/(6μ)) within 0.5 %, the pressure linear behind it, never below the floor;
//   - the volume balance stored = injected − outflow within 0.1 % in every run;
//   - a restart through the checkpoint's sections continues bit for bit;
//   - bad flow input is one InputError naming its JSON path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/math_constants.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "solver/flow/flow_effect.h"
#include "solver/stepping/restart.h"
#include "solver/stepping/time_stepper.h"
#include "tests/ended_ok.h"
#include "tests/flow_probe.h"
#include "tests/temp_dir.h"

namespace nmm::solve {
namespace {

using nlohmann::json;
using test::flow_of;
using test::node_near;

/// A rectangle [0, w] × [0, h] of rock (E, ν) cut by `joints`, its four sides held as `fix`
/// ("xy", or "x" on the sides with "xy" top and bottom when `rollers`), mesh size `mesh`.
json box(double w, double h, const json& joints, double young, double poisson, bool rollers, double mesh) {
  json doc = json::parse(R"({
    "materials": { "rock": { "density": 2500 } },
    "joint_sets": { "j": { "friction_deg": 30, "cohesion": 0, "tensile_strength": 0,
                           "normal": { "model": "constant", "kn": 1e12 },
                           "shear": { "model": "constant", "ks": 4e11 } } } })");
  doc["materials"]["rock"]["young"] = young;
  doc["materials"]["rock"]["poisson"] = poisson;
  doc["mesh"] = {{"size", mesh}};
  doc["bodies"] = json::array({{{"material", "rock"}, {"outer", {{0, 0}, {w, 0}, {w, h}, {0, h}}}}});
  doc["joints"] = json::array();
  for (const json& j : joints) doc["joints"].push_back({{"set", "j"}, {"points", j}});
  const char* side = rollers ? "x" : "xy";
  doc["supports"] = json::array({{{"points", {{0, 0}, {w, 0}}}, {"fix", "xy"}},
                                 {{"points", {{w, 0}, {w, h}}}, {"fix", side}},
                                 {{"points", {{w, h}, {0, h}}}, {"fix", "xy"}},
                                 {{"points", {{0, h}, {0, 0}}}, {"fix", side}}});
  return doc;
}

/// Steps of dt up to t_end; with FLOW_TRACE set, prints the node nearest (x, y) after each.
void run_traced(TimeStepper& st, double dt, double t_end, double x, double y) {
  while (st.view().state.time < t_end - 1e-9 * dt) {
    ASSERT_PRED1(test::ended_ok, st.attempt(dt));
    const RunState& q = st.view().state;
    const std::size_t i = node_near(flow_of(st).network(), x, y);
    if (std::getenv("FLOW_TRACE"))
      std::printf("t %.4g p %.6g ap %.6g stored %.6g inj %.6g out %.6g\n", q.time, q.flow_pressure[i],
                  flow_of(st).network().node_apertures(q.flow_aperture)[i], q.flow_stored, q.flow_injected,
                  q.flow_outflow);
  }
}

TEST(Flow, SteadyNetworkFollowsKirchhoffAndTheCubicLaw) {
  // Joints: J0 along y = 3 from the left side to the right, J1 and J2 across it at x = 5 and 7
  // from the bottom to the top. Boundaries: left 100 kPa, right 0, top 30 kPa; the bottom is
  // closed, so the lower halves of J1 and J2 are dead ends. Gravity: φ = p + ρ·g·y.
  const double mu = 1e-3, a = 1e-4, rho = 1000, g = 9.81;
  json doc = box(10, 6, {{{0, 3}, {10, 3}}, {{5, 0}, {5, 6}}, {{7, 0}, {7, 6}}}, 1e10, 0.25, false, 0.5);
  doc["gravity"] = {0, -g};
  doc["flow"] = {{"fluid", {{"viscosity", mu}, {"density", rho}}},
                 {"aperture", {{"residual", a}, {"coupled", false}}},
                 {"boundaries", {{{"points", {{0, 0}, {0, 6}}}, {"pressure", 1e5}},
                                 {{"points", {{10, 0}, {10, 6}}}, {"pressure", 0}},
                                 {{"points", {{0, 6}, {10, 6}}}, {"pressure", 3e4}}}},
                 {"steady", true}};
  doc["solver"] = {{"time_step", 1e-3}};
  const SceneDef s = scene_from_json(doc, "kirchhoff");
  const Mesh m = pre::build_mesh(s, "kirchhoff");
  TimeStepper st(m, s, "kirchhoff");
  for (int i = 0; i < 2; ++i) ASSERT_PRED1(test::ended_ok, st.attempt(1e-3));

  // By hand: G(L) = a³/(12μL); heads at the boundaries; A = (5, 3), B = (7, 3):
  //   G(5)(φA − φl) + G(2)(φA − φB) + G(3)(φA − φt) = 0
  //   G(2)(φB − φA) + G(3)(φB − φr) + G(3)(φB − φt) = 0
  auto G = [&](double l) { return a * a * a / (12 * mu * l); };
  const double rg = rho * g, phl = 1e5 + rg * 3, phr = 0 + rg * 3, pht = 3e4 + rg * 6;
  const double a11 = G(5) + G(2) + G(3), a12 = -G(2), b1 = G(5) * phl + G(3) * pht;
  const double a22 = G(2) + G(3) + G(3), b2 = G(3) * phr + G(3) * pht;
  const double det = a11 * a22 - a12 * a12;
  const double phA = (b1 * a22 - a12 * b2) / det, phB = (a11 * b2 - a12 * b1) / det;
  const double pA = phA - rg * 3, pB = phB - rg * 3;
  const double q_left = G(5) * (phA - phl), q_right = G(3) * (phB - phr), q_top = G(3) * (phA - pht) + G(3) * (phB - pht);

  const FlowNetwork& net = flow_of(st).network();
  const RunState& state = st.view().state;
  const double got_a = state.flow_pressure[node_near(net, 5, 3)], got_b = state.flow_pressure[node_near(net, 7, 3)];
  EXPECT_NEAR(got_a, pA, 0.01 * std::abs(pA)) << "pressure at (5, 3), Pa";
  EXPECT_NEAR(got_b, pB, 0.01 * std::abs(pB)) << "pressure at (7, 3), Pa";
  // A dead end has its junction's head: at (5, 0) p = pA + ρ·g·3.
  EXPECT_NEAR(state.flow_pressure[node_near(net, 5, 0)], pA + rg * 3, 0.01 * std::abs(pA + rg * 3));
  ASSERT_EQ(state.flow_outflow_rate.size(), 3u);
  EXPECT_NEAR(state.flow_outflow_rate[0], q_left, 0.01 * std::abs(q_left)) << "m³/s per m";
  EXPECT_NEAR(state.flow_outflow_rate[1], q_right, 0.01 * std::abs(q_right));
  EXPECT_NEAR(state.flow_outflow_rate[2], q_top, 0.01 * std::abs(q_top));
  std::printf("kirchhoff: pA %.6g (hand %.6g) Pa, pB %.6g (%.6g) Pa, rates %.6g %.6g %.6g (%.6g %.6g %.6g) m3/s\n",
              got_a, pA, got_b, pB, state.flow_outflow_rate[0], state.flow_outflow_rate[1],
              state.flow_outflow_rate[2], q_left, q_right, q_top);
  // Steady: what enters leaves.
  const double net_out = state.flow_outflow_rate[0] + state.flow_outflow_rate[1] + state.flow_outflow_rate[2];
  EXPECT_LT(std::abs(net_out), 1e-6 * std::abs(q_left));
  EXPECT_LT(flow_of(st).balance_error(state), 1e-3);
}

TEST(Flow, PressureFrontAlongOneJointFollowsErfc) {
  // A joint along y = 1 of a 40 m long bar, rigid walls (coupled: false), a step p0 at its left
  // end at t = 0, its right end closed: the front of p0·erfc(x/2√(Dt)) reaches about 2√(Dt)
  // = 5.4 m at t = 0.1 s, far from the closed end.
  const double mu = 1e-3, kf = 2.2e9, a = 2e-5, p0 = 1e6, t_end = 0.1;
  json doc = box(40, 2, {{{0, 1}, {40, 1}}}, 1e10, 0.25, false, 0.5);
  doc["flow"] = {{"fluid", {{"viscosity", mu}, {"bulk_modulus", kf}}},
                 {"aperture", {{"residual", a}, {"coupled", false}}},
                 {"boundaries", {{{"points", {{0, 0}, {0, 2}}}, {"pressure", p0}}}}};
  doc["solver"] = {{"time_step", 1e-3}};
  const SceneDef s = scene_from_json(doc, "front");
  const Mesh m = pre::build_mesh(s, "front");
  TimeStepper st(m, s, "front");
  ASSERT_PRED1(test::ended_ok, st.run_until(t_end, [](std::int64_t) {}));
  const RunState& state = st.view().state;
  const FlowNetwork& net = flow_of(st).network();
  const double d = a * a * kf / (12 * mu), t = state.time;
  double worst = 0, at = 0;
  for (std::size_t i = 0; i < net.nodes(); ++i) {
    const double x = net.node_xy()[2 * i];
    const double err = std::abs(state.flow_pressure[i] - p0 * std::erfc(x / (2 * std::sqrt(d * t)))) / p0;
    if (err > worst) worst = err, at = x;
  }
  std::printf("erfc front: D %.4g m2/s at t %.4g s over %zu nodes: largest error %.3g %% of p0 at x = %.3g m\n", d, t,
              net.nodes(), 100 * worst, at);
  EXPECT_LT(worst, 0.02);
  // The volume that came in is what the joint stores: ∫ a·p/K_f dx = a·p0·2√(Dt/π)/K_f.
  const double stored = a * p0 * 2 * std::sqrt(d * t / kPi) / kf;
  EXPECT_NEAR(state.flow_stored, stored, 0.02 * stored);
  EXPECT_NEAR(-state.flow_outflow, stored, 0.02 * stored);
  EXPECT_LT(flow_of(st).balance_error(state), 1e-3);
}

TEST(Flow, JointOpenedByItsOwnPressureCarriesTheCubicLawFlow) {
  // Two layers of H = 1 m (E = 10 GPa, ν = 0) held at their far faces, rollers at the sides: a
  // uniform p opens the joint by p/kn, kn = E/(2H) = 5e9 Pa/m (0.2 mm at 1 MPa). Steady flow
  // from 1.01 MPa at the left end to 0.99 MPa at the right; the pressure starts at 1 MPa.
  const double mu = 1e-3, r = 2e-5, young = 1e10, h = 1, len = 10, p_in = 1.01e6, p_out = 0.99e6;
  const double kn = young / (2 * h);
  json doc = box(len, 2 * h, {{{0, h}, {len, h}}}, young, 0.0, true, 0.25);
  doc["flow"] = {{"fluid", {{"viscosity", mu}}},
                 {"aperture", {{"residual", r}, {"max", 1e-2}}},
                 {"initial_pressure", 1e6},
                 {"boundaries", {{{"points", {{0, 0}, {0, 2 * h}}}, {"pressure", p_in}},
                                 {{"points", {{len, 0}, {len, 2 * h}}}, {"pressure", p_out}}}},
                 {"steady", true}};
  doc["solver"] = {{"time_step", 1}, {"static_mode", "equilibrium"}};
  const SceneDef s = scene_from_json(doc, "opened");
  const Mesh m = pre::build_mesh(s, "opened");
  TimeStepper st(m, s, "opened");
  for (int i = 0; i < 8; ++i) ASSERT_PRED1(test::ended_ok, st.attempt(1));
  const RunState& state = st.view().state;
  const FlowNetwork& net = flow_of(st).network();
  const std::size_t mid = node_near(net, len / 2, h);
  const double p_mid = state.flow_pressure[mid];
  const double opening = net.node_apertures(state.flow_aperture)[mid] - r;
  const double q = (std::pow(r + p_in / kn, 4) - std::pow(r + p_out / kn, 4)) * kn / (48 * mu * len);
  std::printf("opened joint: opening %.6g m at p %.6g Pa (p/kn %.6g m); outflow %.6g m3/s per m (closed form %.6g)\n",
              opening, p_mid, p_mid / kn, state.flow_outflow_rate[1], q);
  EXPECT_NEAR(opening, p_mid / kn, 0.02 * p_mid / kn);
  EXPECT_NEAR(state.flow_outflow_rate[1], q, 0.02 * q);
  EXPECT_NEAR(state.flow_outflow_rate[0], -q, 0.02 * q);
  EXPECT_LT(flow_of(st).balance_error(state), 1e-3);
  // The pressure did work on the faces as they opened: about ½·p·w·L... at least its sign.
  EXPECT_GT(state.flow_load_work, 0);
}

TEST(Flow, InjectionIntoAClosedJointIsStoredByTheFluid) {
  // An injection into the middle of a joint that reaches no boundary, rigid walls (coupled:
  // false; the walls that give way: test_flow_coupled.cpp): everything injected is stored by the
  // fluid's compressibility; the pressure spreads in a few ms (D = a²K_f/(12μ) = 458 m²/s over
  // 10 m), so it rises uniformly as p = K_f·Q·t/(a·L).
  const double a = 5e-5, kf = 2.2e9, q = 1e-6, len = 10;
  json doc = box(len, 2, {{{0, 1}, {len, 1}}}, 1e10, 0.0, true, 0.5);
  doc["flow"] = {{"aperture", {{"residual", a}, {"coupled", false}}}, {"injections", {{{"point", {5, 1}}, {"rate", q}}}}};
  doc["solver"] = {{"time_step", 0.01}, {"static_mode", "equilibrium"}};
  const SceneDef s = scene_from_json(doc, "injection");
  const Mesh m = pre::build_mesh(s, "injection");
  TimeStepper st(m, s, "injection");
  run_traced(st, 0.01, 0.2, 5, 1);
  const RunState& state = st.view().state;
  const double p = kf * q * state.time / (a * len);
  EXPECT_NEAR(state.flow_injected, q * state.time, 1e-9 * q * state.time);
  EXPECT_EQ(state.flow_outflow, 0);
  EXPECT_LT(flow_of(st).balance_error(state), 1e-3);
  // The mean pressure (volume-weighted: storage a·L/K_f per node) is the stored volume's; the
  // spread from the injection point to the joint's ends is the quasi-steady Q·L/(8T),
  // T = a³/(12μ), once the pressure has crossed the joint.
  const FlowNetwork& net = flow_of(st).network();
  const std::vector<double> v = net.volumes(state.flow_aperture);
  double pv = 0, vs = 0;
  for (std::size_t i = 0; i < v.size(); ++i) pv += v[i] * state.flow_pressure[i], vs += v[i];
  const double spread = state.flow_pressure[node_near(net, 5, 1)] - state.flow_pressure[node_near(net, 0, 1)];
  const double spread0 = q * len / (8 * a * a * a / (12 * 1e-3));
  std::printf("injection: mean pressure %.6g Pa after %.3g s (K_f·Q·t/(a·L) = %.6g Pa), spread %.6g Pa (Q·L/8T = %.6g)\n",
              pv / vs, state.time, p, spread, spread0);
  EXPECT_NEAR(pv / vs, p, 0.01 * p);
  EXPECT_NEAR(spread, spread0, 0.05 * spread0);
}

TEST(Flow, DryJointFilledFromOneEndFollowsItsFront) {
  // The fluid lag (flow_balance.h): a dry joint along y = 1 of a 10 m bar (rigid walls, coupled:
  // false; `initially_dry`: vapour at the cavitation pressure p_c = 0), a step p0 at its left end
  // at t = 0, its right end closed. The fluid fills it behind a front x_f; ahead of it the vapour
  // holds p_c, so the pressure behind the front is linear, p = p0·(1 − x/x_f), and the front
  // moves as the cubic law's flow fills the opening (the fluid's compressibility, p0/K_f = 1e-5,
  // left out):
  //   a·dx_f/dt = a³/(12μ)·p0/x_f   ⇒   x_f(t) = a·√(p0·t/(6μ)),
  // the volume come in a·x_f (Washburn's front without capillarity). Without the lag the closed
  // joint fills at once by compressibility (the erfc front above, D = a²K_f/(12μ)).
  const double mu = 1e-3, a = 1e-4, p0 = 2e4, pc = 0, dt = 5, t_end = 500;
  json doc = box(10, 2, {{{0, 1}, {10, 1}}}, 1e10, 0.25, false, 0.25);
  doc["flow"] = {{"fluid", {{"viscosity", mu}, {"cavitation_pressure", pc}}},
                 {"aperture", {{"residual", a}, {"coupled", false}}},
                 {"initially_dry", true},
                 {"boundaries", {{{"points", {{0, 0}, {0, 2}}}, {"pressure", p0}}}}};
  doc["solver"] = {{"time_step", dt}, {"static_mode", "equilibrium"}};
  const SceneDef s = scene_from_json(doc, "dry");
  const Mesh m = pre::build_mesh(s, "dry");
  TimeStepper st(m, s, "dry");
  const FlowNetwork& net = flow_of(st).network();
  double lowest = 1e300, worst_front = 0, worst_profile = 0;
  int judged = 0;
  while (st.view().state.time < t_end - 1e-9 * dt) {
    ASSERT_PRED1(test::ended_ok, st.attempt(dt));
    const RunState& q = st.view().state;
    ASSERT_EQ(q.flow_void.size(), net.nodes());
    for (double p : q.flow_pressure) lowest = std::min(lowest, p);
    // The front from the fluid in the joint, against the closed form's: what came in and what
    // the boundary's node holds (its half segment, full from the start, outside the balance).
    const std::vector<double> v = net.volumes(q.flow_aperture);
    double held = 0;
    for (std::size_t i = 0; i < net.nodes(); ++i)
      if (net.node_boundary()[i] >= 0) held += v[i];
    const double front = (held - q.flow_outflow) / a, closed = a * std::sqrt(p0 * q.time / (6 * mu));
    const int k = static_cast<int>(std::lround(q.time / dt));
    if (k % 20 != 0) continue;
    // Behind the front (more than a node spacing) filled and linear; ahead of it dry at p_c.
    double profile = 0;
    for (std::size_t i = 0; i < net.nodes(); ++i) {
      const double x = net.node_xy()[2 * i];
      if (net.node_boundary()[i] >= 0) continue;
      if (x < front - 0.3) {
        EXPECT_EQ(q.flow_void[i], 0) << "x " << x << " m behind the front " << front << " m";
        profile = std::max(profile, std::abs(q.flow_pressure[i] - p0 * (1 - x / front)) / p0);
      } else if (x > front + 0.3) {
        EXPECT_EQ(q.flow_pressure[i], pc) << "x " << x << " m ahead of the front " << front << " m";
        EXPECT_NEAR(q.flow_void[i], v[i], 1e-12 * v[i]) << "x " << x << " m: dry";
      }
    }
    std::printf("dry joint t %5.0f s: front %.4f m (closed form %.4f, %+.2f %%), pressure behind it within %.2f %% of "
                "p0 of the linear profile, balance_error %.1e\n",
                q.time, front, closed, 100 * (front / closed - 1), 100 * profile, flow_of(st).balance_error(q));
    if (front < 1.5) continue;  // judged from six node spacings on
    ++judged;
    worst_front = std::max(worst_front, std::abs(front / closed - 1));
    worst_profile = std::max(worst_profile, profile);
  }
  const RunState& state = st.view().state;
  EXPECT_GE(judged, 4);
  // The scheme is exact where a node has just filled (the rate T·p0/x_n over the node's room
  // a·Δx summed is the midpoint rule of ∫ x dx): within 1e-4 measured (2026-11-30).
  EXPECT_LT(worst_front, 0.005);
  EXPECT_LT(worst_profile, 0.01);
  EXPECT_GE(lowest, pc);  // never below the floor
  EXPECT_LT(flow_of(st).balance_error(state), 1e-3);
  // What came in is the fluid the joint holds: Σ V·(1 + p/K_f) − s.
  const std::vector<double> v = net.volumes(state.flow_aperture);
  double fluid = 0;
  for (std::size_t i = 0; i < net.nodes(); ++i)
    if (net.node_boundary()[i] < 0) fluid += v[i] * (1 + state.flow_pressure[i] / s.flow.bulk_modulus) - state.flow_void[i];
  EXPECT_NEAR(fluid, -state.flow_outflow, 1e-9 * fluid);
}

TEST(Flow, RestartThroughTheCheckpointContinuesBitwise) {
  // Two-way coupled (flow_effect.h): the joint opens as it fills from its left end.
  json doc = box(10, 2, {{{0, 1}, {10, 1}}}, 1e10, 0.0, true, 0.5);
  doc["flow"] = {{"fluid", {{"viscosity", 1e-4}}},
                 {"aperture", {{"residual", 2e-4}}},
                 {"boundaries", {{{"points", {{0, 0}, {0, 2}}}, {"pressure", {{0, 0}, {0.05, 1e6}}}}}}};
  doc["solver"] = {{"time_step", 0.01}, {"static_mode", "equilibrium"}};
  const SceneDef s = scene_from_json(doc, "restart");
  const Mesh m = pre::build_mesh(s, "restart");
  TimeStepper straight(m, s, "restart"), first(m, s, "restart"), second(m, s, "restart");
  ASSERT_PRED1(test::ended_ok, straight.run_until(0.1, [](std::int64_t) {}));
  ASSERT_PRED1(test::ended_ok, first.run_until(0.05, [](std::int64_t) {}));
  // Through a checkpoint file (the state, the contact history and the contact solve's
  // factorisation: restart.h), as nmm-solve --restart reads it.
  const test::TempDir dir;
  write_checkpoint(first.view(), dir.path("flow.nmmstate"));
  second.restart_from(dir.path("flow.nmmstate"));
  EXPECT_EQ(second.view().state.flow_pressure, first.view().state.flow_pressure);
  EXPECT_EQ(state_hash(second.view()), state_hash(first.view()));
  ASSERT_PRED1(test::ended_ok, second.run_until(0.1, [](std::int64_t) {}));
  EXPECT_GT(straight.view().state.flow_injected - straight.view().state.flow_outflow, 0);
  EXPECT_EQ(second.view().state.flow_pressure, straight.view().state.flow_pressure);
  EXPECT_EQ(state_hash(second.view()), state_hash(straight.view()));
}

TEST(Flow, BadInputNamesItsPath) {
  auto message = [](const json& doc) {
    try {
      const SceneDef s = scene_from_json(doc, "bad");
      const Mesh m = pre::build_mesh(s, "bad");
      TimeStepper st(m, s, "bad");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  json doc = box(10, 2, {{{0, 1}, {10, 1}}}, 1e10, 0.0, true, 0.5);
  doc["flow"] = {{"fluid", {{"viscosity", -1}}}};
  EXPECT_NE(message(doc).find("/flow/fluid/viscosity"), std::string::npos) << message(doc);
  doc["flow"] = {{"aperture", {{"residual", 1e-3}, {"max", 1e-4}}}};
  EXPECT_NE(message(doc).find("/flow/aperture/max"), std::string::npos) << message(doc);
  doc["flow"] = {{"boundaries", {{{"points", {{3, 3}, {4, 3}}}, {"pressure", 1}}}}};
  EXPECT_NE(message(doc).find("/flow/boundaries/0/points"), std::string::npos) << message(doc);
  doc["flow"] = {{"injections", {{{"point", {5, 1.4}}, {"rate", 1}}}}};
  EXPECT_EQ(message(doc), "no error");  // within the mesh size of the joint
  doc["flow"] = {{"injections", {{{"point", {5, 30}}, {"rate", 1}}}}};
  EXPECT_NE(message(doc).find("/flow/injections/0/point"), std::string::npos) << message(doc);
  doc["flow"] = {{"steady", true}, {"injections", {{{"point", {5, 1}}, {"rate", 1}}}}};
  EXPECT_NE(message(doc).find("/flow/injections/0"), std::string::npos) << message(doc);
  doc["flow"] = {{"fluid", {{"cavitation_pressure", 1e5}}}};
  EXPECT_NE(message(doc).find("/flow/fluid/cavitation_pressure"), std::string::npos) << message(doc);
  doc["flow"] = {{"initially_dry", true}};
  EXPECT_NE(message(doc).find("/flow/initially_dry"), std::string::npos) << message(doc);
  doc["flow"] = {{"pressure", 1}};
  EXPECT_NE(message(doc).find("/flow"), std::string::npos) << message(doc);
}

}  // namespace
}  // namespace nmm::solve
