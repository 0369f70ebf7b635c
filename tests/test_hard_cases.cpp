// Hard cases for the solver (issue 6): penalties from 1 to 10⁴ × E, time steps far too large,
// joints driven to their maximum closure, a tall stack, sliver elements and a thin wedge,
// near-parallel joints, and a long run of a resting block.
//
// Every case checks what a wrong model would fail, not only that the run finishes:
// - the run ends "ok" (time steps far too large may instead stop cleanly, with a reason);
// - velocity(), stress() and loop_xy() are finite after every accepted step;
// - max_penetration() is far below the block size;
// - no energy from nowhere (all but the joint-closure case, which is quasi-static under point
//   loads): the bodies start at rest, unstressed, with every contact at zero gap and every
//   fixed point unloaded, and gravity is the only load, so the kinetic energy ½·vᵀMv
//   (consistent mass) can never exceed the work gravity has done, W = Σ_c G_c·u_c
//   (G_c = ρg∫w_c dA). Elastic, contact and fixed-point springs store energy, Newmark (γ = 1)
//   and friction dissipate it; none of them may create it. Checked after every step;
// - resting bodies are at rest: the largest cover speed (and, with slivers, the largest speed
//   of a material point) at the end is small, and measure points stay where they were put.
//
// Every test runs (none is disabled). Found by this suite and fixed, each test's comment giving
// the numbers before and after: sliver covers (joints 1e-9·h beside mesh nodes) that stopped the
// run, blocks that fell through a joint along mesh edges, and the period-2 motion at the shared
// bottom corner of two blocks side by side beside mesh nodes. UntiedSliverCoversStopTheRun keeps
// the first failure in view: with the cure switched off the run still stops.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tests/ended_ok.h"
#include "preprocess/cover_cutter.h"
#include "reference/brick_wall.h"
#include "reference/joint_specimen.h"
#include "reference/scene_pieces.h"
#include "solver/discretisation/element_integration.h"
#include "solver/stepping/time_stepper.h"
#include "common/math_constants.h"

namespace nmm::solve {
namespace {

constexpr double kG = 9.81;
constexpr double kE = 1e10;  // Pa, the rock's Young's modulus
// m/s: a body at rest moves slower than this. The damped scheme (Newmark β = 0.6) leaves resting
// blocks at 1e-13–3e-7 m/s in these scenes; Shi's undamped scheme (β = ½), whose resting blocks
// keep rocking, leaves 6e-6–3e-4 m/s (measured with solver.newmark_beta = 0.5), and most of
// these cases then fail.
constexpr double kRestSpeed = 1e-5;

// A frictional interface (φ = 30°) with DDA's point penalty kn = factor·E·(1 m) per contact point
// (model "penalty": the cases are stated in Shi's multiples of E), ks = kn/2.5.
SceneDef contact_scene(double h, double kn_factor) {
  SceneDef s;
  s.materials.push_back({"rock", 2650, kE, 0.25, {}});
  JointSetDef js;
  js.name = "interface";
  js.friction_deg = 30;
  js.normal.model = NormalModel::penalty;
  js.shear.model = ShearModel::penalty;
  js.normal.kn = kn_factor * kE;
  js.shear.ks = js.normal.kn / 2.5;
  s.joint_sets.push_back(js);
  s.interface_set = 0;
  s.mesh_size = h;
  s.has_gravity = true;
  s.gravity = {0, -kG};
  s.solver.time_step = 1e-3;
  return s;
}

using reference::box;

using reference::held_along;

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// Watches a run step by step: finiteness, kinetic energy against the work of gravity, speed.
class Monitor {
 public:
  Monitor(const Mesh& mesh, const SceneDef& scene) : mesh_(mesh) {
    // Consistent mass and gravity integrals on the starting configuration (the same exact
    // simplex integrals the solver uses; the mass of a body does not change as it moves).
    const std::size_t ne = mesh.element_count();
    mass_.resize(9 * ne);
    grav_.assign(2 * mesh.cover_count(), 0.0);
    const bool gravity = scene.has_gravity;
    for (std::size_t e = 0; e < ne; ++e) {
      int c[3];
      double p[6];
      for (int k = 0; k < 3; ++k) {
        c[k] = mesh.element_covers[3 * e + k];
        p[2 * k] = mesh.node_xy[2 * mesh.cover_node[c[k]]] - mesh.node_xy[2 * mesh.cover_node[c[0]]];
        p[2 * k + 1] =
            mesh.node_xy[2 * mesh.cover_node[c[k]] + 1] - mesh.node_xy[2 * mesh.cover_node[c[0]] + 1];
      }
      const TriangleWeights w = triangle_weights(p);
      const std::size_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
      const PolygonMoments m = polygon_moments(mesh.loop_xy.data() + 2 * b, n,
                                               mesh.node_xy[2 * mesh.cover_node[c[0]]],
                                               mesh.node_xy[2 * mesh.cover_node[c[0]] + 1]);
      const double rho = scene.materials[scene.bodies[mesh.element_body[e]].material].density;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) mass_[9 * e + 3 * i + j] = rho * integral_ww(w, m, i, j);
        if (gravity) {
          grav_[2 * c[i]] += rho * scene.gravity.x * integral_w(w, m, i);
          grav_[2 * c[i] + 1] += rho * scene.gravity.y * integral_w(w, m, i);
        }
      }
      total_mass_ += rho * m.a;
    }
  }

  // Call after every accepted step.
  void sample(const TimeStepper& st) {
    ++samples_;
    if (finite_ && !(all_finite(st.view().state.velocity) && all_finite(st.view().state.stress) &&
                     all_finite(st.view().state.loop_xy) && all_finite(st.view().state.cover_u))) {
      finite_ = false;
      first_bad_time_ = st.view().state.time;
    }
    const double ke = kinetic_energy(st.view().state.velocity);
    const double w = gravity_work(st.view().state.cover_u);
    max_ke_ = std::max(max_ke_, ke);
    if (ke - w > max_excess_) {
      max_excess_ = ke - w;
      excess_time_ = st.view().state.time;
      excess_ke_ = ke;
      excess_w_ = w;
    }
  }

  double kinetic_energy(const std::vector<double>& v) const {
    double ke = 0;
    for (std::size_t e = 0; e < mesh_.element_count(); ++e) {
      const std::int32_t* c = &mesh_.element_covers[3 * e];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          ke += mass_[9 * e + 3 * i + j] * (v[2 * c[i]] * v[2 * c[j]] + v[2 * c[i] + 1] * v[2 * c[j] + 1]);
    }
    return 0.5 * ke;
  }
  double gravity_work(const std::vector<double>& u) const {
    double w = 0;
    for (std::size_t i = 0; i < u.size(); ++i) w += grav_[i] * u[i];
    return w;
  }

  bool finite() const { return finite_; }
  double first_bad_time() const { return first_bad_time_; }
  double total_mass() const { return total_mass_; }  ///< kg per metre of thickness
  double max_ke() const { return max_ke_; }
  std::size_t samples() const { return samples_; }
  /// Largest KE − W over the run, J, and where it was.
  double max_excess() const { return max_excess_; }
  double excess_time() const { return excess_time_; }
  double excess_ke() const { return excess_ke_; }
  double excess_w() const { return excess_w_; }
  /// Energy tolerance: round-off on the larger of KE and W, plus the energy of the total weight
  /// moving 1 nm (far below anything a resting block could gain from a wrong contact model).
  double tolerance(double scale) const { return 1e-6 * scale + total_mass_ * kG * 1e-9; }

 private:
  const Mesh& mesh_;
  std::vector<double> mass_;  // [9·me] ρ∫w_i w_j dA
  std::vector<double> grav_;  // [2·pc] N, ρg∫w_c dA
  double total_mass_ = 0;
  bool finite_ = true;
  double first_bad_time_ = -1;
  double max_ke_ = 0;
  double max_excess_ = -std::numeric_limits<double>::infinity();
  double excess_time_ = 0, excess_ke_ = 0, excess_w_ = 0;
  std::size_t samples_ = 0;
};

double max_speed(const TimeStepper& st) {
  const auto& v = st.view().state.velocity;
  double s = 0;
  for (std::size_t i = 0; i + 1 < v.size(); i += 2) s = std::max(s, std::hypot(v[i], v[i + 1]));
  return s;
}

double norm(const std::array<double, 2>& u) { return std::hypot(u[0], u[1]); }

// Runs to time t, sampling every accepted step.
Outcome run_to(TimeStepper& st, Monitor& mon, double t) {
  return st.run_until(t, [&](std::int64_t) { mon.sample(st); });
}

// The checks every case shares: finite state, no energy from nowhere, bounded penetration.
void expect_sound(const TimeStepper& st, const Monitor& mon, double block_size, const char* what) {
  EXPECT_TRUE(mon.finite()) << what << ": a non-finite velocity, stress or vertex at t = "
                            << mon.first_bad_time() << " s";
  EXPECT_TRUE(all_finite(st.view().state.velocity) && all_finite(st.view().state.stress) && all_finite(st.view().state.loop_xy))
      << what;
  EXPECT_GT(mon.samples(), 0u) << what << ": no step was accepted";
  EXPECT_LE(mon.max_excess(), mon.tolerance(std::max(mon.excess_ke(), std::abs(mon.excess_w()))))
      << what << ": kinetic energy " << mon.excess_ke() << " J exceeds the work of gravity "
      << mon.excess_w() << " J at t = " << mon.excess_time() << " s";
  EXPECT_LT(st.view().state.max_penetration, 1e-3 * block_size) << what << ": penetration, m";
}

void print_energy(const char* what, const Monitor& mon) {
  std::printf("  %s: max KE %.3e J; largest KE - W %.3e J at t = %.3f s (KE %.3e J, W %.3e J)\n",
              what, mon.max_ke(), mon.max_excess(), mon.excess_time(), mon.excess_ke(),
              mon.excess_w());
}

// ---- 1. Contact stiffness from 1 to 10⁴ × E ---------------------------------------------------

TEST(HardCases, PenaltyFromOneToTenThousandTimesE) {
  // A 1 m block resting on a held base (touching at t = 0), dynamic, 0.2 s.
  for (double factor : {1.0, 10.0, 100.0, 1e3, 1e4}) {
    SceneDef s = contact_scene(0.25, factor);
    s.bodies = {box(0, 0, 4, 1), box(1.5, 1, 2.5, 2)};
    s.fixed_points = held_along(0.1, 3.9, 0.1);
    s.measure_points = {{2, 1.5}};
    const Mesh m = pre::build_mesh(s, "penalty");
    TimeStepper st(m, s, "penalty");
    Monitor mon(m, s);
    const Outcome status = run_to(st, mon, 0.2);
    const auto u = st.view().state.measure[0].displacement();
    std::printf("kn = %6g E: status %s; block moved (%.3e, %.3e) m; max speed %.3e m/s; max "
                "penetration %.3e m; %zu cuts, %zu iterations\n",
                factor, test::text(status).c_str(), u[0], u[1], max_speed(st), st.view().state.max_penetration,
                st.view().state.cuts, st.view().state.iterations);
    print_energy("energy", mon);
    const std::string what = "kn = " + std::to_string(factor) + " E";
    EXPECT_PRED1(test::ended_ok, status) << what;
    expect_sound(st, mon, 1.0, what.c_str());
    // Weight 26 kN over a 1 m face on springs of ≥ 1·E: it sinks micrometres, never millimetres.
    EXPECT_LT(norm(u), 1e-4) << what << ": the block rests where it was put";
    EXPECT_LT(max_speed(st), kRestSpeed) << what << ": at rest, m/s";
  }
}

// ---- 2. Time steps far too large ------------------------------------------------------------

TEST(HardCases, TimeStepsFarTooLargeAreCutOrStopCleanly) {
  // A 1 m block dropped 5 cm onto the base with Δt = 0.05 s and 0.2 s: the first step alone would
  // move it 1.2 cm and 20 cm, far more than the step control allows (2·g2·w0 = 4 mm).
  for (double dt : {0.05, 0.2}) {
    SceneDef s = contact_scene(0.25, 20);
    s.solver.time_step = dt;
    s.bodies = {box(0, 0, 4, 1), box(1.5, 1.05, 2.5, 2.05)};
    s.fixed_points = held_along(0.1, 3.9, 0.1);
    s.measure_points = {{2, 1.55}};
    const Mesh m = pre::build_mesh(s, "large_dt");
    TimeStepper st(m, s, "large_dt");
    Monitor mon(m, s);
    const Outcome status = run_to(st, mon, 1.0);
    const auto u = st.view().state.measure[0].displacement();
    std::printf("dt = %g s: status %s; t = %.4f s; fell %.5f m; max speed at end %.3e m/s; "
                "penetration %.3e m; %zu cuts, %zu iterations\n",
                dt, test::text(status).c_str(), st.view().state.time, -u[1], max_speed(st), st.view().state.max_penetration,
                st.view().state.cuts, st.view().state.iterations);
    print_energy("energy", mon);
    const std::string what = "dt = " + std::to_string(dt);
    expect_sound(st, mon, 1.0, what.c_str());
    if (status.ok()) {
      EXPECT_GT(st.view().state.cuts, 0u) << what << ": step control must cut a step this long";
      EXPECT_NEAR(u[1], -0.05, 1e-3) << what << ": the block lands on the base";
      EXPECT_LT(std::abs(u[0]), 1e-3) << what;
      EXPECT_LT(max_speed(st), 10 * kRestSpeed) << what << ": and rests there, m/s";
    } else {
      std::printf("  stopped: %s\n", test::text(status).c_str());
    }
  }
}

// ---- 3. Joints near maximum closure ---------------------------------------------------------

TEST(HardCases, BandisBartonJointBeyondMaximumClosureStaysCapped) {
  // One horizontal joint between two 2 m × 1 m bodies (the set-up of test_joint_law), loaded to
  // σn = 100 MPa and 1000 MPa, 29 and 290 times Kni·Vm = 3.48 MPa. The closure curve gives
  // δ = 0.966·Vm at 100 MPa; at 1000 MPa δ would be 0.9965·Vm, above the 0.99·Vm guard, beyond
  // which the force grows linearly with the tangent at the cap (1e4·Kni): the closure may exceed
  // the cap by only (σn − σcap)/(1e4·Kni) = 0.019·Vm (σcap = 99·Kni·Vm = 345 MPa).
  const JointSetDef joint = reference::seed_shear_joint();  // Kni 15.35 GPa/m, Vm 0.227 mm
  const double kni = joint.normal.kni, vm = joint.normal.vm;
  for (double sigma_n : {100e6, 1000e6}) {
    SceneDef s;
    s.materials.push_back({"rock", 2650, 5e11, 0.25, {}});
    s.joint_sets.push_back(joint);
    s.interface_set = 0;
    s.mesh_size = 0.25;
    s.plane = PlaneKind::stress;
    s.bodies = {box(0, 0, 2, 1), box(0, 1, 2, 2)};
    for (double x = 0.05; x < 2; x += 0.1) s.fixed_points.push_back({x, 0.02});
    const int n = 20;
    for (int i = 0; i <= n; ++i) {
      const double w = (i == 0 || i == n) ? 0.5 : 1.0;
      s.loads.push_back({{2.0 * i / n, 2.0}, {0, -sigma_n * 2.0 / n * w}});
    }
    s.measure_points = {{1.0, 1.0001}, {1.0, 0.9999}};
    s.solver.time_step = 1e-3;
    s.solver.dynamic_factor = 0;  // quasi-static: settles to equilibrium
    s.solver.max_displacement_ratio = 0.01;
    const Mesh m = pre::build_mesh(s, "closure");
    TimeStepper st(m, s, "closure");
    std::size_t max_capped = 0;
    bool forces_finite = true, state_finite = true;
    double max_closure = 0;
    const Outcome status = st.run_until(0.3, [&](std::int64_t) {
      max_capped = std::max(max_capped, st.view().contacts.totals().capped);
      state_finite = state_finite && all_finite(st.view().state.velocity) && all_finite(st.view().state.stress) &&
                     all_finite(st.view().state.loop_xy);
      for (const Contact& c : st.view().contacts.contacts()) {
        forces_finite = forces_finite && std::isfinite(c.normal_force) && std::isfinite(c.shear_force);
        if (c.state != ContactState::open) max_closure = std::max(max_closure, -c.gap);
      }
    });
    const auto a = st.view().state.measure[0].displacement();
    const auto b = st.view().state.measure[1].displacement();
    const double closure_mid = b[1] - a[1];
    double closure_end = 0, force_sum = 0;
    std::size_t closed = 0;
    for (const Contact& c : st.view().contacts.contacts()) {
      if (c.state == ContactState::open) continue;
      ++closed;
      closure_end = std::max(closure_end, -c.gap);
      force_sum += c.normal_force;
    }
    const double want = std::min(sigma_n * vm / (kni * vm + sigma_n), 0.99 * vm);
    std::printf("sigma_n = %4.0f MPa: status %s; closure at mid-joint %.4e m = %.4f Vm "
                "(curve, capped at 0.99 Vm: %.4f Vm); largest contact closure %.4f Vm (any step "
                "%.4f Vm); %zu closed contacts carrying %.4e N (load %.4e N); capped now %zu, "
                "most %zu; %zu cuts\n",
                sigma_n / 1e6, test::text(status).c_str(), closure_mid, closure_mid / vm, want / vm,
                closure_end / vm, max_closure / vm, closed, force_sum, sigma_n * 2.0,
                st.view().contacts.totals().capped, max_capped, st.view().state.cuts);
    const std::string what = "sigma_n = " + std::to_string(sigma_n / 1e6) + " MPa";
    EXPECT_PRED1(test::ended_ok, status) << what;
    EXPECT_TRUE(state_finite) << what;
    EXPECT_TRUE(forces_finite) << what;
    EXPECT_LT(max_closure, 1.01 * vm) << what << ": the closure must stay at the cap";
    EXPECT_GT(closure_mid, 0.9 * vm) << what << ": the joint is closed nearly to Vm";
    EXPECT_NEAR(force_sum, sigma_n * 2.0, 0.02 * sigma_n * 2.0) << what << ": the joint carries the load";
    if (sigma_n < 345e6) {
      EXPECT_NEAR(closure_end, want, 0.01 * want) << what << ": below the cap, on the Bandis-Barton curve";
    } else {
      EXPECT_GT(max_capped, 0u) << what << ": contacts reach the closure cap";
    }
  }
}

// ---- 4. A stack of 10 blocks ----------------------------------------------------------------

TEST(HardCases, StackOfTenBlocksStands) {
  SceneDef s = contact_scene(0.25, 20);
  s.bodies = {box(0, 0, 4, 0.5)};
  for (int i = 0; i < 10; ++i) s.bodies.push_back(box(1.5, 0.5 + 0.5 * i, 2.5, 1.0 + 0.5 * i));
  s.fixed_points = held_along(0.1, 3.9, 0.1);
  s.measure_points = {{2, 5.25}, {2, 0.75}};
  const Mesh m = pre::build_mesh(s, "stack10");
  TimeStepper st(m, s, "stack10");
  Monitor mon(m, s);
  const Outcome status = run_to(st, mon, 1.0);
  const auto top = st.view().state.measure[0].displacement();
  const auto bottom = st.view().state.measure[1].displacement();
  std::printf("stack of 10: status %s; top moved (%.3e, %.3e) m, bottom block (%.3e, %.3e) m; "
              "max speed %.3e m/s; penetration %.3e m; %zu cuts, %zu iterations\n",
              test::text(status).c_str(), top[0], top[1], bottom[0], bottom[1], max_speed(st),
              st.view().state.max_penetration, st.view().state.cuts, st.view().state.iterations);
  print_energy("energy", mon);
  EXPECT_PRED1(test::ended_ok, status);
  expect_sound(st, mon, 0.5, "stack of 10");
  EXPECT_LT(norm(top), 1e-3) << "the stack stands";
  EXPECT_LT(max_speed(st), kRestSpeed) << "at rest, m/s";
}

// ---- 5. Slivers and a thin wedge ------------------------------------------------------------
//
// A 2 m × 1 m body resting on the base (mesh size h = 0.25 m) is cut by a joint passing a tiny
// distance beside mesh nodes:
// - horizontal: 1e-9·h or 1e-6·h above the whole row 6 of nodes (y = 6·h·√3/2), crossing the
//   body (two blocks), so every element just below the joint is a sliver of that thickness;
// - vertical: 1e-9·h or 1e-6·h right of the nodes at x = 2 (rows 6 and 8), from the top either
//   down to 5 cm above the base (it ends inside the body: a slit) or down to the base (it splits
//   the body into two blocks).
// Beside it, a wedge (a right triangle with a 2° apex, 1.6 m long and 5.6 cm high) may lie on
// the base.

enum class Beside { horizontal, vertical_slit, vertical_through };

struct NodeJointCase {
  const char* name;
  Beside kind;
  double offset;  // in units of h
};

SceneDef node_joint_scene(const NodeJointCase& c, bool wedge_on) {
  const double h = 0.25;
  SceneDef s = contact_scene(h, 20);
  s.bodies = {box(0, 0, 5, 1), box(1, 1, 3, 2)};
  if (wedge_on) {
    BodyDef wedge;
    wedge.material = 0;
    wedge.outer = {{3.2, 1}, {4.8, 1}, {4.8, 1 + 1.6 * std::tan(2 * kPi / 180)}};
    s.bodies.push_back(wedge);
  }
  const double row6 = 6 * h * std::sqrt(3.0) / 2, x = 2 + c.offset * h;
  if (c.kind == Beside::horizontal)
    s.joints.push_back({0, {{0.9, row6 + c.offset * h}, {3.1, row6 + c.offset * h}}});
  else
    s.joints.push_back({0, {{x, 2.1}, {x, c.kind == Beside::vertical_slit ? 1.05 : 1.0}}});
  s.fixed_points = held_along(0.1, 4.9, 0.1);
  s.measure_points = {{1.5, 1.75}, {2.5, 1.75}, {1.5, 1.1}, {2.5, 1.1}};
  if (wedge_on) s.measure_points.push_back({4.6, 1.02});
  return s;
}

// Largest speed of a material point: every element loop vertex, v = Σ w_k(P)·v_k over its
// element's covers (weights of the starting configuration; the bodies barely move). Unlike a
// cover's speed, this is the speed of the rock itself.
double max_point_speed(const Mesh& m, const TimeStepper& st) {
  const auto& v = st.view().state.velocity;
  double best = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    const std::int32_t* c = &m.element_covers[3 * e];
    const double ox = m.node_xy[2 * m.cover_node[c[0]]], oy = m.node_xy[2 * m.cover_node[c[0]] + 1];
    double p[6];
    for (int k = 0; k < 3; ++k) {
      p[2 * k] = m.node_xy[2 * m.cover_node[c[k]]] - ox;
      p[2 * k + 1] = m.node_xy[2 * m.cover_node[c[k]] + 1] - oy;
    }
    const TriangleWeights w = triangle_weights(p);
    for (std::int32_t i = m.element_loop_offset[e]; i < m.element_loop_offset[e + 1]; ++i) {
      double vx = 0, vy = 0;
      for (int k = 0; k < 3; ++k) {
        const double wk = w.at(k, m.loop_xy[2 * i] - ox, m.loop_xy[2 * i + 1] - oy);
        vx += wk * v[2 * c[k]];
        vy += wk * v[2 * c[k] + 1];
      }
      best = std::max(best, std::hypot(vx, vy));
    }
  }
  return best;
}

// Largest displacement of any element loop vertex since the start, m.
double max_vertex_displacement(const Mesh& m, const TimeStepper& st) {
  double best = 0;
  for (std::size_t i = 0; i < m.loop_xy.size(); i += 2)
    best = std::max(best, std::hypot(st.view().state.loop_xy[i] - m.loop_xy[i], st.view().state.loop_xy[i + 1] - m.loop_xy[i + 1]));
  return best;
}

struct NodeJointRun {
  Outcome status;
  double time = 0, cover_speed = 0, point_speed = 0, moved = 0, measured = 0;
  double drift_speed = 0;  // m/s, largest mean speed of a loop vertex over 0.1–0.2 s
  std::size_t slivers = 0, tied = 0;
};

// Runs the scene to 0.2 s, checks what must hold whatever the outcome (finite, no energy from
// nowhere, bounded penetration, no vertex flung away) and returns what the strict test judges.
NodeJointRun run_node_joint(const NodeJointCase& c, bool wedge_on, double sliver_weight = 1e-3) {
  SceneDef s = node_joint_scene(c, wedge_on);
  s.solver.sliver_cover_weight = sliver_weight;
  const Mesh m = pre::build_mesh(s, c.name);
  NodeJointRun r;
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    const double a = element_area(m, e);
    smallest = std::min(smallest, a);
    r.slivers += a < 1e-6 * s.mesh_size * s.mesh_size ? 1 : 0;
  }
  TimeStepper st(m, s, c.name);
  Monitor mon(m, s);
  r.tied = st.view().space.ties().tied;
  r.status = run_to(st, mon, 0.1);
  const std::vector<double> half_way = st.view().state.loop_xy;
  if (r.status.ok()) r.status = run_to(st, mon, 0.2);
  for (std::size_t i = 0; i < half_way.size(); i += 2)
    r.drift_speed = std::max(r.drift_speed, std::hypot(st.view().state.loop_xy[i] - half_way[i],
                                                       st.view().state.loop_xy[i + 1] - half_way[i + 1]) /
                                                (st.view().state.time - 0.1));
  r.time = st.view().state.time;
  r.cover_speed = max_speed(st);
  r.point_speed = max_point_speed(m, st);
  r.moved = max_vertex_displacement(m, st);
  for (const TrackedPoint& p : st.view().state.measure) r.measured = std::max(r.measured, norm(p.displacement()));
  std::printf("%s%s: %zu elements (%zu below 1e-6 h^2, smallest %.2e m^2), %zu blocks, %zu "
              "covers tied; status %s; t = %.5f s; speeds: cover %.3e, material point %.3e m/s, "
              "mean over 0.1-0.2 s %.3e m/s; largest vertex displacement %.3e m, measure points "
              "%.3e m; penetration %.3e m; %zu cuts\n",
              c.name, wedge_on ? " + 2-degree wedge" : "", m.element_count(), r.slivers, smallest,
              m.block_count(), r.tied, test::text(r.status).c_str(), r.time, r.cover_speed, r.point_speed,
              r.drift_speed, r.moved, r.measured, st.view().state.max_penetration, st.view().state.cuts);
  print_energy("energy", mon);
  EXPECT_GT(r.slivers, 0u) << c.name << ": the scene must make sliver elements";
  if (!r.status.ok()) return r;  // the caller judges a stop
  expect_sound(st, mon, 0.05, c.name);  // the wedge is 5.6 cm high
  EXPECT_LT(r.moved, 1e-3) << c.name << ": a vertex was flung away, m";
  return r;
}

TEST(HardCases, SliverElementsAndAThinWedgeRest) {
  // A slit 1e-6·h beside mesh nodes (its sliver covers tied), and the 2° wedge on the base.
  const NodeJointRun r = run_node_joint({"vertical slit 1e-6 h beside nodes", Beside::vertical_slit, 1e-6}, true);
  EXPECT_PRED1(test::ended_ok, r.status);
  EXPECT_LT(r.measured, 1e-4) << "the bodies rest where they were put, m";
  EXPECT_LT(r.moved, 1e-4) << "m";
  EXPECT_LT(r.cover_speed, kRestSpeed) << "at rest, m/s";
  EXPECT_LT(r.point_speed, kRestSpeed) << "at rest, m/s";
}

const NodeJointCase kHardNodeJoints[] = {
    {"horizontal joint 1e-9 h above a node row", Beside::horizontal, 1e-9},
    {"horizontal joint 1e-6 h above a node row", Beside::horizontal, 1e-6},
    {"vertical slit 1e-9 h beside nodes", Beside::vertical_slit, 1e-9},
    {"vertical joint 1e-9 h beside nodes, through", Beside::vertical_through, 1e-9},
    {"vertical joint 1e-6 h beside nodes, through", Beside::vertical_through, 1e-6},
};

// Found by this suite and fixed: joints a hair's breadth beside mesh nodes leave physical covers
// whose weight never exceeds ~offset/h (17 sliver elements down to 1.8e-20 m² here). Before
// those covers shared a neighbour's unknowns (solver/discretisation/cover_unknowns.cpp), with h = 0.25 m,
// kn = 20·E, Δt = 1e-3 s:
// - horizontal joint 1e-9·h above a node row: stopped at t = 0.00025 s, "time step cut below
//   its floor": a near-null cover moved 0.43 m in one step (387 m at 1e-12·h, 0.043 m at
//   1e-8·h: as 1/offset);
// - horizontal joint 1e-6·h: stopped at t = 0.00064 s, a cover at 1.6e3 m/s;
// - vertical slit or joint 1e-9·h beside nodes: stopped at t = 0.002–0.005 s, "the system matrix
//   is not positive definite" in a dynamic run (covers of 5.4e-20 m² elements lost in rounding);
// - vertical joint 1e-6·h: ran, but a sliver cover chattered at 7.7e-2 m/s for ever.
// Now all rest: material points at 1e-13 m/s.
TEST(HardCases, JointsBesideMeshNodesRest) {
  for (const NodeJointCase& c : kHardNodeJoints) {
    const NodeJointRun r = run_node_joint(c, false);
    EXPECT_PRED1(test::ended_ok, r.status) << c.name;
    EXPECT_GT(r.tied, 0u) << c.name << ": sliver covers must be tied";
    EXPECT_LT(r.measured, 1e-4) << c.name << ": the bodies rest where they were put, m";
    EXPECT_LT(r.moved, 1e-4) << c.name << ": m";
    // Resting on average: chatter (below) goes back and forth, a creeping body does not.
    EXPECT_LT(r.drift_speed, 1e-6) << c.name << ": mean speed over 0.1-0.2 s, m/s";
    EXPECT_LT(r.cover_speed, kRestSpeed) << c.name << ": at rest, m/s";
    EXPECT_LT(r.point_speed, kRestSpeed) << c.name << ": at rest, m/s";
  }
}

TEST(HardCases, UntiedSliverCoversStopTheRun) {
  // The same scene with tying switched off (solver.sliver_cover_weight = 0) still fails as
  // described above: the tie is what cures it. If this starts passing, the solver has become
  // robust to near-null covers by other means; revisit cover_unknowns.cpp.
  const NodeJointRun r = run_node_joint(kHardNodeJoints[0], false, 0.0);
  EXPECT_EQ(r.tied, 0u);
  EXPECT_FALSE(r.status.ok()) << "t = " << r.time << " s";
}

// Found by this suite and fixed: the vertical joint through the upper body (two 1 m blocks side
// by side on the base) within 0.01·h of mesh nodes (also at 1e-6·h and 1e-9·h) left a period-2
// motion at the blocks' shared bottom corner (2 + offset, 1): cover speed 6.9e-5 m/s, material
// points 3.8e-5 m/s (±7e-8 m per step), the mean over 0.1 s 4e-13 m/s — with every step solved
// to a residual of 1e-10, so not the iteration. Cause: each contact vertex kept one edge in all,
// and each of the two bottom corners there faces two blocks (the base and the other upper
// block). The left corner held the base in one step and the right block's face in the next, the
// right corner the reverse: a corner held only by the face sinks into the base, which makes the
// base's gap the smaller one next step, and so on (the step's solution really alternated; the
// Newmark damping of β = 0.6 cannot remove a mode the geometry drives). Now a vertex keeps one
// edge per other block, as DDA detects contacts block pair by block pair
// (solver/contact/contact_detection.cpp): both corners stay on the base every step and the blocks rest
// at 1e-13 m/s. A chattering corner moves ~1e-7 m per 1e-3 s step (1e-4 m/s): 1e-8 m/s fails it.
TEST(HardCases, BlocksSideBySideBesideMeshNodesAreStill) {
  for (const NodeJointCase& c : kHardNodeJoints) {
    if (c.kind != Beside::vertical_through) continue;
    const NodeJointRun r = run_node_joint(c, false);
    EXPECT_PRED1(test::ended_ok, r.status) << c.name;
    EXPECT_LT(r.cover_speed, 1e-8) << c.name << ": at rest, m/s";
    EXPECT_LT(r.point_speed, 1e-8) << c.name << ": at rest, m/s";
    EXPECT_LT(r.drift_speed, 1e-8) << c.name << ": mean speed over 0.1-0.2 s, m/s";
  }
}

TEST(HardCases, ACornerBetweenTwoBlocksTouchesBoth) {
  // The bottom corners of the two upper blocks at the joint each face the base and the other
  // block: each keeps a closed contact with the base in every step.
  const NodeJointCase c = kHardNodeJoints[4];  // vertical joint 1e-6·h beside nodes, through
  SceneDef s = node_joint_scene(c, false);
  s.solver.sliver_cover_weight = 1e-3;
  const Mesh m = pre::build_mesh(s, c.name);
  TimeStepper st(m, s, c.name);
  const double x = 2 + c.offset * s.mesh_size;
  int steps = 0;
  const Outcome status = st.run_until(0.05, [&](std::int64_t) {
    ++steps;
    // Corners at (x, 1): which blocks each touches (closed), by the corner's own block.
    std::map<std::int32_t, std::set<std::int32_t>> touched;
    for (const Contact& k : st.view().contacts.contacts()) {
      const double px = st.view().state.loop_xy[2 * k.at.vertex], py = st.view().state.loop_xy[2 * k.at.vertex + 1];
      if (std::hypot(px - x, py - 1) > 1e-3 * s.mesh_size || k.state == ContactState::open) continue;
      touched[m.element_block[k.at.elem_a]].insert(m.element_block[k.at.elem_b]);
    }
    std::int32_t base = -1;  // the block of an element below y = 0.5
    for (std::size_t e = 0; e < m.element_count() && base < 0; ++e)
      if (m.loop_xy[2 * m.element_loop_offset[e] + 1] < 0.5) base = m.element_block[e];
    int on_base = 0;
    for (const auto& [block, others] : touched)
      if (block != base) on_base += others.count(base) ? 1 : 0;
    EXPECT_EQ(on_base, 2) << "step " << steps << ": both upper corners rest on the base";
  });
  EXPECT_PRED1(test::ended_ok, status);
  EXPECT_GT(steps, 40);
}

TEST(HardCases, SliverCoversShareANeighboursUnknowns) {
  // The horizontal joint 1e-9·h above row 6: the covers of row 7's nodes below the joint are
  // strips 2.2e-10 m thick, weight ≤ 1e-9.
  const SceneDef s = node_joint_scene(kHardNodeJoints[0], false);
  const Mesh m = pre::build_mesh(s, "sliver covers");
  const CoverUnknowns u = assign_cover_unknowns(m, 1e-3);
  ASSERT_GT(u.tied, 0u);
  EXPECT_EQ(u.unknowns(), 2 * static_cast<int>(m.cover_count() - u.tied));
  std::size_t tied = 0;
  for (std::size_t c = 0; c < m.cover_count(); ++c) {
    const std::int32_t master = u.master[c];
    EXPECT_EQ(u.unknown[c], u.unknown[master]);
    EXPECT_EQ(u.cover_of_unknown[u.unknown[c] / 2], master);
    if (master == static_cast<std::int32_t>(c)) {
      EXPECT_GE(u.max_weight[c], 1e-3) << "cover " << c;
      continue;
    }
    ++tied;
    EXPECT_LT(u.max_weight[c], 1e-8) << "cover " << c << ": only the strips are slivers";
    EXPECT_GE(u.max_weight[master], 1e-3) << "cover " << c << ": its master is no sliver";
    EXPECT_EQ(u.master[master], master) << "no chains";
    // The master shares an element with it (same side of the joint, same block).
    bool shares = false;
    for (std::size_t e = 0; e < m.element_count() && !shares; ++e) {
      const std::int32_t* ec = &m.element_covers[3 * e];
      const bool has_c = ec[0] == static_cast<std::int32_t>(c) || ec[1] == static_cast<std::int32_t>(c) ||
                         ec[2] == static_cast<std::int32_t>(c);
      shares = has_c && (ec[0] == master || ec[1] == master || ec[2] == master);
    }
    EXPECT_TRUE(shares) << "cover " << c;
  }
  EXPECT_EQ(tied, u.tied);
  // Without slivers nothing is tied and cover c owns unknowns 2c, 2c + 1.
  const CoverUnknowns none = assign_cover_unknowns(m, 0.0);
  EXPECT_EQ(none.tied, 0u);
  for (std::size_t c = 0; c < m.cover_count(); ++c) EXPECT_EQ(none.unknown[c], 2 * static_cast<int>(c));
}

// Found by this suite and fixed: contact was lost where the face a vertex presses on belongs to
// elements that do not contain the vertex once it has sunk in a little, and the block above fell
// through with status "ok" (free fall conserves energy, so only the displacement check sees it).
// - A joint exactly along a row of mesh edges (y = 6·h·√3/2) through a body on the base: every
//   vertex on the joint is a mesh node, i.e. a corner of the element below; the upper block fell
//   0.195 m in 0.2 s (½·g·t² = 0.196 m).
// - Two bodies touching along y = 6·h·√3/2 + 1e-9·h (the lower body's top elements are slivers
//   2.5e-10 m thick): the same fall.
// Cause: a negative gap was accepted only inside the element owning the edge; a vertex sinking
// at a mesh node enters the triangle below the node. Now any element of that block sharing a
// mesh node with it counts (solver/contact/contact_detection.cpp, inside_near).
TEST(HardCases, JointAlongMeshEdgesHoldsTheBlockAbove) {
  const double h = 0.25, row6 = 6 * h * std::sqrt(3.0) / 2;
  for (int variant = 0; variant < 2; ++variant) {
    SceneDef s = contact_scene(h, 20);
    const char* name = variant == 0 ? "joint along a row of mesh edges"
                                    : "bodies touching 1e-9 h above a row of mesh nodes";
    if (variant == 0) {
      s.bodies = {box(0, 0, 4, 1), box(1, 1, 3, 2)};
      s.joints.push_back({0, {{0.9, row6}, {3.1, row6}}});
      s.measure_points = {{2, 1.9}, {2, 1.1}};
    } else {
      const double y = row6 + 1e-9 * h;
      s.bodies = {box(0, 0, 4, y), box(1.5, y, 2.5, y + 1)};
      s.measure_points = {{2, y + 0.9}, {2, y - 0.1}};
    }
    s.fixed_points = held_along(0.1, 3.9, 0.1);
    const Mesh m = pre::build_mesh(s, name);
    TimeStepper st(m, s, name);
    Monitor mon(m, s);
    const Outcome status = run_to(st, mon, 0.2);
    const auto top = st.view().state.measure[0].displacement();
    std::printf("%s: status %s; upper block moved (%.3e, %.3e) m; %zu contacts, %zu closed\n", name,
                test::text(status).c_str(), top[0], top[1], st.view().contacts.contacts().size(),
                st.view().contacts.totals().closed);
    EXPECT_PRED1(test::ended_ok, status) << name;
    expect_sound(st, mon, 1.0, name);
    EXPECT_LT(norm(top), 1e-4) << name << ": the upper block rests on the lower one, m";
    EXPECT_LT(max_point_speed(m, st), kRestSpeed) << name << ": at rest, m/s";
  }
}

// A mesh coarser than the blocks (the DDA code's 20 × 20 wall, bricks 1 × 0.5 m, h = 2 m, so
// 0.3·h = 0.6 m exceeds a brick's height): a brick corner closed against its neighbour's side,
// with a mesh node at the corner, was taken as 0.5 m deep below the neighbour's top face and the
// run cut Δt below its floor at t = 0.078 s. A closed vertex may be at most 0.35 of how far the
// other block reaches behind the edge (contact_detection.cpp).
TEST(HardCases, AWallMeshedCoarserThanItsBricksRuns) {
  const SceneDef s = reference::peer_wall(20, 20, true, 2.0);
  const Mesh m = pre::build_mesh(s, "coarse_wall");
  TimeStepper st(m, s, "coarse_wall");
  Monitor mon(m, s);
  const Outcome status = run_to(st, mon, 0.1);
  std::printf("20 x 20 wall at h = 2 m: status %s; penetration %.3e m; %zu cuts\n", test::text(status).c_str(),
              st.view().state.max_penetration, st.view().state.cuts);
  print_energy("energy", mon);
  EXPECT_PRED1(test::ended_ok, status);
  expect_sound(st, mon, 1.0, "20 x 20 wall at h = 2 m");
}

// ---- 6. Near-parallel joints ----------------------------------------------------------------

TEST(HardCases, NearParallelJointsAtHalfADegree) {
  // Two joints crossing a 2 m × 1 m body on the base: y = 1.5, and one h/50 above it at x = 0.9
  // rising at 0.5° (h/50 = 5 mm apart at the body's left face, 22 mm at its right face): a thin
  // tapering slab between two blocks.
  const double h = 0.25;
  SceneDef s = contact_scene(h, 20);
  s.bodies = {box(0, 0, 4, 1), box(1, 1, 3, 2)};
  const double rise = 2.2 * std::tan(0.5 * kPi / 180);
  s.joints.push_back({0, {{0.9, 1.5}, {3.1, 1.5}}});
  s.joints.push_back({0, {{0.9, 1.5 + h / 50}, {3.1, 1.5 + h / 50 + rise}}});
  s.fixed_points = held_along(0.1, 3.9, 0.1);
  s.measure_points = {{2, 1.25}, {2, 1.75}, {2.9, 1.5 + h / 50 / 2}};
  const Mesh m = pre::build_mesh(s, "parallel");
  TimeStepper st(m, s, "parallel");
  Monitor mon(m, s);
  const Outcome status = run_to(st, mon, 0.2);
  std::printf("near-parallel joints: %zu elements, %zu blocks; status %s; max speed %.3e m/s; "
              "penetration %.3e m; %zu cuts, %zu iterations\n",
              m.element_count(), m.block_count(), test::text(status).c_str(), max_speed(st),
              st.view().state.max_penetration, st.view().state.cuts, st.view().state.iterations);
  for (std::size_t i = 0; i < st.view().state.measure.size(); ++i) {
    const auto u = st.view().state.measure[i].displacement();
    std::printf("  point %zu moved (%.3e, %.3e) m\n", i, u[0], u[1]);
    EXPECT_LT(norm(u), 1e-4) << "point " << i << " rests where it was";
  }
  print_energy("energy", mon);
  EXPECT_EQ(m.block_count(), 4u) << "base, lower block, slab, upper block";
  EXPECT_PRED1(test::ended_ok, status);
  expect_sound(st, mon, h / 50, "near-parallel joints");  // the slab is 5 mm thin at its end
  EXPECT_LT(max_speed(st), kRestSpeed) << "at rest, m/s";
}

// ---- 7. A long run of a resting block -------------------------------------------------------

TEST(HardCases, RestingBlockStaysPutForTwoSeconds) {
  SceneDef s = contact_scene(0.25, 20);
  s.bodies = {box(0, 0, 4, 1), box(1.5, 1, 2.5, 2)};
  s.fixed_points = held_along(0.1, 3.9, 0.1);
  s.measure_points = {{2, 1.5}, {1.6, 1.9}};
  const Mesh m = pre::build_mesh(s, "long");
  TimeStepper st(m, s, "long");
  Monitor mon(m, s);
  double speed_max_late = 0;  // after the first 0.1 s
  std::vector<std::array<double, 2>> at;  // centre's displacement at 0.5, 1, 1.5, 2 s
  Outcome status;
  for (double t : {0.5, 1.0, 1.5, 2.0}) {
    status = st.run_until(t, [&](std::int64_t) {
      mon.sample(st);
      if (st.view().state.time > 0.1) speed_max_late = std::max(speed_max_late, max_speed(st));
    });
    if (!status.ok()) break;
    at.push_back(st.view().state.measure[0].displacement());
  }
  const auto corner = st.view().state.measure[1].displacement();
  std::printf("resting block, 2 s: status %s; centre moved (%.3e, %.3e) m at 0.5 s, (%.3e, %.3e) "
              "m at 2 s; corner (%.3e, %.3e) m; max speed after 0.1 s %.3e m/s; penetration "
              "%.3e m; %zu cuts, %zu iterations in %zu steps\n",
              test::text(status).c_str(), at.empty() ? 0 : at.front()[0], at.empty() ? 0 : at.front()[1],
              at.empty() ? 0 : at.back()[0], at.empty() ? 0 : at.back()[1], corner[0], corner[1],
              speed_max_late, st.view().state.max_penetration, st.view().state.cuts,
              st.view().state.iterations, mon.samples());
  print_energy("energy", mon);
  ASSERT_PRED1(test::ended_ok, status);
  expect_sound(st, mon, 1.0, "resting block");
  EXPECT_LT(speed_max_late, kRestSpeed) << "m/s";
  EXPECT_LT(norm(at.back()), 1e-4) << "no drift: the block stays where it was put";
  EXPECT_LT(norm(corner), 1e-4) << "nor does it rock";
  EXPECT_LT(std::hypot(at.back()[0] - at.front()[0], at.back()[1] - at.front()[1]), 1e-4)
      << "no drift from 0.5 s to 2 s";
  EXPECT_LE(st.view().state.cuts, 20u) << "a resting block needs (almost) no cuts";
}

}  // namespace
}  // namespace nmm::solve
