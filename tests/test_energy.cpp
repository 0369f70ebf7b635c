// The energy meter's path terms against closed forms (solver/output/energy.h, docs/energy.md):
//
// 1. Friction under a falling normal force. A stiff block on a held base (φ = 30°, a frictional
//    interface), pressed by a traction on its top and pushed sideways by a support moving at a
//    constant speed, slides at that speed. Over the last steps the traction falls linearly to
//    half. Friction's work over that part is ∫ N·tanφ ds, N the traction's resultant (the
//    contacts' normal forces sum to it), s the block's travel: with N linear in time and s
//    uniform, the trapezoid Σ ½(N_k + N_k+1)·tanφ·Δs_k is exact. Booking each step's slip at its
//    end force (the meter's old rule) misses ½ ΔN·tanφ·Δs a step: 6.7 % over five steps.
//
//        traction p(t) ↓↓↓↓↓
//          ┌──────────┐
//    v →  ▐│  block   │          1 m × 0.5 m, E 500 GPa
//          └──────────┘ φ 30°
//          ┌──────────┐
//          │   base   │ held
//          └──────────┘
//
//    The same block in the step its contacts close from open and slide (1b: its first step,
//    the traction put on at once on faces that touch with no force) and in the step they slide
//    on into and open (1c: the traction turned to a pull that lifts the block). A static step's
//    balance gives each contact −½ (c0 + c1)·d exactly (c0 its force at the start, c1 at the
//    end, d the step's motion), its springs keeping ½ N·closure + ½ T·s_el, so friction's share
//    is the trapezoid ½ (|T0| + |T1|)·slip: from no force, ½ tanφ·N1·Δs (the end force booked
//    twice that, and the compression cells' contacts that close and slide after a crack left
//    R at −500 J/m a step); into the opening, ½ tanφ·N0·Δs over the shear the spring lets go
//    of (nothing booked before).
//
// 2. A moving support pushing a pre-stressed body. A column under the in-situ stress σyy = −p
//    (σxx = 0: its free sides carry nothing) stands on a roller and is shortened by a roller
//    moving down on its top. Both rollers carry the in-situ reaction p·w locked in (integrators.cpp
//    support_terms) besides their springs, so the top pushes with F = w·(p + E'·δ/H) and does
//    W = ∫ F dδ = w·(p·δ + E'δ²/(2H)) on the column, which its strain energy takes
//    (U − U0 = the same, from σ = −p to −p − E'δ/H). Counting the springs alone leaves w·p·δ out:
//    here 4/5 of the work.
//
// 3. A contact found sunk with no force carried. Two stiff blocks touch on a joint (kn per unit
//    length); the upper one is moved into the lower one by p (1e-3·h deep at most: a new contact
//    may start there, as a vertex that chattered — released in one step, found sunk in the next —
//    does in the fracture matrix's compression cells), and the contact history is cleared. The
//    first step starts with the joint's springs holding S0 = ½ kn·w·p², from no work: heavy
//    blocks in a short static step (inertia term 2M/Δt² ≈ 100× the joint's kn·w) barely move,
//    so their springs still hold S ≈ S0 at the step's end and the meter must book what the
//    detection put in — S0 less ½ c0·d, the share of the push c0 = N0·cn the static step threw
//    away (contact_effect.cpp commit) — or R ≈ −S (unbooked, R = −0.98 S0).
//    The same blocks in a dynamic step, the upper one moving up fast enough to leave the lower
//    within the step: the joint ends open with no force, the implicit step (forces at its end)
//    neither spends nor keeps S0, K stays ½ m v0² and nothing is booked; the start force's
//    trapezoid ½ N0·Δg over the whole lift would put 4 S0 in `damped` (R = −4 S0).
//    And the converse: the upper block above the lower, moving down to close the joint within
//    the step — the implicit step applies the end force over the gap too (½ N1·g0 in `damped`).
//    Then, closed so under N1, the upper block sent up out of the joint in the next step: the
//    scheme's trapezoid takes N1 over the whole lift, the springs held ½ N1·c1 (`damped` gives
//    back ½ N1·(Δg − c1)).
//
// 4. A vertex that passes a corner onto the next edge. A stiff wedge, its apex down on a held
//    base, pressed by a traction on its top and pushed sideways 1 mm a step (frictionless: N
//    alone), crosses x = 1 m in its second step, where the base's top turns down by θ = 5°. The
//    third step starts with the apex closed on the sloping edge: its history goes on (kept per
//    vertex and block), its spring is loaded afresh from its gap to that edge, N0 = kn·L·closure0
//    with closure0 = δ·cosθ − ε·sinθ (δ its depth below the flat edge, ε how far past the
//    corner), along that edge's normal. The step started in balance with the old end force
//    N_prev on the flat edge, so the detection swapped c_prev for c0 at once and S_prev =
//    ½ N_prev·δ for S0 = ½ N0·closure0 with no work; the step's motion takes ½ (c0 − c_prev)·d
//    + S_prev − S0 (4.3 J/m here, against 1.8 J/m in the springs before it) into `damped`, or R
//    jumps by as much (contact_effect.cpp moved_on_work). The same wedge over a straight face
//    (θ = 0) passes from one element's edge to the next at x = 1 m: the same point, normal and
//    depth, the force goes on, and the rule books nothing (releasing the old spring alone would
//    book −½ c_prev·d + S_prev there).
//
// 5. A contact released between steps. The blocks of 3 after their static step, the joint closed
//    under N with its springs holding S1 = ½ N·closure + ½ |T·s_el| (energy.csv's springs at that
//    row); before the next step the upper block is lifted out of the search distance with its
//    contacts' history, as a vertex that slid past its edge's end onto a face that turns away is
//    found closed nowhere (the fracture matrix's compression cells, the steps after a crack). The
//    step starts with no spring there: S1 leaves S with no work, and the step's balance never
//    sees it. `damped` books it with ½ (0 − c_end)·d, or R = S1 (contact_effect.cpp
//    released_energy).
//    Lifted by half its closure instead, the joint is found closed again on the same edges, its
//    springs set afresh at about ½ N and ¼ S1, while the step starts in balance with the end
//    force it carries — as a re-cut that shortens a contact's tributary length sets its springs
//    at the same closure (the crack's mouth under a platen): `damped` books S1 − S0 with
//    ½ (c0 − c_prev)·d, or R = S1 − S0 (contact_effect.cpp reloaded_work).
//
// 6. A contact found open on its edge while its point stays closed elsewhere. Three blocks meet
//    at a point (a held base B, A and C side by side on it, A pressed down and into C); A is
//    moved back from C by twice the joint's closure between two steps. The A–C joint's contacts
//    are found open on the edges they ended closed on, with no force at rest; at the junction
//    the point's vertices still start closed on B, so commit does not release that one (a vertex
//    closed elsewhere may have handed its force on), and R kept its ½ (0 − c_end)·d + S_end
//    (contact_effect.cpp open_on_edge_work; the fracture matrix's biaxial compression, where
//    three blocks met at a crack junction: 2727 J/m in one step).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "common/math_constants.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "solver/contact/contact_history.h"
#include "solver/output/energy.h"
#include "solver/stepping/time_stepper.h"
#include "tests/ended_ok.h"

namespace nmm {
namespace {

// The meter as nmm-solve runs it (solve_run.cpp EnergyOutput), after every step.
struct MeteredRun {
  explicit MeteredRun(const nlohmann::json& doc, const std::string& name)
      : scene(scene_from_json(doc, name)), mesh(pre::build_mesh(scene, name)), st(mesh, scene, name),
        meter(st.view().model, &st.view().space) {
    meter.after_step(st.view().state, solve::energy_sources(st.view()), true);
  }
  SceneDef scene;
  Mesh mesh;
  solve::TimeStepper st;
  solve::EnergyMeter meter;
};

// m, the mean displacement component d of the loop vertices within 1e-9 m of the line
// coordinate[axis] = at in the mesh as cut.
double mean_displacement(const solve::RunState& s, int axis, double at, int d) {
  double sum = 0;
  int n = 0;
  for (std::size_t v = 0; 2 * v < s.loop_u.size(); ++v)
    if (std::abs(s.loop_xy[2 * v + axis] - s.loop_u[2 * v + axis] - at) < 1e-9) sum += s.loop_u[2 * v + d], ++n;
  return n ? sum / n : NAN;
}

// A stiff block on another (1 m × 0.5 m each, a joint of kn = ks = 1e13 Pa/m, φ 30°), the lower
// held, the upper pressed by p·table(t) on its top and pushed at v by its left side.
nlohmann::json pushed_block(double p, double v, double dt, int steps, const nlohmann::json& table) {
  return {{"name", "pushed-block"},
          {"plane", "strain"},
          {"materials", {{"stiff", {{"density", 2650}, {"young", 5e11}, {"poisson", 0.25}}}}},
          {"joint_sets", {{"joint", {{"friction_deg", 30}, {"normal", {{"model", "constant"}, {"kn", 1e13}}},
                                     {"shear", {{"model", "constant"}, {"ks", 1e13}}}}}}},
          {"interface_set", "joint"},
          {"mesh", {{"size", 0.25}}},
          {"bodies", {{{"material", "stiff"}, {"outer", {{0, 0}, {1, 0}, {1, 0.5}, {0, 0.5}}}},
                      {{"material", "stiff"}, {"outer", {{0, 0.5}, {1, 0.5}, {1, 1}, {0, 1}}}}}},
          {"supports", {{{"points", {{0, 0}, {1, 0}}}, {"fix", "xy"}},
                        {{"points", {{0, 0.5}, {0, 1}}}, {"fix", "x"}, {"velocity", {v, 0}}}}},
          {"tractions", {{{"points", {{1, 1}, {0, 1}}}, {"normal", -p}, {"shear", 0}, {"table", table}}}},
          {"solver", {{"time_step", dt}, {"steps", steps}, {"support_stiffness", 1e15}}}};
}

TEST(EnergyPaths, FrictionUnderAFallingNormalForceIsItsIntegral) {
  const double p = 1e6, w = 1, tan_phi = std::tan(30 * kPi / 180);
  const double dt = 1e-3, v = 0.2;  // s; m/s: 0.2 mm a step, 400× what the block's own shear strain gives back
  const int steady = 10, falling = 5;  // steps at p, then steps while p falls to p/2
  const double t_fall = steady * dt, t_end = (steady + falling) * dt;
  MeteredRun r(pushed_block(p, v, dt, steady + falling, {{0, 1}, {t_fall, 1}, {t_end, 0.5}}), "falling");
  double friction_fall = 0, closed = 0, end_force_rule = 0, x_prev = 0, n_prev = p * w;
  const Outcome o = r.st.run_until(t_end * (1 - 1e-9), [&](std::int64_t n) {
    const solve::RunView view = r.st.view();
    r.meter.after_step(view.state, solve::energy_sources(view), true);
    const double x = mean_displacement(view.state, 1, 1.0, 0);  // the block's travel (its top)
    const double t = view.state.time;
    const double normal = p * w * (t <= t_fall ? 1.0 : 1 - 0.5 * (t - t_fall) / (t_end - t_fall));
    if (n > steady) {
      closed += 0.5 * (n_prev + normal) * tan_phi * (x - x_prev);
      end_force_rule += normal * tan_phi * (x - x_prev);  // each step's slip at its end force (the old rule)
      const auto& rows = r.meter.rows();
      friction_fall += rows[rows.size() - 1].friction - rows[rows.size() - 2].friction;
    }
    x_prev = x, n_prev = normal;
  });
  ASSERT_PRED1(test::ended_ok, o);
  // The balance over the fall (the first steps' residual is the static steps' sudden start).
  const solve::EnergyRow& end = r.meter.rows().back();
  const solve::EnergyRow& before = r.meter.rows()[steady];
  const double work = end.load_work - before.load_work, residual = end.residual - before.residual;
  std::printf("falling normal force: travel %.6g m; friction while p falls %.6g J/m, ∫N·tanφ ds %.6g J/m "
              "(end-force rule %.6g); over the fall: work %.6g, residual %.4g J/m\n",
              x_prev, friction_fall, closed, end_force_rule, work, residual);
  EXPECT_NEAR(x_prev, v * t_end, 0.02 * v * t_end);  // the block slid with the support
  EXPECT_NEAR(friction_fall, closed, 0.003 * closed);
  EXPECT_GT(std::abs(end_force_rule - closed), 0.05 * closed);  // the old rule fails this check
  EXPECT_LT(std::abs(residual), 0.01 * work);
}

// N/m, the closed contacts' normal forces summed (contacts.csv's normal_force), at the state now.
double closed_normal_force(const solve::RunView& view) {
  double n = 0;
  for (const solve::Contact& c : view.contacts.contacts())
    if (c.state != solve::ContactState::open) n += c.normal_force;
  return n;
}

// m, the upper block's bottom face's mean x displacement less the base's top's (pushed_block's
// joint at y = 0.5): the slip, which the top's travel overstates by the blocks' shear strain.
double joint_slip(const Mesh& mesh, const solve::RunState& s) {
  double sum[2] = {0, 0};
  int n[2] = {0, 0};
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const int body = mesh.cover_body[static_cast<std::size_t>(mesh.element_covers[3 * e])];
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v) {
      const auto k = 2 * static_cast<std::size_t>(v);
      if (std::abs(s.loop_xy[k + 1] - s.loop_u[k + 1] - 0.5) < 1e-9) sum[body] += s.loop_u[k], ++n[body];
    }
  }
  return n[0] && n[1] ? sum[1] / n[1] - sum[0] / n[0] : NAN;
}

TEST(EnergyPaths, AContactThatClosesAndSlidesWithinAStepBooksHalfItsEndForce) {
  const double p = 1e6, w = 1, tan_phi = std::tan(30 * kPi / 180), dt = 1e-3, v = 0.2;
  MeteredRun r(pushed_block(p, v, dt, 1, {{0, 1}, {1, 1}}), "closing");
  double normal = 0, travel = 0, slip = 0;
  const Outcome o = r.st.run_until(dt * (1 - 1e-9), [&](std::int64_t) {
    const solve::RunView view = r.st.view();
    r.meter.after_step(view.state, solve::energy_sources(view), true);
    normal = closed_normal_force(view);
    travel = mean_displacement(view.state, 1, 1.0, 0);  // the block's top
    slip = joint_slip(r.mesh, view.state);
  });
  ASSERT_PRED1(test::ended_ok, o);
  const solve::EnergyRow& end = r.meter.rows().back();
  const double closed = 0.5 * tan_phi * normal * slip;  // J/m: the shear force from 0 to tanφ·N1
  std::printf("closing contacts: N1 %.6g N/m (p·w %.6g), travel %.6g m, slip %.6g m; friction %.6g J/m, "
              "½ tanφ·N1·Δs %.6g (end force %.6g); work %.6g, damped %.6g, residual %.4g J/m\n",
              normal, p * w, travel, slip, end.friction, closed, 2 * closed, end.load_work, end.damped, end.residual);
  EXPECT_NEAR(normal, p * w, 0.01 * p * w);     // the contacts carry the traction
  EXPECT_NEAR(travel, v * dt, 0.02 * v * dt);   // and the block slid with the support
  EXPECT_NEAR(end.friction, closed, 0.005 * closed);
  EXPECT_LT(std::abs(end.residual), 1e-3 * end.load_work);  // the step's balance closes
}

TEST(EnergyPaths, AContactThatSlidesIntoItsOpeningBooksHalfItsStartForce) {
  const double p = 1e6, w = 1, tan_phi = std::tan(30 * kPi / 180), dt = 1e-3, v = 0.2;
  const int steady = 5;  // steps pressed by p; the next one pulls the block off the base
  const double t_lift = steady * dt;
  MeteredRun r(pushed_block(p, v, dt, steady + 1, {{0, 1}, {t_lift, 1}, {t_lift + dt, -0.1}}), "opening");
  double normal = 0, x_prev = 0, x = 0, slip_prev = 0, slip = 0, friction_lift = 0, closed_after = 0;
  const Outcome o = r.st.run_until((steady + 1) * dt * (1 - 1e-9), [&](std::int64_t n) {
    const solve::RunView view = r.st.view();
    r.meter.after_step(view.state, solve::energy_sources(view), true);
    x_prev = x, slip_prev = slip;
    x = mean_displacement(view.state, 1, 1.0, 0);
    slip = joint_slip(r.mesh, view.state);
    if (n == steady) normal = closed_normal_force(view);
    if (n == steady + 1) {
      const auto& rows = r.meter.rows();
      friction_lift = rows[rows.size() - 1].friction - rows[rows.size() - 2].friction;
      closed_after = closed_normal_force(view);
    }
  });
  ASSERT_PRED1(test::ended_ok, o);
  const double closed = 0.5 * tan_phi * normal * (slip - slip_prev);  // J/m: the shear force from tanφ·N0 to 0
  std::printf("opening contacts: N0 %.6g N/m, closed after %.6g N/m, travel %.6g m, slip %.6g m; friction in the "
              "lift %.6g J/m, ½ tanφ·N0·Δs %.6g\n",
              normal, closed_after, x - x_prev, slip - slip_prev, friction_lift, closed);
  EXPECT_NEAR(normal, p * w, 0.01 * p * w);
  EXPECT_EQ(closed_after, 0.0);                     // the block left the base
  EXPECT_NEAR(x - x_prev, v * dt, 0.02 * v * dt);   // still pushed along
  EXPECT_NEAR(friction_lift, closed, 0.005 * closed);
}

TEST(EnergyPaths, AMovingSupportWorksWithItsLockedInReaction) {
  const double p = 10e6, E = 2e10, nu = 0.2, w = 1, H = 2;
  const double Ep = E / (1 - nu * nu);  // Pa, plane strain, free sides
  const double dt = 1e-3, steps = 20;
  const double shortening = 0.5 * p / Ep * H;  // m: the column's stress goes from −p to −1.5 p
  const double v = shortening / (steps * dt);
  const nlohmann::json doc = {
      {"name", "prestressed-column"},
      {"plane", "strain"},
      {"materials", {{"rock", {{"density", 2650}, {"young", E}, {"poisson", nu}}}}},
      {"mesh", {{"size", 0.25}}},
      {"bodies", {{{"material", "rock"}, {"outer", {{0, 0}, {w, 0}, {w, H}, {0, H}}}}}},
      {"supports", {{{"points", {{0, 0}, {w, 0}}}, {"fix", "y"}},
                    {{"points", {{0, H}, {w, H}}}, {"fix", "y"}, {"velocity", {0, -v}}}}},
      {"fixed_points", {{w / 2, 0}}},
      {"insitu_stress", {{"sxx", 0}, {"syy", -p}, {"sxy", 0}, {"y_ref", 0}, {"gradient", {0, 0, 0}}}},
      {"solver", {{"time_step", dt}, {"steps", steps}, {"static_mode", "equilibrium"}}}};
  MeteredRun r(doc, "column");
  const Outcome o = r.st.run_until(steps * dt * (1 - 1e-9), [&](std::int64_t) {
    const solve::RunView view = r.st.view();
    r.meter.after_step(view.state, solve::energy_sources(view), true);
  });
  ASSERT_PRED1(test::ended_ok, o);
  const solve::RunState& s = r.st.view().state;
  const double delta = mean_displacement(s, 1, 0.0, 1) - mean_displacement(s, 1, H, 1);  // m, shortening
  const double closed = w * (p * delta + Ep * delta * delta / (2 * H));  // ∫ F dδ
  const solve::EnergyRow& first = r.meter.rows().front();
  const solve::EnergyRow& end = r.meter.rows().back();
  std::printf("pre-stressed column: shortening %.6g m (support %.6g); load_work %.6g J/m, "
              "∫F dδ %.6g J/m (springs alone %.6g); ΔU %.6g, ΔS %.6g, residual %.4g J/m\n",
              delta, shortening, end.load_work, closed, w * Ep * delta * delta / (2 * H),
              end.strain - first.strain, end.springs - first.springs, end.residual);
  EXPECT_NEAR(delta, shortening, 0.02 * shortening);
  EXPECT_NEAR(end.strain - first.strain, closed, 0.005 * closed);  // the column took ∫F dδ
  // The support's springs hold what it pushed beyond the column: W = ∫F dδ + ΔS.
  EXPECT_NEAR(end.load_work, closed + (end.springs - first.springs), 0.005 * closed);
  EXPECT_LT(std::abs(end.residual), 0.005 * closed);
}

// Two stiff blocks w × 0.5 m on a joint of constant kn = ks, the lower held at its base: the scene
// of the two tests below (a static step, or a dynamic one with β = ½).
nlohmann::json stacked_blocks(const std::string& name, double kn, double w, double h, double dt, bool dynamic) {
  nlohmann::json solver = {{"time_step", dt}, {"steps", 1}};
  if (dynamic) solver["dynamic"] = true, solver["newmark_beta"] = 0.5;
  return {{"name", name},
          {"plane", "strain"},
          {"materials", {{"stiff", {{"density", 2650}, {"young", 5e11}, {"poisson", 0.25}}}}},
          {"joint_sets", {{"joint", {{"friction_deg", 30}, {"normal", {{"model", "constant"}, {"kn", kn}}},
                                     {"shear", {{"model", "constant"}, {"ks", kn}}}}}}},
          {"interface_set", "joint"},
          {"mesh", {{"size", h}}},
          {"bodies", {{{"material", "stiff"}, {"outer", {{0, 0}, {w, 0}, {w, 0.5}, {0, 0.5}}}},
                      {{"material", "stiff"}, {"outer", {{0, 0.5}, {w, 0.5}, {w, 1}, {0, 1}}}}}},
          {"supports", {{{"points", {{0, 0}, {w, 0}}}, {"fix", "xy"}}}},
          {"solver", solver}};
}

// The upper block (body 1) moved down by p — its covers' constant terms, nodes and loop
// vertices — and given the upward velocity v0 (m/s), with no contact force carried.
void sink_upper_block(solve::TimeStepper& st, const Mesh& mesh, double p, double v0, const std::string& name) {
  solve::RunState moved = st.view().state;
  const std::size_t m = moved.cover_u.size() / mesh.cover_count();
  for (std::size_t c = 0; c < mesh.cover_count(); ++c)
    if (mesh.cover_body[c] == 1) moved.cover_u[m * c + 1] -= p, moved.cover_xy[2 * c + 1] -= p, moved.velocity[m * c + 1] = v0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (mesh.cover_body[static_cast<std::size_t>(mesh.element_covers[3 * e])] != 1) continue;
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v)
      moved.loop_u[2 * static_cast<std::size_t>(v) + 1] -= p, moved.loop_xy[2 * static_cast<std::size_t>(v) + 1] -= p;
  }
  st.restore(moved, solve::save_contact_history(st.view().contacts), name);
}

// One step of Δt metered as nmm-solve meters it, from the state st holds now (at t = t0).
solve::EnergyMeter metered_step(solve::TimeStepper& st, double dt, double t0 = 0) {
  solve::EnergyMeter meter(st.view().model, &st.view().space);
  meter.after_step(st.view().state, solve::energy_sources(st.view()), true);
  const Outcome o = st.run_until(t0 + dt * (1 - 1e-9), [&](std::int64_t) {
    const solve::RunView view = st.view();
    meter.after_step(view.state, solve::energy_sources(view), true);
  });
  EXPECT_PRED1(test::ended_ok, o);
  return meter;
}

TEST(EnergyPaths, AContactFoundSunkWithNoForceBooksTheEnergyItsSpringsStartWith) {
  const double kn = 1e10, w = 1, p = 1e-4, h = 0.25;  // Pa/m, m, m (p < 1e-3·h: a new contact's depth)
  const double dt = 5e-5;  // s: 2M/Δt² = 1.06e12 N/m against kn·w = 1e10 N/m per block
  const SceneDef scene = scene_from_json(stacked_blocks("sunk-contact", kn, w, h, dt, false), "sunk");
  const Mesh mesh = pre::build_mesh(scene, "sunk");
  solve::TimeStepper st(mesh, scene, "sunk");
  sink_upper_block(st, mesh, p, 0.0, "sunk");
  const solve::EnergyMeter meter = metered_step(st, dt);
  ASSERT_GE(meter.rows().size(), 2u);
  const solve::EnergyRow& first = meter.rows().front();
  const solve::EnergyRow& end = meter.rows().back();
  const double s0 = 0.5 * kn * w * p * p;  // J/m, the joint's springs at the step's start
  std::printf("sunk contact: S0 = ½kn·w·p² = %.6g J/m; after the step S %.6g, U %.6g, damped %.6g, "
              "work %.6g, residual %.4g J/m\n",
              s0, end.springs, end.strain - first.strain, end.damped - first.damped, end.load_work, end.residual);
  EXPECT_GT(first.springs, -1e-12);
  EXPECT_LT(first.springs, 1e-9 * s0);  // no contact before the first step
  // The joint's springs still hold most of what they started with (a test that a missing
  // booking fails: R would be −S)...
  EXPECT_GT(end.springs, 0.9 * s0);
  EXPECT_LT(end.springs, 1.01 * s0);
  // ...and the balance closes: what remains is ½ (2M/Δt²) d², the static step's inertia term,
  // about 1 % of S0 here.
  EXPECT_LT(std::abs(end.residual), 0.02 * s0);
}

TEST(EnergyPaths, AContactFoundSunkThatOpensWithinTheStepBooksNothing) {
  // The blocks of the test above in a dynamic step (β = ½, no gravity), the upper one found p
  // deep in the lower and moving up at v0 with v0·Δt = 5p: the step ends with the joint open,
  // its end force 0, so the implicit step, which sees its forces at its end, neither spends nor
  // keeps the ½ N0·closure0 the detection put into the springs (S never held it): K stays
  // ½ m v0², S ends at 0, Q = ½ dᵀM (a1,prev + a1) − ΔK = 0 and the balance closes with nothing
  // booked. The start force's trapezoid ½ N0·Δg (Δg = 5p) less ½ N0·closure0 would book
  // ½ kn·w·p·(5p − p) = 4 S0 in `damped` (R = −4 S0).
  const double kn = 1e10, w = 1, p = 1e-4, h = 0.25;  // Pa/m, m, m
  const double dt = 5e-5, v0 = 5 * p / dt;            // s, m/s (10 m/s)
  const SceneDef scene = scene_from_json(stacked_blocks("sunk-contact-opens", kn, w, h, dt, true), "sunk-opens");
  const Mesh mesh = pre::build_mesh(scene, "sunk-opens");
  solve::TimeStepper st(mesh, scene, "sunk-opens");
  sink_upper_block(st, mesh, p, v0, "sunk-opens");
  const solve::EnergyMeter meter = metered_step(st, dt);
  ASSERT_GE(meter.rows().size(), 2u);
  const solve::EnergyRow& first = meter.rows().front();
  const solve::EnergyRow& end = meter.rows().back();
  const double s0 = 0.5 * kn * w * p * p;    // J/m, the joint's springs at the step's start
  const double k0 = 0.5 * 2650 * 0.5 * v0 * v0;  // J/m, ½ m v0² of the upper block
  std::printf("sunk contact that opens: S0 = %.6g, K0 = %.6g J/m; after the step K %.8g, S %.6g, damped %.6g, "
              "residual %.4g J/m\n",
              s0, k0, end.kinetic, end.springs, end.damped - first.damped, end.residual);
  EXPECT_NEAR(first.kinetic, k0, 1e-9 * k0);
  EXPECT_NEAR(end.kinetic, k0, 1e-6 * k0);     // no force at the step's end: a1 = 0
  EXPECT_LT(std::abs(end.springs), 1e-9 * s0);  // the joint ended open
  // Booked as a contact that stayed closed: damped 4 S0, R −4 S0.
  EXPECT_LT(std::abs(end.damped - first.damped), 0.02 * s0);
  EXPECT_LT(std::abs(end.residual), 0.02 * s0);
}

TEST(EnergyPaths, AContactThatClosesFromOpenWithinAStepBooksItsEndForceOverTheGap) {
  // The blocks of the tests above in a dynamic step (β = ½, no gravity), the upper one g0 above
  // the lower and moving down at v0 with v0·Δt = 2 g0: the joint closes within the step and ends
  // at closure c1 under N1 = kn·w·c1. Rigid blocks (E = 5e11 Pa, 1000× the joint over 0.5 m),
  // one degree of freedom: from rest of force (a0 = 0), a1 = N1/m up and d = v0·Δt − ¼Δt²·a1
  // down, so c1 = (v0·Δt − g0)/(1 + ¼Δt²·kn·w/m). The implicit step applies N1 over the whole
  // motion d = g0 + c1: K falls by N1·d, the scheme damps Q = ½ N1·d (energy.cpp (1)), the
  // spring keeps ½ N1·c1, and ½ N1·g0 — the end force over the gap the faces closed before they
  // touched — is the impact the step took out of the motion: `damped` books it, or R = ½ N1·g0.
  const double kn = 1e10, w = 1, g0 = 2e-5, h = 0.25;  // Pa/m, m, m, m
  const double dt = 5e-5, v0 = 2 * g0 / dt;            // s, m/s (0.8 m/s)
  const SceneDef scene = scene_from_json(stacked_blocks("closing-contact", kn, w, h, dt, true), "closing");
  const Mesh mesh = pre::build_mesh(scene, "closing");
  solve::TimeStepper st(mesh, scene, "closing");
  sink_upper_block(st, mesh, -g0, -v0, "closing");
  const solve::EnergyMeter meter = metered_step(st, dt);
  ASSERT_GE(meter.rows().size(), 2u);
  const solve::EnergyRow& first = meter.rows().front();
  const solve::EnergyRow& end = meter.rows().back();
  const double m = 2650 * w * 0.5;                                     // kg/m, the upper block
  const double c1 = (v0 * dt - g0) / (1 + 0.25 * dt * dt * kn * w / m);  // m
  const double n1 = kn * w * c1;                                       // N/m
  const double impact = 0.5 * n1 * g0;                                 // J/m
  std::printf("closing contact: c1 = %.6g m, N1 = %.6g N/m; S %.6g (½N1·c1 %.6g), K %.6g → %.6g, damped %.6g "
              "(½N1·(g0 + c1) + ½N1·g0 = %.6g), U %.4g, residual %.4g J/m (½N1·g0 = %.6g unbooked)\n",
              c1, n1, end.springs, 0.5 * n1 * c1, first.kinetic, end.kinetic, end.damped - first.damped,
              0.5 * n1 * (g0 + c1) + impact, end.strain - first.strain, end.residual, impact);
  EXPECT_LT(std::abs(first.springs), 1e-12);       // open at the start
  EXPECT_NEAR(end.springs, 0.5 * n1 * c1, 0.03 * 0.5 * n1 * c1);  // closed at c1 at the end
  EXPECT_NEAR(first.kinetic - end.kinetic, n1 * (g0 + c1), 0.03 * n1 * (g0 + c1));
  // The rigid one-degree model within 3 % (the blocks are elastic and the joint's contact points
  // share N1 unevenly); without the impact's share `damped` would be a third less.
  EXPECT_NEAR(end.damped - first.damped, 0.5 * n1 * (g0 + c1) + impact, 0.03 * (0.5 * n1 * (g0 + c1) + impact));
  EXPECT_LT(std::abs(end.residual), 1e-3 * impact);
}

// A wedge (apex down at x = 0.9985 m, y = 0.5 m; 0.5 m wide, frictionless joint of kn 1e10 Pa/m)
// pressed by 100 kPa on its top and pushed along x at 1 m/s by a roller on its left side, in
// static steps of 1 ms, on a held base whose top is flat to x = 1 m and falls by tanθ beyond.
nlohmann::json wedge_over_corner(double tan_theta) {
  return {{"name", "wedge-over-corner"},
          {"plane", "strain"},
          {"materials", {{"stiff", {{"density", 2650}, {"young", 5e11}, {"poisson", 0.25}}}}},
          {"joint_sets", {{"joint", {{"friction_deg", 0}, {"normal", {{"model", "constant"}, {"kn", 1e10}}},
                                     {"shear", {{"model", "constant"}, {"ks", 1e10}}}}}}},
          {"interface_set", "joint"},
          {"mesh", {{"size", 0.25}}},
          {"bodies", {{{"material", "stiff"}, {"outer", {{0, 0}, {2, 0}, {2, 0.5 - tan_theta}, {1, 0.5}, {0, 0.5}}}},
                      {{"material", "stiff"},
                       {"outer", {{0.9985, 0.5}, {1.2485, 0.75}, {1.2485, 1.0}, {0.7485, 1.0}, {0.7485, 0.75}}}}}},
          {"supports", {{{"points", {{0, 0}, {2, 0}}}, {"fix", "xy"}},
                        {{"points", {{0.7485, 0.75}, {0.7485, 1.0}}}, {"fix", "x"}, {"velocity", {1.0, 0}}}}},
          {"tractions", {{{"points", {{1.2485, 1.0}, {0.7485, 1.0}}}, {"normal", -1e5}, {"shear", 0}}}},
          {"solver", {{"time_step", 1e-3}, {"steps", 3}, {"support_stiffness", 1e15}}}};
}

// What the wedge's third step books, the apex's contact at the ends of steps 2 and 3 and the closed
// form of the moved-on rule from the apex's place.
struct CornerPass {
  int edge2 = -1, edge3 = -1;  // the apex's contact's edge at the end of steps 2 and 3
  double n_prev = 0, closure_prev = 0;  // N/m, m: its force and depth below the flat edge after step 2
  double n0 = 0, closure0 = 0;          // N/m, m: its start force and depth on the edge of step 3
  double rule = 0;                      // J/m, ½ (c0 − c_prev)·d + S_prev − S0
  double springs2 = 0, residual_step = 0, damped_step = 0;  // J/m: S after step 2; R and damped over step 3
};

CornerPass pass_corner(double theta_deg, const std::string& name) {
  const double theta = theta_deg * kPi / 180, kn = 1e10;
  MeteredRun r(wedge_over_corner(std::tan(theta)), name);
  CornerPass c;
  // The base's corner at (1, 0.5) m: the apex's place is taken from it (the base moves a little).
  std::size_t corner = r.mesh.loop_xy.size();
  for (std::size_t v = 0; 2 * v < r.mesh.loop_xy.size(); ++v)
    if (std::abs(r.mesh.loop_xy[2 * v] - 1) < 1e-9 && std::abs(r.mesh.loop_xy[2 * v + 1] - 0.5) < 1e-9) corner = v;
  EXPECT_LT(corner, r.mesh.loop_xy.size());
  if (corner == r.mesh.loop_xy.size()) return c;
  double x2 = 0, y2 = 0;
  const Outcome o = r.st.run_until(3e-3 * (1 - 1e-9), [&](std::int64_t n) {
    const solve::RunView view = r.st.view();
    r.meter.after_step(view.state, solve::energy_sources(view), true);
    const solve::Contact* apex = nullptr;
    for (const solve::Contact& k : view.contacts.contacts())
      if (k.state != solve::ContactState::open) apex = &k;
    if (!apex) return;
    const auto v = 2 * static_cast<std::size_t>(apex->at.vertex);
    const double x = view.state.loop_xy[v] - view.state.loop_xy[2 * corner];
    const double y = view.state.loop_xy[v + 1] - view.state.loop_xy[2 * corner + 1];
    if (n == 2) {
      c.edge2 = apex->at.edge;
      c.n_prev = apex->normal_force;
      c.closure_prev = -y;
      c.springs2 = r.meter.rows().back().springs;
      x2 = x, y2 = y;
    }
    if (n == 3) {
      c.edge3 = apex->at.edge;
      // Its depth below the sloping edge at the step's start, and the spring there (kn·L).
      c.closure0 = -(x2 * std::sin(theta) + y2 * std::cos(theta));
      c.n0 = kn * apex->length * c.closure0;
      const double dg_prev = y - y2;                                                  // on the flat edge's normal
      const double dg_new = (x - x2) * std::sin(theta) + (y - y2) * std::cos(theta);  // on the sloping one's
      c.rule = 0.5 * (c.n0 * dg_new - c.n_prev * dg_prev) + 0.5 * c.n_prev * c.closure_prev - 0.5 * c.n0 * c.closure0;
      const auto& rows = r.meter.rows();
      c.residual_step = rows.back().residual - rows[rows.size() - 2].residual;
      c.damped_step = rows.back().damped - rows[rows.size() - 2].damped;
    }
  });
  EXPECT_PRED1(test::ended_ok, o);
  std::printf("%s (θ %g°): apex on edge %d after step 2 (N %.6g N/m, δ %.6g m, S %.6g J/m), on edge %d in step 3 "
              "(N0 %.6g N/m, closure0 %.6g m); ½(c0 − c_prev)·d + S_prev − S0 = %.6g J/m; step 3: damped %.6g, "
              "residual %.4g J/m\n",
              name.c_str(), theta_deg, c.edge2, c.n_prev, c.closure_prev, c.springs2, c.edge3, c.n0, c.closure0, c.rule,
              c.damped_step, c.residual_step);
  return c;
}

TEST(EnergyPaths, AVertexThatPassesACornerReleasesItsOldSpringAndLoadsTheNext) {
  const CornerPass c = pass_corner(5, "corner");
  ASSERT_NE(c.edge2, c.edge3);  // the apex passed onto the next edge between the steps
  ASSERT_GT(c.closure0, 0);     // and starts closed on it
  // Most of the spring is let go at the corner: the sloping edge lies ε·sinθ above the apex's
  // depth (N0 a sixth of N_prev here), a jump the step's motion takes.
  EXPECT_LT(c.n0, 0.5 * c.n_prev);
  EXPECT_GT(c.rule, c.springs2);  // a term of the size of S (it is not round-off)
  // The balance closes with it booked (before the rule: R jumped by the whole of it, 4.28 J/m).
  EXPECT_LT(std::abs(c.residual_step), 0.01 * c.rule);
}

TEST(EnergyPaths, AVertexThatPassesOntoTheNextEdgeOfAStraightFaceKeepsItsForce) {
  const CornerPass c = pass_corner(0, "straight");
  ASSERT_NE(c.edge2, c.edge3);  // from one element's edge to the next
  ASSERT_GT(c.closure0, 0);
  // The same point, normal and depth: the force goes on, and the rule books next to nothing
  // (the old spring released alone, −½ c_prev·d + S_prev, would be 2.2 J/m here).
  EXPECT_NEAR(c.n0, c.n_prev, 1e-3 * c.n_prev);
  EXPECT_LT(std::abs(c.rule), 2e-3 * c.springs2);
  EXPECT_LT(std::abs(c.residual_step), 5e-3 * c.springs2);
}

TEST(EnergyPaths, AContactThatOpensWithinAStepGivesBackItsStartForceBeyondTheGap) {
  // The blocks of the tests above in two dynamic steps (β = ½, no gravity). The first closes the
  // joint as in the test above: the upper block, g0 above the lower and moving down at v0, ends
  // it at closure c1 under N1, the force the second step starts in balance with (M·a1,prev =
  // N1 up on the upper block). Then the upper block is sent up at v_up with v_up·Δt = 5·c1: the
  // joint opens within the second step and ends it with no force, so a1 = 0, K stays ½ m v_up²
  // and d = v_up·Δt = Δg. The time scheme's identity (energy.cpp (1)) takes the start force
  // linear over the whole lift, Q = ½ dᵀM (a1,prev + a1) − ΔK = ½ N1·Δg, but N1 pushed the faces
  // apart only until the gap opened: ½ N1·c1, what the springs held (S falls by it). `damped`
  // gives back ½ N1·(Δg − c1), or R = −½ N1·(Δg − c1) = −4 × the springs' ½ N1·c1.
  const double kn = 1e10, w = 1, g0 = 2e-5, h = 0.25;  // Pa/m, m, m, m
  const double dt = 5e-5, v0 = 2 * g0 / dt;            // s, m/s (0.8 m/s)
  const SceneDef scene = scene_from_json(stacked_blocks("opening-contact", kn, w, h, dt, true), "opening");
  const Mesh mesh = pre::build_mesh(scene, "opening");
  solve::TimeStepper st(mesh, scene, "opening");
  sink_upper_block(st, mesh, -g0, -v0, "opening");
  st.step(dt);  // the joint closes
  const double n1 = closed_normal_force(st.view());  // N/m
  const double m = 2650 * w * 0.5;                                       // kg/m, the upper block
  const double c1 = (v0 * dt - g0) / (1 + 0.25 * dt * dt * kn * w / m);  // m (the test above)
  const double v_up = 5 * c1 / dt;                                       // m/s
  sink_upper_block(st, mesh, 0.0, v_up, "opening");  // sent up, the contact and a1,prev kept
  solve::EnergyMeter meter(st.view().model, &st.view().space);
  meter.after_step(st.view().state, solve::energy_sources(st.view()), true);
  st.step(dt);  // the joint opens
  meter.after_step(st.view().state, solve::energy_sources(st.view()), true);
  ASSERT_EQ(meter.rows().size(), 2u);
  const solve::EnergyRow& first = meter.rows().front();
  const solve::EnergyRow& end = meter.rows().back();
  const double held = 0.5 * n1 * c1;               // J/m, the springs at the start
  const double beyond = 0.5 * n1 * (v_up * dt - c1);  // J/m, the trapezoid's share beyond the gap
  std::printf("opening contact: N1 = %.6g N/m, c1 = %.6g m; S %.6g → %.6g (½N1·c1 %.6g), K %.8g → %.8g, damped %.6g, "
              "U %.4g → %.4g, residual %.4g J/m (½N1·(Δg − c1) = %.6g)\n",
              n1, c1, first.springs, end.springs, held, first.kinetic, end.kinetic, end.damped - first.damped,
              first.strain, end.strain, end.residual, beyond);
  EXPECT_NEAR(n1, kn * w * c1, 0.03 * kn * w * c1);   // closed at c1 under N1 after the first step
  EXPECT_NEAR(first.springs, held, 0.03 * held);
  EXPECT_LT(std::abs(end.springs), 1e-3 * held);     // open at the second step's end (but a corner)
  EXPECT_NEAR(end.kinetic, first.kinetic, 1e-4 * first.kinetic);  // no force at its end: a1 = 0
  // What the motion lost is what the springs gave up (the trapezoid would book 5 × that).
  EXPECT_NEAR(end.damped - first.damped, held, 0.05 * held);
  EXPECT_LT(std::abs(end.residual), 0.05 * held);
}

// The blocks of 3 after their static step, the joint closed under N ≈ kn·w·p, then lifted by
// `lift` with the contacts' history (test 5): the meter's rows before and after the next step.
std::pair<solve::EnergyRow, solve::EnergyRow> step_after_lift(double lift, const std::string& name) {
  const double kn = 1e10, w = 1, p = 1e-4, h = 0.25;  // Pa/m, m, m
  const double dt = 5e-5;                             // s (the static step of 3)
  const SceneDef scene = scene_from_json(stacked_blocks(name, kn, w, h, dt, false), name);
  const Mesh mesh = pre::build_mesh(scene, name);
  solve::TimeStepper st(mesh, scene, name);
  sink_upper_block(st, mesh, p, 0.0, name);
  metered_step(st, dt);
  sink_upper_block(st, mesh, -lift, 0.0, name);
  const solve::EnergyMeter meter = metered_step(st, dt, dt);
  EXPECT_GE(meter.rows().size(), 2u);
  const solve::EnergyRow& first = meter.rows().front();
  const solve::EnergyRow& end = meter.rows().back();
  std::printf("%s: lifted %.3g m; S before the step %.6g J/m (½kn·w·p² = %.6g); after it S %.6g, U %.4g, "
              "damped %.6g, work %.4g, residual %.4g J/m\n",
              name.c_str(), lift, first.springs, 0.5 * kn * w * p * p, end.springs, end.strain - first.strain,
              end.damped - first.damped, end.load_work, end.residual);
  return {first, end};
}

TEST(EnergyPaths, AContactReleasedBetweenStepsBooksTheEnergyItsSpringsHeld) {
  // Lifted 0.1 m (0.4 h: out of the search distance): found closed nowhere.
  const auto [first, end] = step_after_lift(0.1, "released-contact");
  const double s0 = 0.5 * 1e10 * 1 * 1e-4 * 1e-4;  // J/m, ½kn·w·p²
  EXPECT_GT(first.springs, 0.9 * s0);              // the joint held its springs' energy...
  EXPECT_LT(std::abs(end.springs), 1e-4 * s0);     // ...and the step ends without them (the base's support springs)
  // What the step's motion releases against the lost end forces is small here (stiff heavy
  // blocks, no load, ½ (0 − c_end)·d = 0.34 J/m): `damped` is the springs' energy, and R would be
  // S1 without it (measured: +48.1 J/m; now −2e-6).
  EXPECT_NEAR(end.damped - first.damped, first.springs, 0.02 * first.springs);
  EXPECT_LT(std::abs(end.residual), 0.02 * first.springs);
}

TEST(EnergyPaths, AContactFoundOpenOnItsEdgeWithNoForceIsReleased) {
  // Lifted 2p: the detection finds the vertex on the same edge again, about p open, and the
  // constant-stiffness joint gives it no force at rest — released as one found closed nowhere
  // (contact_effect.cpp held_open). Before, a contact found open on its edge kept its end force
  // in the bookings (a Barton–Bandis joint that dilated apart is still held so): those the
  // detection found on their edges booked nothing, and R kept 25.2 J/m.
  const double p = 1e-4;
  const auto [first, end] = step_after_lift(2 * p, "open-on-its-edge");
  const double s0 = 0.5 * 1e10 * 1 * p * p;  // J/m
  EXPECT_GT(first.springs, 0.9 * s0);
  EXPECT_LT(std::abs(end.springs), 1e-4 * s0);
  EXPECT_NEAR(end.damped - first.damped, first.springs, 0.02 * first.springs);
  EXPECT_LT(std::abs(end.residual), 0.02 * first.springs);
}

TEST(EnergyPaths, AContactFoundCloserOnItsEdgeBooksItsSpringsSetAfresh) {
  // Lifted p/2: the detection finds each vertex on the same edge again, closed at about half its
  // closure, and sets its springs afresh there, N0 = kn·L·closure0 ≈ ½ N_prev, S0 ≈ ¼ S_prev,
  // while the step starts in balance with the end force N_prev it carries — as a re-cut that
  // shortens a contact's tributary length sets its springs at L_now/L_prev of their force and
  // energy at the same closure (uniaxial compression h 0.1 m, dynamic, the crack's mouth). The
  // springs gave up S_prev − S0 with no work, and the step's motion takes ½ (c0 − c_prev)·d:
  // `damped` books both (contact_effect.cpp reloaded_work), or R = S_prev − S0.
  const double p = 1e-4;
  const auto [first, end] = step_after_lift(0.5 * p, "closer-on-its-edge");
  const double s_prev = first.springs, s0 = 0.25 * s_prev;  // J/m
  EXPECT_GT(s_prev, 0.9 * 0.5 * 1e10 * 1 * p * p);         // closed under N ≈ kn·w·p
  EXPECT_NEAR(end.springs, s0, 0.05 * s0);                 // stiff heavy blocks barely move in the step
  EXPECT_NEAR(end.damped - first.damped, s_prev - s0, 0.02 * (s_prev - s0));
  EXPECT_LT(std::abs(end.residual), 0.02 * (s_prev - s0));
}

// Three blocks meeting at a point (test 6): a held base B (2 m × 0.5 m), and on it A (left) and C
// (right), 1 m × 0.5 m each, on a frictionless joint of kn = ks. A is pressed down by p_top on its
// top and right into C by p_side on its left side; C is held along its right side.
nlohmann::json blocks_at_a_junction(double kn, double p_top, double p_side, double dt, int steps) {
  return {{"name", "junction"},
          {"plane", "strain"},
          {"materials", {{"stiff", {{"density", 2650}, {"young", 5e11}, {"poisson", 0.25}}}}},
          {"joint_sets", {{"joint", {{"friction_deg", 0}, {"normal", {{"model", "constant"}, {"kn", kn}}},
                                     {"shear", {{"model", "constant"}, {"ks", kn}}}}}}},
          {"interface_set", "joint"},
          {"mesh", {{"size", 0.25}}},
          {"bodies", {{{"material", "stiff"}, {"outer", {{0, 0}, {2, 0}, {2, 0.5}, {0, 0.5}}}},
                      {{"material", "stiff"}, {"outer", {{0, 0.5}, {1, 0.5}, {1, 1}, {0, 1}}}},
                      {{"material", "stiff"}, {"outer", {{1, 0.5}, {2, 0.5}, {2, 1}, {1, 1}}}}}},
          {"supports", {{{"points", {{0, 0}, {2, 0}}}, {"fix", "xy"}}, {{"points", {{2, 0.5}, {2, 1}}}, {"fix", "x"}}}},
          {"tractions", {{{"points", {{1, 1}, {0, 1}}}, {"normal", -p_top}, {"shear", 0}},
                         {{"points", {{0, 1}, {0, 0.5}}}, {"normal", -p_side}, {"shear", 0}}}},
          {"solver", {{"time_step", dt}, {"steps", steps}, {"support_stiffness", 1e15}}}};
}

// J/m, the springs' energy ½ N·closure + ½ |T·s_el| of the closed contacts between blocks a and b.
double joint_springs(const solve::RunView& view, const Mesh& mesh, int a, int b) {
  double s = 0;
  for (const solve::Contact& c : view.contacts.contacts()) {
    const int ba = mesh.element_block[static_cast<std::size_t>(c.at.elem_a)];
    const int bb = mesh.element_block[static_cast<std::size_t>(c.at.elem_b)];
    if (c.state == solve::ContactState::open || !((ba == a && bb == b) || (ba == b && bb == a))) continue;
    s += 0.5 * std::max(0.0, c.normal_force * -c.gap) + 0.5 * std::abs(c.shear_force * c.shear_el);
  }
  return s;
}

// Body `body` moved by (dx, dy) m — its covers' constant terms, nodes and loop vertices — with its
// velocity and the contacts' history kept.
void shift_body(solve::TimeStepper& st, const Mesh& mesh, int body, double dx, double dy, const std::string& name) {
  solve::RunState moved = st.view().state;
  const std::size_t m = moved.cover_u.size() / mesh.cover_count();
  for (std::size_t c = 0; c < mesh.cover_count(); ++c)
    if (mesh.cover_body[c] == body)
      moved.cover_u[m * c] += dx, moved.cover_u[m * c + 1] += dy, moved.cover_xy[2 * c] += dx, moved.cover_xy[2 * c + 1] += dy;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (mesh.cover_body[static_cast<std::size_t>(mesh.element_covers[3 * e])] != body) continue;
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v) {
      const auto i = 2 * static_cast<std::size_t>(v);
      moved.loop_u[i] += dx, moved.loop_xy[i] += dx, moved.loop_u[i + 1] += dy, moved.loop_xy[i + 1] += dy;
    }
  }
  st.restore(moved, solve::save_contact_history(st.view().contacts), name);
}

TEST(EnergyPaths, AContactFoundOpenOnItsEdgeWhileItsPointStaysClosedElsewhereIsReleased) {
  // Test 6. Loaded in static steps until the joints hold still, the A–C joint (0.5 m) closed under
  // p_side: its springs hold S_AC = p_side²·H/(2 kn) = 25 J/m. A is then moved back from C by
  // 2 closure (with the contacts' history): the next step finds the joint's contacts open on the
  // edges they ended closed on, with no force at rest (a constant joint) — but at the junction
  // (1, 0.5) the point's vertices, A's corner and C's, still start closed on B. commit releases a
  // contact only where its vertex and the other face's vertex at its point start closed nowhere
  // (one closed somewhere may have handed its force on), so before this rule the junction's
  // contact kept its end force and springs out of every booking, and R held its share of S_AC, as
  // in the fracture matrix's biaxial compression at h 0.1 m (three blocks meeting where cracks
  // met: 2727 J/m in one step). `damped` books ½ (0 − c_end)·d + S_end for it
  // (contact_effect.cpp open_on_edge_work), as for those released.
  const double kn = 1e10, p_top = 1e6, p_side = 1e6, H = 0.5;  // Pa/m, Pa, Pa, m
  const double dt = 1e-3;  // s: 2M/Δt² = 2.65e9 N/m per block against kn·H = 5e9 N/m
  const int steps = 60;
  MeteredRun r(blocks_at_a_junction(kn, p_top, p_side, dt, steps + 1), "junction");
  const Outcome o = r.st.run_until(steps * dt * (1 - 1e-9), [](std::int64_t) {});
  ASSERT_PRED1(test::ended_ok, o);
  const double s_ac = joint_springs(r.st.view(), r.mesh, 1, 2);
  const double closure = p_side / kn;  // m
  shift_body(r.st, r.mesh, 1, -2 * closure, 0.0, "junction");
  // A short step (2M/Δt² = 6.6e12 N/m per block): A moves p_side·H/(2M/Δt²) ≈ 1e-7 m in it, and
  // the joint stays open.
  solve::EnergyMeter meter(r.st.view().model, &r.st.view().space);
  meter.after_step(r.st.view().state, solve::energy_sources(r.st.view()), true);
  r.st.step(dt / 50);
  meter.after_step(r.st.view().state, solve::energy_sources(r.st.view()), true);
  ASSERT_EQ(meter.rows().size(), 2u);
  const solve::EnergyRow& first = meter.rows().front();
  const solve::EnergyRow& end = meter.rows().back();
  const double s_after = joint_springs(r.st.view(), r.mesh, 1, 2);
  std::printf("junction: A–C springs %.6g J/m (p²H/(2kn) = %.6g); after the step %.6g; S %.6g → %.6g, damped %.6g, "
              "work %.6g, U %.4g, residual %.4g J/m\n",
              s_ac, p_side * p_side * H / (2 * kn), s_after, first.springs, end.springs, end.damped - first.damped,
              end.load_work - first.load_work, end.strain - first.strain, end.residual - first.residual);
  EXPECT_NEAR(s_ac, p_side * p_side * H / (2 * kn), 0.03 * s_ac);  // the joint was closed under p_side
  EXPECT_LT(s_after, 1e-6 * s_ac);                                 // and ends the step open
  // What the step releases is the joint's springs (the blocks barely move in it: ½ c_end·d is
  // small), all of it in `damped`...
  EXPECT_NEAR(end.damped - first.damped, s_ac, 0.03 * s_ac);
  // ...and the balance closes (without the rule R keeps the junction's share of S_AC).
  EXPECT_LT(std::abs(end.residual - first.residual), 0.01 * s_ac);
}

}  // namespace
}  // namespace nmm
