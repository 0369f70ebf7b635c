// Hydraulic fracturing (docs/flow.md "Hydraulic fracturing"): cracks in the flow network, a crack
// loaded by its fluid, and a pressurised crack that grows — against closed forms:
//   - a Griffith crack 2a in a plate of width 2W (α = a/W = 0.5), its faces loaded by the fluid
//     in it at pressure p (the flow network's initial pressure, no injection, no leak-off: the
//     crack is the network, closed at its tips): by superposition with Tada's remote tension,
//     K_I = p·√(πa)·F(α), F = (1 − 0.025α² + 0.06α⁴)·√sec(πα/2), K_II = 0 — within 2 % at
//     h = a/10 and converging as h falls; without the fluid's face term in the interaction
//     integral the same field gives a K_I ten times further off;
//   - breakdown: the same crack confined by σ3 across it, fluid injected at its middle, filling
//     it to about 90 % of the breakdown's net pressure in the first step and then at a constant
//     rate so its pressure rises about 0.5 % of K_Ic/(F√(πa)) a step, the rock's toughness
//     K_Ic (tip_growth.h): K_I = (p − σ3)·√(πa)·F, so the tips first grow at
//     p_c = σ3 + K_Ic/(F·√(πa)) — the net pressure p_c − σ3 within 3 %. The crack's opening
//     draws on the injected fluid (two-way coupling, flow_effect.h), so it then grows stably,
//     the flow network with it, and stays inside the plate (the sides' `boundaries` at 0 see no
//     fluid);
//   - the volume balance: stored = injected − outflow within 1e-3 of the volume exchanged, and
//     the fluid the run put into the new cracks at the pressure carried to them (filled_m3,
//     flow_transfer.h) is exactly the change of the network's content beyond what was stored;
//   - a restart through a checkpoint written after the crack grew continues bit for bit;
//   - the carry-over onto a re-cut network (flow_transfer.h): a crack that crosses a joint
//     divides its segment and takes the pressure linear along it there, the crack's other nodes
//     that pressure, its segments the residual aperture, the joint's pieces its apertures.
// Plane strain, E 10 GPa, ν 0.25; the crack's faces a joint of stiff springs that open freely;
// static equilibrium steps; each plate held statically determinately (a fixed point at its
// bottom middle, a roller on a short stretch of its bottom at a corner), so the pressure and the
// tractions are the only loads.
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
#include "solver/flow/flow_effect.h"
#include "solver/flow/flow_transfer.h"
#include "solver/fracture/crack_tips.h"
#include "solver/fracture/interaction_integral.h"
#include "solver/stepping/fracture_effect.h"
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

constexpr double kE = 1e10, kNu = 0.25;

// Tada (The Stress Analysis of Cracks Handbook, 3rd ed., 2.1): centre crack, α = a/W; 0.1 %.
double tada_centre(double alpha) {
  return (1 - 0.025 * alpha * alpha + 0.06 * std::pow(alpha, 4)) / std::sqrt(std::cos(kPi * alpha / 2));
}

// A plate [−W, W] × [−H, H] with the crack (−a, 0)–(a, 0), held statically determinately.
json plate(double W, double H, double a, double h) {
  json d;
  d["plane"] = "strain";
  d["materials"]["rock"] = {{"density", 2500}, {"young", kE}, {"poisson", kNu}};
  d["joint_sets"]["crack"] = {{"friction_deg", 30},
                              {"normal", {{"model", "constant"}, {"kn", 1e12}}},
                              {"shear", {{"model", "constant"}, {"ks", 4e11}}}};
  d["bodies"] = {{{"material", "rock"}, {"outer", {{-W, -H}, {W, -H}, {W, H}, {-W, H}}}}};
  d["joints"] = {{{"set", "crack"}, {"points", {{-a, 0}, {a, 0}}}}};
  d["mesh"]["size"] = h;
  d["fixed_points"] = {{0, -H + 0.01 * h}};
  d["supports"] = {{{"points", {{W - 0.5 * h, -H}, {W, -H}}}, {"fix", "y"}}};
  d["solver"] = {{"time_step", 1}, {"dynamic", false}, {"static_mode", "equilibrium"}};
  return d;
}

// m³ per m: the fluid the network's free nodes hold, Σ V·(1 + p/K_f) (flow_transfer.h).
double content(const FlowNetwork& net, const RunState& s, double kf) {
  const std::vector<double> v = net.volumes(s.flow_aperture);
  double sum = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (net.node_boundary()[i] < 0) sum += v[i] * (1 + s.flow_pressure[i] / kf);
  return sum;
}

}  // namespace

// K_I of a crack loaded by its own fluid at p = 1 MPa: p·√(πa)·F within 2 % at h = a/10, closer
// at a/20 (measured −3.04, −1.49, −0.77 % at a/5, a/10, a/20); K_II/K_I below 1e-6 (the crack on
// the lattice's row of nodes is symmetric). Without the fluid's face term the same field gives a
// K_I more than ten times further off (−66, −46, −32 %): the face term carries K_I where the
// domain is a few elements wide, and the domain part alone reaches it only as h → 0.
TEST(HydraulicFracture, PressurisedGriffithCrackMatchesTada) {
  const double W = 1, H = 2, a = 0.5, p = 1e6;
  const double k0 = p * std::sqrt(kPi * a) * tada_centre(a / W);
  std::vector<double> err;
  for (const double h : {0.1, 0.05, 0.025}) {
    json d = plate(W, H, a, h);
    // Steady: a network that reaches no boundary keeps its pressure (flow_balance.h), so the
    // crack is loaded by p however far it opens (transient, the fluid would expand into it).
    d["flow"] = {{"initial_pressure", p}, {"steady", true}};
    d["solver"]["steps"] = 1;
    const SceneDef s = scene_from_json(d, "griffith");
    const Mesh m = pre::build_mesh(s, "griffith");
    TimeStepper st(m, s, "griffith");
    ASSERT_PRED1(test::ended_ok, st.run_until(1.0, [](std::int64_t) {}));
    // The fluid kept its pressure (a closed network, no source): the crack is loaded by p.
    for (const double q : st.view().state.flow_pressure) ASSERT_NEAR(q, p, 1e-9 * p);
    CrackTipFinder finder;
    const std::vector<TipReading> t = read_crack_tips(st.view(), finder);
    ASSERT_EQ(t.size(), 2u);
    // The same field without the fluid's traction on the faces.
    CrackTipFinder bare_finder;
    const std::vector<CrackTip> tips = bare_finder.find(m, s, {});
    const TipElasticity el = tip_elasticity(s.materials[0], s.plane);
    const StressIntensity bare = interaction_integral(m, {tips[0].at, tips[0].direction, tips[0].radius, 0}, el,
                                                      st.view().state.stress, st.view().state.loop_u, {});
    for (const TipReading& r : t) {
      std::printf("  pressurised crack, h %.4f m (a/h %.0f), tip %d: K_I %.5g Pa·√m (%+.2f %% of p√(πa)F = %.5g), "
                  "K_II/K_I %+.2e; without the face term K_I %.4g\n",
                  h, a / h, r.tip, r.k1, 100 * (r.k1 / k0 - 1), k0, r.k2 / r.k1, bare.k1);
      EXPECT_NEAR(r.k1, t[0].k1, 1e-6 * k0);  // the two tips alike
      EXPECT_LT(std::abs(r.k2), 1e-6 * r.k1);
    }
    EXPECT_GT(std::abs(bare.k1 - k0), 10 * std::abs(t[0].k1 - k0)) << "the fluid's face term matters";
    err.push_back(t[0].k1 / k0 - 1);
  }
  EXPECT_LT(std::abs(err[1]), 0.02);
  EXPECT_LT(std::abs(err[2]), std::abs(err[1]));
}

// Breakdown of a confined pressurised crack by the rock's toughness, the crack then growing
// through the plate with the flow network; the balance; a restart after the crack grew.
TEST(HydraulicFracture, BreakdownPressureMatchesTheToughnessAndTheNetworkGrows) {
  const double W = 1, H = 2, a = 0.5, h = 0.05, k_ic = 1e6, s3 = 1e6, kf = 2.2e9, residual = 1e-4;
  const double net_c = k_ic / (std::sqrt(kPi * a) * tada_centre(a / W));  // Pa, p_c − σ3
  const double p_c = s3 + net_c;
  // The crack opens as it fills (two-way coupling: flow_effect.h), by about C = 2π·a²·G/E′ per
  // Pa of net pressure (Griffith's volume, G ≈ 1.09 measured for this plate (α = 0.5) and its supports; the
  // test measures the increments): the first step fills it to 90 % of the net pressure at
  // breakdown, then the rate raises it about 0.5 % of it a step (dt = 1 s).
  const double e1 = kE / (1 - kNu * kNu), compliance = 2 * kPi * a * a * 1.09 / e1;
  const double p0 = s3, dp = 0.005 * net_c, q = dp * (compliance + residual * 2 * a / kf);
  const double q_fill = 0.9 * net_c * compliance;
  json d = plate(W, H, a, h);
  d["materials"]["rock"]["strength"] = {{"tensile", 1e9}, {"cohesion", 1e9}, {"friction_deg", 30}, {"toughness", k_ic}};
  d["fracture"] = {{"crack_set", "crack"}};
  d["tractions"] = {{{"points", {{-W, H}, {W, H}}}, {"normal", -s3}, {"shear", 0}},
                    {{"points", {{-W, -H}, {W, -H}}}, {"normal", -s3}, {"shear", 0}}};
  d["flow"] = {{"aperture", {{"residual", residual}}},
               {"initial_pressure", p0},
               {"injections", {{{"point", {0, 0}}, {"rate", {{0, q_fill}, {1, q_fill}, {1 + 1e-9, q}, {1e3, q}}}}}},
               {"boundaries", {{{"points", {{W, -H}, {W, H}}}, {"pressure", 0}},
                               {{"points", {{-W, H}, {-W, -H}}}, {"pressure", 0}}}}};
  const SceneDef s = scene_from_json(d, "breakdown");
  Mesh m = pre::build_mesh(s, "breakdown");
  m.scene_text = d.dump();  // as nmm-preprocess records it: a cracked checkpoint's MESH section checks it
  m.scene_sha256 = sha256(m.scene_text);
  TimeStepper st(m, s, "breakdown");
  const double content0 = content(flow_of(st).network(), st.view().state, kf);
  const std::size_t nodes0 = flow_of(st).network().nodes();
  std::vector<double> pressure;  // Pa, at the crack's middle after each intact step
  std::int64_t grew = -1;
  const double t_end = 30;
  ASSERT_PRED1(test::ended_ok, st.run_until(t_end, [&](std::int64_t n) {
    if (grew < 0 && !fracture_of(st.view()).segments().empty()) grew = n;
    if (grew < 0) pressure.push_back(st.view().state.flow_pressure[node_near(flow_of(st).network(), 0, 0)]);
  }));
  ASSERT_GT(grew, 1) << "the crack held at the first steps";
  // The step that grew had its pressure one increment above the last intact step's.
  ASSERT_GT(pressure.size(), 2u);
  const double at = 2 * pressure.back() - pressure[pressure.size() - 2];
  std::printf("  the net pressure rose %.3f %% of p_c − σ3 a step before the breakdown\n",
              100 * (pressure.back() - pressure[pressure.size() - 2]) / net_c);
  const RunState& state = st.view().state;
  const FlowNetwork& net = flow_of(st).network();
  const std::vector<CrackSegment>& seg = fracture_of(st.view()).segments();
  double reach = 0, grown = 0;
  for (const CrackSegment& c : seg) {
    reach = std::max(reach, std::max(std::abs(c.a.x), std::abs(c.b.x)));
    grown += std::hypot(c.b.x - c.a.x, c.b.y - c.a.y);
  }
  std::printf("  breakdown at step %lld: p %.6g Pa (p_c = σ3 + K_Ic/(F√(πa)) = %.6g: %+.2f %%; net p − σ3 %+.2f %% of %.5g); "
              "%zu segments, %.4f m grown to |x| %.4f m; network %zu → %zu nodes; injected %.4g, outflow %.4g, "
              "stored %.4g, filled %.4g m³/m, balance_error %.2e\n",
              static_cast<long long>(grew), at, p_c, 100 * (at / p_c - 1), 100 * ((at - s3) / net_c - 1), net_c,
              seg.size(), grown, reach, nodes0, net.nodes(), state.flow_injected, state.flow_outflow,
              state.flow_stored, state.flow_filled, flow_of(st).balance_error(state));
  EXPECT_NEAR(at - s3, net_c, 0.03 * net_c);
  EXPECT_LT(pressure.back() - s3, 1.03 * net_c);
  // Fed at a rate, the crack's opening draws on the fluid it was given (two-way coupling), so
  // it grows stably — a tip step or a few, the pressure falling as it lengthens — rather than
  // through the plate as under a pressure that the fluid's compressibility alone sets; straight
  // along the crack's line, the network with it.
  EXPECT_GT(reach, a + 0.5 * h);
  EXPECT_LT(reach, W);
  double off = 0;  // m, the farthest the path strays from the crack's line
  for (const CrackSegment& c : seg) off = std::max(off, std::abs(c.b.y));
  std::printf("  the path strays at most %.3g m (%.3f h) from y = 0\n", off, off / h);
  EXPECT_LT(off, 0.1 * h);
  EXPECT_GT(net.nodes(), nodes0);
  // The crack did not reach the sides' boundaries: all the fluid is in it.
  EXPECT_EQ(state.flow_outflow, 0);
  EXPECT_LT(flow_of(st).balance_error(state), 1e-3);
  // The new cracks were filled at the residual aperture: about residual × the length grown (the
  // nodes on the sides hold none: boundary nodes), and exactly the content's change beyond what
  // was stored.
  EXPECT_GT(state.flow_filled, 0.9 * residual * grown);
  EXPECT_LT(state.flow_filled, 1.01 * residual * grown);
  const double content1 = content(net, state, kf);
  EXPECT_NEAR(content1 - content0, state.flow_stored + state.flow_filled, 1e-9 * content1);

  // A restart from a checkpoint written two steps after the breakdown.
  const double t_mid = static_cast<double>(grew + 2);
  TimeStepper first(m, s, "breakdown"), second(m, s, "breakdown");
  ASSERT_PRED1(test::ended_ok, first.run_until(t_mid, [](std::int64_t) {}));
  ASSERT_FALSE(fracture_of(first.view()).segments().empty());
  const test::TempDir dir;
  write_checkpoint(first.view(), dir.path("hf.nmmstate"));
  second.restart_from(dir.path("hf.nmmstate"));
  EXPECT_EQ(state_hash(second.view()), state_hash(first.view()));
  ASSERT_PRED1(test::ended_ok, second.run_until(t_end, [](std::int64_t) {}));
  EXPECT_EQ(second.view().state.flow_pressure, state.flow_pressure);
  EXPECT_EQ(second.view().state.flow_filled, state.flow_filled);
  EXPECT_EQ(state_hash(second.view()), state_hash(st.view()));
}

// The carry-over by position: a joint along y = 1 with a pressure linear in x (1 MPa at x = 0,
// 0 at x = 10) and apertures linear in x; then a crack x = 3.3 from y = 0.4 to 1.6 crosses it
// (the mesh cut again with it as a joint). The crossing node takes p(3.3) = 0.67 MPa, the
// crack's nodes the same, its segments the residual aperture, the joint's pieces the aperture
// linear along their old segment; the fill is the crack's volume at that pressure.
TEST(HydraulicFracture, TheNetworkCarriesPressuresOntoACrackByPosition) {
  auto doc = [](bool crack) {
    json d = plate(5, 2, 1, 0.5);
    d["bodies"][0]["outer"] = {{0, 0}, {10, 0}, {10, 2}, {0, 2}};
    d["joints"] = {{{"set", "crack"}, {"points", {{0, 1}, {10, 1}}}}};
    if (crack) d["joints"].push_back({{"set", "crack"}, {"points", {{3.3, 0.4}, {3.3, 1.6}}}});
    d["flow"] = {{"aperture", {{"residual", 1e-4}}}};
    return d;
  };
  const SceneDef s0 = scene_from_json(doc(false), "before"), s1 = scene_from_json(doc(true), "after");
  const Mesh m0 = pre::build_mesh(s0, "before"), m1 = pre::build_mesh(s1, "after");
  const FlowNetwork before(m0, s0, "before"), now(m1, s1, "after");
  RunState st;
  for (std::size_t i = 0; i < before.nodes(); ++i) st.flow_pressure.push_back(1e6 * (1 - before.node_xy()[2 * i] / 10));
  for (const FlowSegment& sg : before.segments())
    for (const std::int32_t n : {sg.a, sg.b}) st.flow_aperture.push_back(1e-4 + 1e-5 * before.node_xy()[2 * static_cast<std::size_t>(n)]);
  const double kf = 2.2e9;
  transfer_flow(before, now, s1.flow, 1e-6 * m1.mesh_size, st);
  ASSERT_EQ(st.flow_pressure.size(), now.nodes());
  ASSERT_EQ(st.flow_aperture.size(), 2 * now.segments().size());
  double crack_length = 0;
  for (std::size_t k = 0; k < now.segments().size(); ++k) {
    const FlowSegment& sg = now.segments()[k];
    const double xa = now.node_xy()[2 * static_cast<std::size_t>(sg.a)], xb = now.node_xy()[2 * static_cast<std::size_t>(sg.b)];
    if (sg.joint == 1) {
      crack_length += sg.length;
      EXPECT_EQ(st.flow_aperture[2 * k], 1e-4);
      EXPECT_EQ(st.flow_aperture[2 * k + 1], 1e-4);
    } else {
      EXPECT_NEAR(st.flow_aperture[2 * k], 1e-4 + 1e-5 * xa, 1e-15);
      EXPECT_NEAR(st.flow_aperture[2 * k + 1], 1e-4 + 1e-5 * xb, 1e-15);
    }
  }
  for (std::size_t i = 0; i < now.nodes(); ++i) {
    const double x = now.node_xy()[2 * i];
    EXPECT_NEAR(st.flow_pressure[i], 1e6 * (1 - x / 10), 1e-6) << "node at " << x << ", " << now.node_xy()[2 * i + 1];
  }
  EXPECT_NEAR(crack_length, 1.2, 1e-9);
  const double p = 1e6 * (1 - 0.33);
  std::printf("  crossing at x = 3.3: p %.6g Pa; crack 1.2 m filled %.6g m³/m (residual·L·(1 + p/K_f) = %.6g)\n",
              st.flow_pressure[node_near(now, 3.3, 1)], st.flow_filled, 1e-4 * 1.2 * (1 + p / kf));
  EXPECT_NEAR(st.flow_filled, 1e-4 * 1.2 * (1 + p / kf), 1e-12);
}

}  // namespace nmm::solve
