// The resting-block reference run, shared by the contact tests at every cover order
// (tests/test_contact.cpp, tests/test_contact_orders.cpp): a 2 m × 1 m block placed on a 6 m ×
// 1 m base held along its bottom, dynamic, φ = 30°, 2 s with no damping but the scheme's. Its
// kinetic energy must settle onto the contact springs in the first steps and then stay at
// round-off, and nothing may creep (docs/contact.md, "What the tests show").
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "tests/ended_ok.h"
#include "preprocess/cover_cutter.h"
#include "solver/output/energy.h"
#include "reference/scene_pieces.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::test {

struct RestingBlockRun {
  Outcome status;        ///< the run's status ("ok")
  double kinetic_max = 0;    ///< J/m, largest kinetic energy over the 2 s
  double kinetic_late = 0;   ///< J/m, largest after t = 1 s
  double weight_height = 0;  ///< J/m, the block's weight times its height (m·g·1 m)
  std::array<double, 2> moved{};  ///< m, displacement of the block's centre at 2 s
  double normal_force_sum = 0;     ///< N/m, Σ N over the contacts at 2 s
  double weight = 0;               ///< N/m, the block's weight (2 m × 1 m of rock)
};

inline RestingBlockRun resting_block_two_seconds(int order) {
  SceneDef s = reference::interface_scene(0.5, 30, order);
  s.bodies = {reference::box(0, 0, 6, 1), reference::box(2, 1, 4, 2)};
  s.fixed_points = reference::held_along(0.1, 5.9, 0.1);
  s.measure_points = {{3, 1.5}};
  const Mesh m = pre::build_mesh(s, "rest");
  solve::TimeStepper st(m, s, "rest");
  solve::EnergyMeter meter(st.view().model);
  meter.after_step(st.view().state, energy_sources(st.view()), true);
  RestingBlockRun r;
  r.status = st.run_until(2.0, [&](std::int64_t) {
    meter.after_step(st.view().state, energy_sources(st.view()), true);
    r.kinetic_max = std::max(r.kinetic_max, meter.rows().back().kinetic);
    if (st.view().state.time > 1.0) r.kinetic_late = std::max(r.kinetic_late, meter.rows().back().kinetic);
  });
  r.weight_height = 2650 * 2.0 * 9.81 * 1.0;
  const auto u = st.view().state.measure[0].displacement();
  r.moved = {u[0], u[1]};
  for (const solve::Contact& c : st.view().contacts.contacts()) r.normal_force_sum += c.normal_force;
  r.weight = 2650 * 2.0 * 9.81;
  return r;
}

/// What the run must show at any order, with `label` naming it in the printed line.
inline void expect_resting_block_at_rest(const RestingBlockRun& r, const char* label) {
  ASSERT_PRED1(test::ended_ok, r.status);
  std::printf("%sresting block, 2 s: largest kinetic energy %.3e J/m (after 1 s %.3e), moved %.3e, %.3e m, "
              "Σ N / weight %.6f\n",
              label, r.kinetic_max, r.kinetic_late, r.moved[0], r.moved[1], r.normal_force_sum / r.weight);
  EXPECT_LT(r.kinetic_max, 1e-5 * r.weight_height);  // settling onto its springs in the first steps
  EXPECT_LT(r.kinetic_late, 1e-8 * r.weight_height);
  EXPECT_LT(std::abs(r.moved[0]), 1e-6);
  EXPECT_LT(std::abs(r.moved[1]), 1e-4);
  // The block's weight is carried by its contacts: Σ N = m·g.
  EXPECT_NEAR(r.normal_force_sum, r.weight, 1e-3 * r.weight);
}

}  // namespace nmm::test
