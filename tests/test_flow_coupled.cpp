// Two-way transient coupling of the flow and the rock (solver/flow/flow_effect.h, docs/flow.md
// "Coupling"): the apertures follow the faces within the step while the water is stored.
// A joint along y = H between two layers of thickness H (E, ν = 0, plane strain), held at their
// far faces, rollers at the sides the joint reaches: a pressure p uniform along the joint opens
// it by p/kn, kn = E/(2H) (each layer shortens by p·H/E), exactly. Closed forms:
//   - an injection Q into the joint's middle, its ends closed, low viscosity so that the pressure
//     is nearly uniform (spread Q·L/(8T), T = a³/(12μ), a few hundred Pa): all of it is stored,
//       L·(a0 + p/kn)·(1 + p/K_f) − L·a0 = Q·t,
//     a quadratic in the mean p — within 2 % (p, and the opening p/kn); the one-way scheme
//     (apertures fixed at the start) stores it by the water's compressibility alone,
//     p = K_f·Q·t/(a0·L), 2,200 times too high here;
//   - a step p0 at the joint's left end, its right end closed: the joint fills and opens until
//     it holds p0 everywhere, a = a0 + p0/kn — within 2 %, the volume that came in equal to
//     L·(a0 + p0/kn)·(1 + p0/K_f) − L·a0 within 1 %;
//   - in both: injected − outflow equals the change of the network's water Σ V·(1 + p/K_f),
//     measured here from the state's apertures and pressures, within 1 % (in practice 1e-6),
//     and summary's balance_error below 1e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "solver/flow/flow_effect.h"
#include "solver/stepping/time_stepper.h"
#include "tests/ended_ok.h"
#include "tests/flow_probe.h"

namespace nmm::solve {
namespace {

using nlohmann::json;
using test::flow_of;
using test::node_near;

constexpr double kYoung = 1e10, kH = 1, kLength = 10, kF = 2.2e9;
constexpr double kKn = kYoung / (2 * kH);  // Pa/m, 5e9

/// Two layers [0, L] × [0, 2H] with the joint along y = H, ν = 0, held at y = 0 and 2H, rollers
/// at x = 0 and L; static steps of dt.
json layers(double dt) {
  json doc = json::parse(R"({
    "materials": { "rock": { "density": 2500, "poisson": 0 } },
    "joint_sets": { "j": { "friction_deg": 30, "cohesion": 0, "tensile_strength": 0,
                           "normal": { "model": "constant", "kn": 1e12 },
                           "shear": { "model": "constant", "ks": 4e11 } } } })");
  doc["materials"]["rock"]["young"] = kYoung;
  doc["mesh"] = {{"size", 0.25}};
  doc["bodies"] = json::array({{{"material", "rock"}, {"outer", {{0, 0}, {kLength, 0}, {kLength, 2 * kH}, {0, 2 * kH}}}}});
  doc["joints"] = json::array({{{"set", "j"}, {"points", {{0, kH}, {kLength, kH}}}}});
  doc["supports"] = json::array({{{"points", {{0, 0}, {kLength, 0}}}, {"fix", "xy"}},
                                 {{"points", {{kLength, 0}, {kLength, 2 * kH}}}, {"fix", "x"}},
                                 {{"points", {{kLength, 2 * kH}, {0, 2 * kH}}}, {"fix", "xy"}},
                                 {{"points", {{0, 2 * kH}, {0, 0}}}, {"fix", "x"}}});
  doc["solver"] = {{"time_step", dt}, {"static_mode", "equilibrium"}};
  return doc;
}

/// m³ per m: the water the network's free nodes hold, Σ V·(1 + p/K_f).
double content(const FlowNetwork& net, const RunState& s) {
  const std::vector<double> v = net.volumes(s.flow_aperture);
  double sum = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (net.node_boundary()[i] < 0) sum += v[i] * (1 + s.flow_pressure[i] / kF);
  return sum;
}

/// The volume-weighted mean pressure of the network (Pa).
double mean_pressure(const FlowNetwork& net, const RunState& s) {
  const std::vector<double> v = net.volumes(s.flow_aperture);
  double pv = 0, vs = 0;
  for (std::size_t i = 0; i < v.size(); ++i) pv += v[i] * s.flow_pressure[i], vs += v[i];
  return pv / vs;
}

struct Contents {
  double content0 = 0, content1 = 0;
};

/// Runs to t_end, printing the coupling's iterations; the network's content at the start and end.
Contents run(TimeStepper& st, double t_end, const char* name) {
  Contents r;
  r.content0 = content(flow_of(st).network(), st.view().state);
  const Outcome o = st.run_until(t_end, [](std::int64_t) {});
  EXPECT_PRED1(test::ended_ok, o);
  r.content1 = content(flow_of(st).network(), st.view().state);
  const FlowEffect::Iterations& it = flow_of(st).iterations();
  std::printf("%s: %ld steps, %ld balance solves (%.2f a step, at most %ld), %lld cuts\n", name, it.steps, it.solves,
              static_cast<double>(it.solves) / static_cast<double>(it.steps), it.worst,
              static_cast<long long>(st.view().state.cuts));
  return r;
}

TEST(FlowCoupled, InjectionOpensTheJointItFills) {
  const double a0 = 2e-4, mu = 1e-4, q = 1e-6, t_end = 20;
  json doc = layers(1.0);
  doc["flow"] = {{"fluid", {{"viscosity", mu}, {"bulk_modulus", kF}}},
                 {"aperture", {{"residual", a0}, {"max", 1e-2}}},
                 {"injections", {{{"point", {kLength / 2, kH}}, {"rate", q}}}}};
  const SceneDef s = scene_from_json(doc, "coupled-injection");
  const Mesh m = pre::build_mesh(s, "coupled-injection");
  TimeStepper st(m, s, "coupled-injection");
  const Contents r = run(st, t_end, "injection into a joint between layers");
  const RunState& state = st.view().state;
  const FlowNetwork& net = flow_of(st).network();
  // L·(a0 + p/kn)·(1 + p/K_f) − L·a0 = Q·t:  (L/(kn·K_f))·p² + L·(1/kn + a0/K_f)·p − Q·t = 0.
  const double qa = kLength / (kKn * kF), qb = kLength * (1 / kKn + a0 / kF), qc = -q * state.time;
  const double p = (-qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
  const double one_way = kF * q * state.time / (a0 * kLength);
  const double got = mean_pressure(net, state);
  const std::size_t mid = node_near(net, kLength / 2, kH), end = node_near(net, 0, kH);
  const double opening = net.node_apertures(state.flow_aperture)[mid] - a0;
  const double spread = state.flow_pressure[mid] - state.flow_pressure[end];
  std::printf("  t %.3g s: mean p %.6g Pa (closed form %.6g: %+.3f %%; one-way K_f·Q·t/(a0·L) = %.4g, %.3g times "
              "too high), opening at the middle %.6g m (p/kn %.6g: %+.3f %%), spread %.4g Pa (Q·L/8T %.4g)\n",
              state.time, got, p, 100 * (got / p - 1), one_way, one_way / p, opening, p / kKn,
              100 * (opening * kKn / p - 1), spread, q * kLength * 12 * mu / (8 * std::pow(a0 + p / kKn, 3)));
  std::printf("  injected %.6g m3/m, outflow %g, content change %.6g (%+.2e), balance_error %.2e\n",
              state.flow_injected, state.flow_outflow, r.content1 - r.content0,
              (r.content1 - r.content0) / state.flow_injected - 1, flow_of(st).balance_error(state));
  EXPECT_NEAR(got, p, 0.02 * p);
  EXPECT_NEAR(opening, p / kKn, 0.02 * p / kKn);
  EXPECT_GT(one_way, 1000 * p) << "the case the one-way scheme gets wrong";
  EXPECT_NEAR(state.flow_injected, q * state.time, 1e-9 * q * state.time);
  EXPECT_EQ(state.flow_outflow, 0);
  EXPECT_NEAR(r.content1 - r.content0, state.flow_injected - state.flow_outflow, 0.01 * state.flow_injected);
  EXPECT_LT(flow_of(st).balance_error(state), 1e-4);
}

TEST(FlowCoupled, JointFilledFromOneEndOpensToTheSteadyAperture) {
  const double a0 = 2e-4, mu = 1e-4, p0 = 1e5, t_end = 10;
  json doc = layers(0.5);
  doc["flow"] = {{"fluid", {{"viscosity", mu}, {"bulk_modulus", kF}}},
                 {"aperture", {{"residual", a0}, {"max", 1e-2}}},
                 {"boundaries", {{{"points", {{0, 0}, {0, 2 * kH}}}, {"pressure", p0}}}}};
  const SceneDef s = scene_from_json(doc, "coupled-filling");
  const Mesh m = pre::build_mesh(s, "coupled-filling");
  TimeStepper st(m, s, "coupled-filling");
  const Contents r = run(st, t_end, "joint filled from one end");
  const RunState& state = st.view().state;
  const FlowNetwork& net = flow_of(st).network();
  const double a = a0 + p0 / kKn;
  const std::vector<double> ap = net.node_apertures(state.flow_aperture);
  double worst = 0;  // the largest relative error of the aperture over the joint's nodes
  for (std::size_t i = 0; i < net.nodes(); ++i) worst = std::max(worst, std::abs(ap[i] / a - 1));
  const double came_in = -state.flow_outflow, held = kLength * (a * (1 + p0 / kF) - a0);
  std::printf("  t %.3g s: apertures within %.3f %% of a0 + p0/kn = %.6g m; came in %.6g m3/m (L·(a·(1 + p0/K_f) "
              "− a0) = %.6g: %+.3f %%), content change %.6g (%+.2e), balance_error %.2e\n",
              state.time, 100 * worst, a, came_in, held, 100 * (came_in / held - 1), r.content1 - r.content0,
              (r.content1 - r.content0) / came_in - 1, flow_of(st).balance_error(state));
  EXPECT_LT(worst, 0.02);
  EXPECT_NEAR(came_in, held, 0.01 * held);
  EXPECT_NEAR(r.content1 - r.content0, came_in, 0.01 * came_in);
  EXPECT_LT(flow_of(st).balance_error(state), 1e-4);
}

}  // namespace
}  // namespace nmm::solve
