// Cohesion and tensile bonds break only on the accepted state of a step (docs/contact.md
// "Cohesion and tensile bonds"), checked against limit equilibrium and the joint's own strength:
//   - Hoek–Bray wedges with F = 2.19 and 1.43 by peak strength stand, brittle as plastic,
//     nothing broken;
//   - a brittle wedge with F < 1 by peak strength slides, as friction alone lets it;
//   - a direct shear box with brittle cohesion peaks at c + σ·tanφ and drops to σ·tanφ;
//   - a bonded block pulled off its base breaks at T × its contact length;
//   - progressive failure where accepted states do exceed the strength: a box pushed above its
//     joint breaks contact by contact from its unloaded end, below the uniform peak.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/ended_ok.h"
#include "common/math_constants.h"
#include "preprocess/cover_cutter.h"
#include "reference/direct_shear.h"
#include "reference/joint_specimen.h"
#include "reference/scene_pieces.h"
#include "reference/slides.h"
#include "solver/stepping/time_stepper.h"
#include "studies/direct_shear_run.h"

namespace nmm {
namespace {

double rad(double deg) { return deg * kPi / 180; }

struct WedgeRun {
  Outcome status;
  double moved = 0;    ///< m, |displacement| of the wedge's measure point at the end
  long broken = 0;     ///< bonds broken
  long slips = 0;      ///< contacts that started to slide
  long resolved = 0;   ///< steps solved again for breaks
};

// The wedge of reference::planar_slide (H 8 m, face 60°, plane 35°, crack 6 m from the toe),
// φ 34°, cohesion c (Pa), brittle or perfectly plastic, for 0.8 s; `dynamic` off: DDA static
// analysis. *fos: Hoek & Bray's F by peak strength.
WedgeRun wedge(double cohesion, bool plastic, bool dynamic, double* fos = nullptr) {
  const double seconds = 0.8;
  const reference::ReferenceSlide ref = reference::planar_slide(8, 60, 35, 6, 34, cohesion, seconds, plastic);
  if (fos) *fos = ref.fos;
  nlohmann::json doc = ref.scene;
  doc["solver"]["dynamic"] = dynamic;
  const SceneDef s = scene_from_json(doc, "wedge");
  const Mesh m = pre::build_mesh(s, "wedge");
  solve::TimeStepper st(m, s, "wedge");
  WedgeRun r;
  r.status = st.run_until(seconds, [](std::int64_t) {});
  const auto u = st.view().state.measure[0].displacement();
  r.moved = std::hypot(u[0], u[1]);
  r.broken = st.view().contacts.events.broken;
  r.slips = st.view().contacts.events.slid;
  r.resolved = st.view().contact_solve.steps_resolved_for_breaks;
  return r;
}

}  // namespace

// F = 2.19 and 1.43 by peak strength (c 40 and 15 kPa): the brittle wedge stands like the
// plastic one, in DDA static analysis and dynamic. No contact reaches its peak, so nothing breaks
// and the brittle run is the plastic run, bit for bit. (Before bonds broke only on accepted
// states, iterates that slid broke 5 and 47 bonds in the static runs, and the dynamic brittle
// wedge at F = 1.43 slid 6.8 cm in 0.8 s.)
TEST(Bonds, WedgeAboveItsPeakStrengthStandsUnbroken) {
  for (const double c : {40e3, 15e3})
    for (const bool dynamic : {false, true}) {
      double fos = 0;
      const WedgeRun brittle = wedge(c, false, dynamic, &fos);
      const WedgeRun plastic = wedge(c, true, dynamic);
      std::printf("wedge F = %.3f, %s: brittle moved %.4e m, %ld broken, %ld slips; plastic moved %.4e m, "
                  "%ld broken\n", fos, dynamic ? "dynamic" : "static", brittle.moved, brittle.broken,
                  brittle.slips, plastic.moved, plastic.broken);
      ASSERT_PRED1(test::ended_ok, brittle.status);
      ASSERT_PRED1(test::ended_ok, plastic.status);
      EXPECT_GT(fos, 1.4);
      EXPECT_EQ(plastic.broken, 0);
      EXPECT_EQ(brittle.broken, 0);
      EXPECT_EQ(brittle.slips, 0);
      EXPECT_EQ(brittle.moved, plastic.moved);  // the same strengths all along: bit for bit
      EXPECT_LT(brittle.moved, 1e-4);           // elastic: it stands
    }
}

// c 1 kPa: F = 0.994 by peak strength. The brittle wedge breaks along its plane at once and
// slides as friction alone lets it: as the same wedge without cohesion (within 1 %), and as a
// rigid block from rest, s = ½·g(sinψ − cosψ·tanφ)·t² (within 5 %: the wedge's first steps
// settle it onto the plane's springs).
TEST(Bonds, WedgeBelowItsPeakStrengthSlides) {
  double fos = 0;
  const WedgeRun r = wedge(1e3, false, true, &fos);
  const WedgeRun frictional = wedge(0, false, true);
  const double a = 9.81 * (std::sin(rad(35)) - std::cos(rad(35)) * std::tan(rad(34)));
  const double rigid = 0.5 * a * 0.8 * 0.8;
  std::printf("wedge F = %.3f: moved %.4e m in 0.8 s (without cohesion %.4e m, rigid block %.4e m), %ld broken, "
              "%ld steps re-solved\n", fos, r.moved, frictional.moved, rigid, r.broken, r.resolved);
  ASSERT_PRED1(test::ended_ok, r.status);
  EXPECT_LT(fos, 1.0);
  EXPECT_GT(r.broken, 20);
  EXPECT_NEAR(r.moved, frictional.moved, 0.01 * frictional.moved);
  EXPECT_NEAR(r.moved, rigid, 0.05 * rigid);
}

namespace {
// A joint of constant stiffness (kn 5e11, ks 1e10 Pa/m) with friction φ, cohesion c and tensile
// strength T, brittle (residual cohesion 0).
JointSetDef bonded_joint(double phi_deg, double cohesion, double tensile) {
  JointSetDef j;
  j.name = "joint";
  j.friction_deg = phi_deg;
  j.cohesion = cohesion;
  j.tensile_strength = tensile;
  j.normal.model = NormalModel::constant;
  j.normal.kn = 5e11;
  j.shear.model = ShearModel::constant;
  j.shear.ks = 1e10;
  return j;
}

// The stiff rock (E = 500 GPa) and soft joint of the two boxes below: the blocks move nearly as
// rigid bodies against the joint's springs, so the joint's stress is uniform along it and every
// contact reaches its strength together (a softer rock or a stiffer joint spreads the load from
// where it is applied: Bonds.ProgressiveFailureFromAStressConcentration).
SceneDef stiff_rock_on_joint(const JointSetDef& joint) {
  SceneDef s = reference::interface_scene(0.25, joint.friction_deg);
  s.materials[0].young = 5e11;
  s.joint_sets[0] = joint;
  s.has_gravity = false;
  s.solver.dynamic_factor = 0;  // quasi-static: each step starts from rest
  s.solver.support_stiffness = 1e14;
  return s;
}

// Σ over the closed contacts of the last accepted step: normal force (N/m, compression > 0) and
// shear force (N/m).
std::array<double, 2> joint_forces(const solve::TimeStepper& st) {
  std::array<double, 2> f{};
  for (const solve::Contact& k : st.view().contacts.accepted())
    if (k.state != solve::ContactState::open) {
      f[0] += k.normal_force;
      f[1] += k.shear_force;
    }
  return f;
}
}  // namespace

// A direct shear box, displacement-controlled, without the overturning moment of a push above
// the joint: the upper block (2.5 m × 1 m) overhangs the lower one (2 m × 1 m, held along its
// base) by 0.5 m at its left, and the overhang's underside — at the joint's level — is driven
// along the joint at 10 mm/s; σn = 1 MPa by point loads on its top face above the joint.
// Joint: kn 10 GPa/m, ks 1 GPa/m, φ 30°, c 0.5 MPa, brittle. The joint's 2 m carry τ up to the peak
// c + σn·tanφ = 1.077 MPa, break, and then slide at σn·tanφ = 0.577 MPa, within 1 %.
TEST(Bonds, DirectShearPeaksAtCohesionPlusFrictionThenDropsToFriction) {
  const double sn = 1e6, c = 0.5e6, phi = 30, length = 2;
  JointSetDef joint = bonded_joint(phi, c, 0);
  joint.normal.kn = 1e9;
  joint.shear.ks = 1e9;
  SceneDef s = stiff_rock_on_joint(joint);
  s.bodies = {reference::box(0, 0, 2, 1), reference::box(-0.5, 1, 2, 2)};
  s.fixed_points = reference::held_along(0.1, 1.9, 0.05);
  const int n = 20;  // point loads on the top face above the joint's 2 m, the end ones half
  for (int i = 0; i <= n; ++i)
    s.loads.push_back({{length * i / n, 2}, {0, -sn * length / n * (i == 0 || i == n ? 0.5 : 1.0)}});
  SupportDef drive;
  drive.points = {{-0.5, 1}, {0, 1}};
  drive.fix_x = true;
  drive.velocity = {2e-3, 0};
  s.supports.push_back(drive);
  s.measure_points = {{1, 1.5}};
  const Mesh m = pre::build_mesh(s, "shear box");
  solve::TimeStepper st(m, s, "shear box");
  double peak = 0, peak_t = 0, normal_at_peak = 0;
  std::array<double, 2> end{};
  for (int k = 1; k <= 700; ++k) {
    ASSERT_PRED1(test::ended_ok, st.run_until(k * s.solver.time_step, [](std::int64_t) {}));
    end = joint_forces(st);
    if (std::abs(end[1]) > peak) {
      peak = std::abs(end[1]);
      peak_t = st.view().state.time;
      normal_at_peak = end[0];
    }
  }
  const double want_peak = (c + sn * std::tan(rad(phi))) * length, want_residual = sn * std::tan(rad(phi)) * length;
  std::printf("shear box: peak %.5e N/m at %.3f s (σn %.4f MPa; (c + σn·tanφ)·L = %.5e), at the end %.5e N/m "
              "(σn·tanφ·L = %.5e), %ld bonds broken\n", peak, peak_t, normal_at_peak / length / 1e6, want_peak,
              std::abs(end[1]), want_residual, st.view().contacts.events.broken);
  EXPECT_NEAR(peak, want_peak, 0.01 * want_peak);
  EXPECT_NEAR(std::abs(end[1]), want_residual, 0.01 * want_residual);
  EXPECT_GT(st.view().state.time, peak_t + 0.05);  // well past the peak
}

// A 2 m × 1 m block resting on its base, bonded to it by a joint of tensile strength
// T = 0.2 MPa (kn 1 GPa/m), pulled off by its top face at 0.5 mm/s. A bond forms only where the
// joint is closed at the start of a step, so the top face is first pushed down for 10 ms (its
// velocity history −1, then +1). The bond carries tension up to T × 2 m = 0.4 MN/m, within 1 %,
// and then lets go.
TEST(Bonds, BondedBlockPulledApartBreaksAtTensileStrengthTimesLength) {
  const double tensile = 0.2e6, width = 2;
  JointSetDef joint = bonded_joint(30, 1e6, tensile);
  joint.normal.kn = 1e9;
  SceneDef s = stiff_rock_on_joint(joint);
  s.bodies = {reference::box(0, 0, 4, 1), reference::box(1, 1, 1 + width, 2)};
  s.fixed_points = reference::held_along(0.1, 3.9, 0.05);
  SupportDef pull;
  pull.points = {{1, 2}, {1 + width, 2}};
  pull.fix_y = true;
  pull.velocity = {0, 5e-4};
  pull.table.time = {0, 0.01, 0.0101};
  pull.table.value = {-1, -1, 1};
  s.supports.push_back(pull);
  s.measure_points = {{2, 1.5}};
  const Mesh m = pre::build_mesh(s, "pull");
  solve::TimeStepper st(m, s, "pull");
  double largest = 0, after = 0;
  long broke_at = -1;
  for (int k = 1; k <= 500; ++k) {
    ASSERT_PRED1(test::ended_ok, st.run_until(k * s.solver.time_step, [](std::int64_t) {}));
    const double tension = -joint_forces(st)[0];
    if (broke_at < 0 && st.view().contacts.events.broken > 0) broke_at = k;
    if (broke_at < 0) largest = std::max(largest, tension);
    after = tension;
  }
  std::printf("bonded block: largest tension %.6e N/m (T × L = %.6e), broken at step %ld, %ld bonds, then "
              "%.3e N/m\n", largest, tensile * width, broke_at, st.view().contacts.events.broken, after);
  EXPECT_NEAR(largest, tensile * width, 0.01 * tensile * width);
  EXPECT_GT(broke_at, 0);
  EXPECT_LT(std::abs(after), 1e-6 * tensile * width);
}

// Progressive failure where accepted states do exceed the strength: the same box and joint, but
// pushed on the upper block's whole left face (x = 0, 1 ≤ y ≤ 2) as a careless apparatus would.
// The push acts 0.5 m above the joint, and its moment unloads the pushed end: the joint breaks
// there first and unzips towards the far end over many steps, each break at an accepted state
// where that contact's force had reached c·L + tanφ·N, while the joint as a whole never carries
// its uniform peak (c + σn·tanφ)·L.
TEST(Bonds, ProgressiveFailureFromAStressConcentration) {
  const double sn = 1e6, c = 0.5e6, phi = 30, length = 2;
  JointSetDef joint = bonded_joint(phi, c, 0);
  joint.normal.kn = 1e10;  // stiffer than the box above: the far end closes 0.3 mm, not 3
  joint.shear.ks = 1e9;
  SceneDef s = stiff_rock_on_joint(joint);
  s.bodies = {reference::box(0, 0, 2, 1), reference::box(0, 1, 2, 2)};
  s.fixed_points = reference::held_along(0.1, 1.9, 0.05);
  const int n = 20;
  for (int i = 0; i <= n; ++i)
    s.loads.push_back({{length * i / n, 2}, {0, -sn * length / n * (i == 0 || i == n ? 0.5 : 1.0)}});
  SupportDef push;
  push.points = {{0, 1}, {0, 2}};
  push.fix_x = true;
  push.velocity = {2e-3, 0};
  s.supports.push_back(push);
  s.measure_points = {{1, 1.5}};
  const Mesh m = pre::build_mesh(s, "pushed box");
  solve::TimeStepper st(m, s, "pushed box");
  double peak = 0;
  std::vector<int> break_steps;      // steps in which bonds broke
  double first_x = -1, last_x = -1;  // m, where the first and the last bonds broke
  long broken = 0;
  for (int k = 1; k <= 700; ++k) {
    ASSERT_PRED1(test::ended_ok, st.run_until(k * s.solver.time_step, [](std::int64_t) {}));
    peak = std::max(peak, std::abs(joint_forces(st)[1]));
    if (st.view().contacts.events.broken == broken) continue;
    broken = st.view().contacts.events.broken;
    break_steps.push_back(k);
    // Where this step's breaks are: the mean x of the newly broken contacts' vertices.
    double sum = 0;
    int count = 0;
    for (std::size_t i = 0; i < st.view().contacts.history().size(); ++i) {
      const solve::ContactHistory& h = st.view().contacts.history()[i];
      if (!h.broken) continue;
      sum += st.view().state.loop_xy[2 * static_cast<std::size_t>(h.vertex)];
      ++count;
    }
    const double x = count > 0 ? sum / count : -1;
    if (first_x < 0) first_x = x;
    last_x = x;
  }
  const double uniform_peak = (c + sn * std::tan(rad(phi))) * length;
  std::printf("pushed box: peak %.4e N/m (%.1f %% of the uniform peak %.4e), bonds broke in %zu steps from "
              "step %d to %d, the broken part's centre moving from x = %.2f m to %.2f m\n", peak,
              100 * peak / uniform_peak, uniform_peak, break_steps.size(), break_steps.empty() ? -1 : break_steps.front(),
              break_steps.empty() ? -1 : break_steps.back(), first_x, last_x);
  ASSERT_GE(break_steps.size(), 5u);  // progressive: over many steps, not at once
  EXPECT_LT(first_x, 0.5);            // from the pushed end
  EXPECT_GT(last_x, first_x + 0.3);   // growing along the joint
  EXPECT_LT(peak, 0.97 * uniform_peak);  // the uniform box: 99.8 %
}
}  // namespace nmm
