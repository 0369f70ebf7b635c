// The time scheme's damping, metered (solver/output/energy.cpp: the `damped` column of a dynamic
// run, Q = Σ_steps ½ dᵀM (a1,prev + a1) − ΔK; docs/energy.md) against a closed form:
//
//        fixed point (penalty spring k_f = 1e9 N/m)
//             v
//     +-------------+
//     |             |   a stiff block 1 m × 1 m (ρ = 1000 kg/m³, E = 1e13 Pa): m = 1000 kg,
//     |      o----> F   F = 1e6 N/m from t = 0 at its centre, where the spring holds it
//     |             |
//     +-------------+   a spring–mass, ω = √(k_f/m) = 1000 rad/s, Δt = 5e-5 s: ωΔt = 0.05
//
// Released from rest, it swings about x_eq = F/k_f with the energy E0 = ½ F²/k_f, and the
// balance K + S + Q = W (S the spring's ½ k_f x²) holds at every step to round-off — the meter
// before Q left all of Q in the residual (27 % of E0 after two cycles). What Q takes over whole
// cycles is what the Newmark scheme with γ = 1 damps: a damping ratio ξ = (γ − ½)ωΔt/2, so
// Q/E0 = 1 − exp(−2ξω t) (to O(ωΔt)), and exactly what the scheme's 1-DOF recursion loses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "solver/output/energy.h"
#include "solver/stepping/time_stepper.h"
#include "tests/ended_ok.h"

namespace nmm::solve {
namespace {

using nlohmann::json;

constexpr double kMass = 1000, kSpring = 1e9, kForce = 1e6, kDt = 5e-5;  // kg/m, N/m, N/m, s

json spring_mass(double beta, double dynamic_factor) {
  json doc = json::parse(R"({
    "materials": { "rock": { "density": 1000, "young": 1e13, "poisson": 0.0 } },
    "bodies": [ { "material": "rock", "outer": [[0, 0], [1, 0], [1, 1], [0, 1]] } ],
    "mesh": { "size": 0.5 },
    "fixed_points": [[0.5, 0.5]],
    "loads": [ { "point": [0.5, 0.5], "force": [1e6, 0] } ],
    "measure_points": [[0.5, 0.5]] })");
  doc["solver"] = {{"time_step", kDt}, {"steps", 400}, {"dynamic", true}, {"fixed_point_stiffness", kSpring},
                   {"newmark_beta", beta}, {"dynamic_factor", dynamic_factor}};
  return doc;
}

/// What the scheme's 1-DOF recursion (newmark.h, β = ½ in its first step) has lost after n
/// steps: W − K − S of the spring–mass (J/m).
double recursion_loss(double beta, double dynamic_factor, int n) {
  double u = 0, v = 0, a = 0, w = 0;
  for (int i = 0; i < n; ++i) {
    const double b = i == 0 ? 0.5 : beta;
    const double d = (kForce - kSpring * u + kMass * (v / (b * kDt) + (1 / (2 * b) - 1) * a)) /
                     (kSpring + kMass / (b * kDt * kDt));
    const double a1 = (d - kDt * v - (0.5 - b) * kDt * kDt * a) / (b * kDt * kDt);
    v = dynamic_factor * (v + kDt * a1);
    a = dynamic_factor * a1;
    u += d;
    w += kForce * d;
  }
  return w - 0.5 * kMass * v * v - 0.5 * kSpring * u * u;
}

struct SwingRow {
  std::int64_t step;
  EnergyRow row;
};

std::vector<SwingRow> swing(double beta, double dynamic_factor, int steps) {
  const SceneDef s = scene_from_json(spring_mass(beta, dynamic_factor), "spring-mass");
  const Mesh m = pre::build_mesh(s, "spring-mass");
  TimeStepper st(m, s, "spring-mass");
  EnergyMeter meter(st.view().model);
  meter.after_step(st.view().state, energy_sources(st.view()), true);
  std::vector<SwingRow> rows;
  for (int i = 0; i < steps; ++i) {
    const Outcome o = st.attempt(kDt);
    EXPECT_PRED1(test::ended_ok, o);
    if (!o.ok()) break;
    meter.after_step(st.view().state, energy_sources(st.view()), true);
    rows.push_back({st.view().state.step, meter.rows().back()});
  }
  return rows;
}

// K + S + Q = W at every step, from the first (the start is out of balance by F alone), for
// Shi's β = ½, the default β = 0.6, and a dynamic_factor of 0.8 (Q then holds the motion each
// step throws away too); Q after n steps is what the scheme's recursion lost.
TEST(SchemeDamping, SpringMassBalancesEveryStep) {
  const double e0 = 0.5 * kForce * kForce / kSpring;  // J/m, 500
  for (const auto& [beta, k] : {std::pair{0.5, 1.0}, std::pair{0.6, 1.0}, std::pair{0.5, 0.8}}) {
    const std::vector<SwingRow> rows = swing(beta, k, 260);
    ASSERT_EQ(rows.size(), 260u);
    double worst = 0;  // –, |R| over the work so far
    for (const SwingRow& r : rows) worst = std::max(worst, std::abs(r.row.residual) / std::max(1.0, r.row.load_work));
    const EnergyRow& end = rows.back().row;
    const double lost = recursion_loss(beta, k, 260);
    std::printf("beta %.1f, dynamic_factor %.1f: W %.6g J/m, K %.6g, S %.6g, Q %.9g (recursion %.9g), "
                "|R| at worst %.3g of W; R + Q (the residual without Q) %.4g (%.1f %% of E0)\n",
                beta, k, end.load_work, end.kinetic, end.springs, end.damped, lost, worst, end.residual + end.damped,
                100 * (end.residual + end.damped) / e0);
    // Measured 1e-14 … 1e-13 of W.
    EXPECT_LT(worst, 1e-10) << "beta " << beta << ", dynamic_factor " << k;
    // The block is rigid to 1e-5 of the spring: Q follows the 1-DOF recursion within that.
    EXPECT_NEAR(end.damped, lost, 1e-4 * lost) << "beta " << beta << ", dynamic_factor " << k;
    // The old meter's residual: a quarter of the swing's energy or more.
    EXPECT_GT(end.damped, 0.25 * e0);
  }
}

// Over whole cycles Q takes what a damping ratio ξ = (γ − ½)ωΔt/2 = ωΔt/4 takes out of the swing:
// E0·(1 − exp(−2ξωt)), at 1, 2 and 3 periods (steps 126, 251, 377 of T/Δt = 125.66), for
// β = ½ and 0.6 (β changes the damping only at O((ωΔt)³)). Measured within 0.3 %.
TEST(SchemeDamping, SpringMassLosesWhatGammaOneDampsPerCycle) {
  const double e0 = 0.5 * kForce * kForce / kSpring, omega = std::sqrt(kSpring / kMass);
  const double xi = (1.0 - 0.5) * omega * kDt / 2;
  for (const double beta : {0.5, 0.6}) {
    const std::vector<SwingRow> rows = swing(beta, 1.0, 377);
    ASSERT_EQ(rows.size(), 377u);
    for (const int n : {126, 251, 377}) {
      const EnergyRow& r = rows[static_cast<std::size_t>(n - 1)].row;
      const double theory = e0 * (1 - std::exp(-2 * xi * omega * r.time));
      std::printf("beta %.1f, %.3f periods: Q %.6g J/m = %.4f E0, (γ − ½)ωΔt/2 theory %.4f E0 (%+.2f %%)\n", beta,
                  r.time * omega / (2 * 3.141592653589793), r.damped, r.damped / e0, theory / e0,
                  100 * (r.damped / theory - 1));
      EXPECT_NEAR(r.damped, theory, 0.005 * theory) << "beta " << beta << ", step " << n;
    }
  }
}

}  // namespace
}  // namespace nmm::solve
