// nmm-study OUTDIR [--quick] [--data DIR] [--only CASE...]
//
// Accuracy against run time (docs/accuracy.md is made from it): reference problems with known
// answers, each run across settings, every run timed.
//  cantilever        L = 10, H = 1, tip load, static, against Timoshenko; mesh size.
//  sliding_block     2 m × 1 m block on a held 12 m base, gravity tilted 30°, φ = 20°, 1 s,
//                    against ½g(sin α − cos α tan φ)t²; time step, and penalty kn (as a multiple
//                    of E·1 m).
//  bandis_barton     data/single_joint.json (with ν = 0) at σn = 5 MPa against
//                    σn·Vm/(Kni·Vm + σn); mesh
//                    size, settling time, time step, contact model (constant springs or the
//                    joint law).
//  hyperbolic_shear  the same joint sheared at 60 % of its strength against the hyperbola;
//                    mesh size, settling time, contact model.
//  tight_joint       the same specimen with penalty springs standing for a tight joint: the
//                    shortening across it against the intact rock's σn·(1 m)/E; penalty kn.
//  kirsch            a circular opening excavated under K0 = 0.5 in-situ stress
//                    (reference/kirsch.h), the hoop stress along the wall against Kirsch
//                    (RMS over the wall points, relative to its peak); mesh size at cover order
//                    n = 0, 1, 2.
//  joint_wave        a 1 MPa half-sine pulse crossing one joint of constant springs (kn =
//                    1.37 GPa/m, τ = 2 ms; reference/wave_bar.h, data/joint_wave.json): the
//                    transmitted displacement history against the displacement-discontinuity
//                    model (RMS relative to its peak), the peak particle velocity shown; mesh
//                    size, time step. Also writes OUTDIR/joint_wave_tables.md (the read-off of
//                    joint_wave.h for τ = 2 and 0.5 ms at h = 0.5 and 0.25 m) and
//                    OUTDIR/joint_wave.svg (particle velocity before and after the joint, the
//                    runs against the closed form; docs/joint-studies.md).
//  bar_peak, bar_energy, bar_energy_brittle
//                    the cohesive tension bar (reference/cohesive_bar.h: 1 m, 0.19 m at its
//                    neck, σt 1 MPa, G_f 100 J/m²) pulled 1 µm a static step: its peak stress at
//                    the neck against σt, and the energy its cracks dissipate against G_f × 0.19 m
//                    (with softening) or against the elastic energy ½P²C the bar holds at its peak
//                    (without: `fracture_energy` left out, the crack lets go at once); mesh size,
//                    time step (the travel a step).
//  disc_first_crack  the Brazilian disc on rigid flats of the fracturing matrix
//                    (reference/rock_tests.h disc_flats, static): the load at its first crack
//                    against the rigid flat's D·σt·E(sinα)/cos2α (its peak is printed); mesh
//                    size, loading rate (steps to that load).
//  centre_crack_k1, edge_crack_k1
//                    K_I of a centre and of an edge crack in a plate under 1 MPa
//                    (reference/crack_plate.h, one static equilibrium step) against Tada; mesh
//                    size.
//  critical_load     the centre-cracked plate pulled by its top edge with K_Ic 1.5 MPa·√m: the
//                    mean stress at which its tips first grow against K_Ic/(√(πa)·F); mesh size,
//                    loading rate (the support's speed: the load a step).
// The cover order axis (docs/higher-order-covers.md): the cantilever and the Kirsch opening at
// n = 0, 1, 2 across mesh sizes, the sliding block (a joint case) at n = 0, 1, 2. A run the
// solver refuses at an order (exit-2 input error naming /solver/cover_order) is listed as not
// available, with the solver's reason, and the study goes on.
// Writes OUTDIR/accuracy_time.csv (case,setting,value,error,wall_seconds: one row per completed
// run), OUTDIR/accuracy_time.svg (error against wall time, log–log) and OUTDIR/accuracy_tables.md
// (a table per case, the runs that did not complete, and whether the costliest setting of each
// sweep beat the cheapest). wall_seconds covers building the mesh from the scene (cover cutting)
// and the run; parsing the scene file is left out; short runs are repeated and the fastest is
// kept (see timed_run). --quick runs a subset of the settings (the fracture cases' cheapest:
// about 30 s of its time). Exit status 2 on bad input.
#include <CLI/CLI.hpp>

#include <filesystem>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/command_line.h"
#include "preprocess/cover_cutter.h"
#include "common/error.h"
#include "reference/cantilever.h"
#include "reference/cohesive_bar.h"
#include "reference/crack_plate.h"
#include "reference/rock_tests.h"
#include "reference/joint_specimen.h"
#include "studies/fracture_readings.h"
#include "studies/joint_specimen_run.h"
#include "studies/joint_wave.h"
#include "studies/kirsch_opening.h"
#include "reference/sliding_block.h"
#include "common/scene.h"
#include "common/svg_plot.h"
#include "solver/fracture/crack_tip_readout.h"
#include "solver/fracture/crack_tips.h"
#include "solver/stepping/fracture_effect.h"
#include "solver/stepping/time_stepper.h"
#include "common/vtk_writer.h"
#include "common/stopwatch.h"
#include "common/math_constants.h"
#include "common/number_format.h"
#include "solver/discretisation/blas_kernels.h"

namespace {

using nmm::SceneDef;
using nmm::format_fixed;
using nmm::format_rough;
using nmm::format_scientific;
using nmm::format_signed;
using nmm::kPi;

// Four significant digits unless a column asks for another format.
std::string num(double v) { return format_rough(v, 4); }

// What one run gives: the computed value (or why it has none) and what it cost. A run is ok
// when it ended ok with a finite value; a setting the solver does not support (a cover order it
// refuses with an input error at /solver/cover_order) is not available, which is no failure of
// the study.
struct RunResult {
  nmm::Outcome run;         // how the run ended (common/outcome.h)
  bool available = true;    // false: the solver does not support this setting
  bool finite = true;       // the computed value is a finite number
  bool ok() const { return available && run.ok() && finite; }
  // Why not, when not ok.
  std::string reason() const {
    return !available || !run.ok() ? run.reason : finite ? "" : "result is not a finite number";
  }
  double computed = 0;     // the quantity compared with the closed form
  double mesh_seconds = 0;  // cover cutting
  double run_seconds = 0;   // TimeStepper construction and stepping
  int unknowns = 0;
  std::int64_t steps = 0;
  std::size_t cuts = 0, iterations = 0;
  // A case that measures its relative error itself (an RMS along a line) sets it here; others
  // leave it NaN and the error is |computed − exact| / |exact|.
  double own_error = std::nan("");
};

// One row of the study: a case, the setting varied and its value, and the outcome.
struct Row {
  std::string case_name, setting;  // setting: what the sweep it belongs to varies
  double value = 0;
  std::string value_text;                 // as shown in the tables
  double exact = 0;
  RunResult out;
  double error() const {
    return std::isfinite(out.own_error) ? out.own_error : std::abs(out.computed - exact) / std::abs(exact);
  }
  double wall() const { return out.mesh_seconds + out.run_seconds; }
};

// Builds the mesh and runs `body` on a fresh TimeStepper, timing both; RunError and a run that
// did not end ok become a failed result (InputError is bad input and goes up).
RunResult timed_run_once(const SceneDef& s, const std::string& name,
                         const std::function<nmm::Outcome(nmm::solve::TimeStepper&, RunResult&)>& body) {
  RunResult o;
  const nmm::Stopwatch t0;
  const nmm::Mesh m = nmm::pre::build_mesh(s, name);
  o.mesh_seconds = t0.seconds();
  const nmm::Stopwatch t1;
  try {
    std::unique_ptr<nmm::solve::TimeStepper> st;
    try {
      st = std::make_unique<nmm::solve::TimeStepper>(m, s, name);
    } catch (const nmm::InputError& e) {
      // What the solver does not support at this cover order yet (its input error's place is
      // /solver/cover_order): not available, not a failure of the study.
      if (s.solver.cover_order == 0 || e.where().rfind("/solver/cover_order", 0) != 0) throw;
      o.available = false;
      o.run.reason = "not available at this cover order: " + e.where() + ": " + e.message();
      o.run_seconds = t1.seconds();
      return o;
    }
    o.unknowns = st->view().space.unknowns();
    o.run = body(*st, o);
    o.cuts = st->view().state.cuts;
    o.iterations = st->view().state.iterations;
    o.finite = std::isfinite(o.computed);
  } catch (const nmm::RunError& e) {
    o.run = nmm::Outcome::stop(nmm::StopCode::failed, e.what(), 0);
  }
  o.run_seconds = t1.seconds();
  return o;
}

// Short runs are repeated and the fastest is kept: the runs are deterministic, so only the time
// differs, and the fastest is the one least disturbed by other work on the machine. A run is
// repeated until three runs and half a second have been spent on it (at most 25 runs); a run
// that took over 5 s, or did not complete, is kept as it is (at that length the machine's noise
// is the 10–20 % docs/accuracy.md states, and the fracture cases' longest runs would triple the
// study's time).
RunResult timed_run(const SceneDef& s, const std::string& name,
                  const std::function<nmm::Outcome(nmm::solve::TimeStepper&, RunResult&)>& body) {
  RunResult best = timed_run_once(s, name, body);
  if (!best.available) return best;  // nothing to time
  if (!best.ok() || best.mesh_seconds + best.run_seconds > 5) return best;
  double spent = best.mesh_seconds + best.run_seconds;
  for (int runs = 1; runs < 25 && (runs < 3 || spent < 0.5); ++runs) {
    const RunResult o = timed_run_once(s, name, body);
    spent += o.mesh_seconds + o.run_seconds;
    if (o.mesh_seconds + o.run_seconds < best.mesh_seconds + best.run_seconds) best = o;
  }
  return best;
}

nmm::Outcome run_steps(nmm::solve::TimeStepper& st, double t_end, RunResult& o) {
  return st.run_until(t_end, [&o](std::int64_t n) { o.steps = n; });
}

// ---- cantilever ----------------------------------------------------------------------------
// L = 10, H = 1, E = 10 GPa, ν = 0.25, plane stress, clamped by fixed points every h/2 along
// x = 0, P = 1e5 N down at (L, H/2), one static step (tests/test_solver_physics.cpp).
Row cantilever(double h, int order = 0) {
  const SceneDef s = nmm::reference::cantilever(h, order);
  Row r;
  r.case_name = "cantilever";
  // Cover order n ≥ 1 is its own sweep over h (docs/higher-order-covers.md).
  r.setting = order == 0 ? "mesh_size" : "mesh_size_n" + std::to_string(order);
  r.value = h;
  r.value_text =
      "h = " + format_rough(h, 6) + " m" + (order == 0 ? "" : ", n = " + std::to_string(order));
  r.exact = nmm::reference::timoshenko_tip_deflection();
  r.out = timed_run(s, "cantilever", [](nmm::solve::TimeStepper& st, RunResult& o) {
    st.step(1.0);
    o.steps = 1;
    o.computed = -st.view().state.measure[0].displacement()[1];
    return nmm::Outcome{};
  });
  return r;
}

// ---- sliding block -------------------------------------------------------------------------
// Flat 12 m × 1 m base held by fixed points every 0.25 m along y = 0.1, a 2 m × 1 m block on it,
// gravity tilted by 30°, φ = 20°, h = 0.5, ks = kn/2.5, 1 s (tests/test_contact.cpp).
Row sliding_block(const std::string& setting, double dt, double kn_over_e, int order = 0,
                  double contact_tolerance = nmm::SolverDef{}.contact_tolerance) {
  const double alpha_deg = 30, phi_deg = 20, t = 1.0;
  SceneDef s = nmm::reference::sliding_block_tilted(alpha_deg, phi_deg, 0.5, order, dt, kn_over_e);
  s.solver.contact_tolerance = contact_tolerance;
  Row r;
  r.case_name = "sliding_block";
  r.setting = setting;
  if (setting == "time_step") {
    r.value = dt;
  } else if (setting == "cover_order") {
    r.value = order;
  } else if (setting == "contact_tolerance") {
    r.value = contact_tolerance;
  } else {
    r.value = kn_over_e;
  }
  r.value_text = "Δt = " + num(dt) + " s, kn = " + num(kn_over_e) + "·E" +
                 (setting == "cover_order" ? ", n = " + std::to_string(order) : "") +
                 (setting == "contact_tolerance" ? ", τ = " + num(contact_tolerance) : "");
  r.exact = nmm::reference::sliding_distance(alpha_deg, phi_deg, t);
  r.out = timed_run(s, "sliding block", [t](nmm::solve::TimeStepper& st, RunResult& o) {
    const nmm::Outcome status = run_steps(st, t, o);
    o.computed = st.view().state.measure[0].displacement()[0];
    return status;
  });
  return r;
}

// ---- Kirsch opening (reference/kirsch.h, studies/kirsch_opening.h) ---------------------------------------------
// K0 = 0.5, b = 20a, the core excavated at the start of one static step. The error is the RMS
// of the hoop stress along the wall against Kirsch, relative to its peak (3p_y − p_x = 25 MPa):
// each wall element's stress field at the ends of its wall edges, the same read-off at every
// order (what the VTU frames show). The table's value column is σθ at the side wall (a, 0).
Row kirsch(double h, int order) {
  nmm::reference::KirschSetup k;
  k.h = h;
  k.k0 = 0.5;
  k.b_over_a = 20;
  k.order = order;
  Row r;
  r.case_name = "kirsch";
  r.setting = order == 0 ? "mesh_size" : "mesh_size_n" + std::to_string(order);
  r.value = h;
  r.value_text =
      "h = " + format_rough(h, 6) + " m" + (order == 0 ? "" : ", n = " + std::to_string(order));
  r.exact = nmm::reference::kirsch_hoop(k.k0 * nmm::reference::kKirschPressure, nmm::reference::kKirschPressure,
                                     nmm::reference::kKirschRadius, 0);
  const SceneDef s = nmm::reference::kirsch_scene(k);
  // The read-off needs the mesh: kept from the timed run (build_mesh is deterministic).
  r.out = timed_run(s, "kirsch", [&k](nmm::solve::TimeStepper& st, RunResult& o) {
    st.step(1.0);
    o.steps = 1;
    const nmm::studies::KirschWall w = nmm::studies::kirsch_wall(k, st.view().mesh, st);
    o.computed = w.side_wall_hoop;
    o.own_error = w.hoop_wall;
    return nmm::Outcome{};
  });
  return r;
}

// ---- single joint (data/single_joint.json) --------------------------------------------------
SceneDef single_joint_scene(const std::string& path) {
  SceneDef s = nmm::reference::joint_specimen_scene(path);
  // ν = 0: the closed forms assume the same stress all along the joint. With the file's ν = 0.25
  // the blocks' Poisson expansion, held at the base, makes the joint's stress uneven (5.018 MPa
  // at the middle, 4.963 MPa at the ends, h = 0.25) and the closure settled 0.15 % high at every
  // mesh size: a floor of the problem that no setting moves (docs/accuracy.md).
  for (nmm::MaterialDef& m : s.materials) m.poisson = 0;
  return s;
}

// The single-joint specimen loaded as everywhere else (reference/joint_specimen.h); closure or slip at the
// joint's middle.
RunResult joint_run(SceneDef s, double sigma, double tau, double seconds, bool want_slip) {
  nmm::reference::load_joint_specimen(s, sigma, tau);
  return timed_run(s, "single joint", [&](nmm::solve::TimeStepper& st, RunResult& o) {
    const nmm::Outcome status = run_steps(st, seconds, o);
    const auto a = st.view().state.measure[0].displacement();
    const auto b = st.view().state.measure[1].displacement();
    o.computed = want_slip ? a[0] - b[0] : b[1] - a[1];
    return status;
  });
}

// The joint's constant stiffnesses (the scene's kn, ks in Pa/m beside the law's parameters)
// instead of its laws: the setting "contact_model" (value 0 constant, 1 the joint laws).
std::string use_constant_springs(SceneDef& s) {
  auto& js = s.joint_sets[0];
  js.normal.model = nmm::NormalModel::constant;
  js.shear.model = nmm::ShearModel::constant;
  return "constant kn = " + num(js.normal.kn) + " Pa/m, ks = " + num(js.shear.ks) + " Pa/m, ";
}

Row bandis_barton(const SceneDef& joint, const std::string& setting, double h, double dt,
                  double seconds, bool joint_law = true) {
  const auto& law = joint.joint_sets[0].normal;
  const double sigma = 5e6;
  SceneDef s = joint;
  s.mesh_size = h;
  s.solver.time_step = dt;
  Row r;
  r.case_name = "bandis_barton";
  r.setting = setting;
  if (setting == "mesh_size") r.value = h;
  if (setting == "time_step") r.value = dt;
  if (setting == "settling_time") r.value = seconds;
  if (setting == "contact_model") r.value = joint_law ? 1 : 0;
  if (!joint_law) r.value_text = use_constant_springs(s);
  r.value_text +=
      "h = " + format_rough(h, 6) + " m, Δt = " + num(dt) + " s, " + num(seconds) + " s";
  r.exact = sigma * law.vm / (law.kni * law.vm + sigma);
  r.out = joint_run(s, sigma, 0, seconds, false);
  return r;
}

Row hyperbolic_shear(const SceneDef& joint, const std::string& setting, double h, double seconds,
                     bool joint_law = true) {
  const auto& js = joint.joint_sets[0];
  const double sigma = 5e6, tf = sigma * std::tan(js.friction_deg * kPi / 180), tau = 0.6 * tf;
  SceneDef s = joint;
  s.mesh_size = h;
  Row r;
  r.case_name = "hyperbolic_shear";
  r.setting = setting;
  r.value = setting == "mesh_size" ? h : setting == "contact_model" ? (joint_law ? 1 : 0) : seconds;
  if (!joint_law) r.value_text = use_constant_springs(s);
  r.value_text += "h = " + format_rough(h, 6) + " m, Δt = " + num(s.solver.time_step) + " s, " +
                  num(seconds) + " s";
  r.exact = tau / (js.shear.ksi * (1 - js.shear.rf * tau / tf));
  r.out = joint_run(s, sigma, tau, seconds, true);
  return r;
}

// ---- tight joint: what a penalty spring costs in accuracy ------------------------------------
// The single-joint specimen with DDA's point penalty kn = factor·E·(1 m) per contact point
// (model "penalty") standing for a tight joint
// (no closure of its own), σn = 5 MPa. The exact shortening between (1, 0.5) and (1, 1.5) is
// that of the intact rock, σn·(1 m)/E (uniform stress; constant-strain elements represent it
// exactly); the penalty springs add their own compliance, N/kn per contact, which a stiffer kn
// shrinks: this is the trade penalty contact makes.
Row tight_joint(const SceneDef& joint, double kn_over_e) {
  const double sigma = 5e6, e = joint.materials[0].young;
  SceneDef s = joint;
  auto& js = s.joint_sets[0];
  js.normal.model = nmm::NormalModel::penalty;
  js.shear.model = nmm::ShearModel::penalty;
  js.normal.kn = kn_over_e * e;
  js.shear.ks = js.normal.kn / 2.5;
  s.measure_points = {{1.0, 1.5}, {1.0, 0.5}};
  Row r;
  r.case_name = "tight_joint";
  r.setting = "penalty";
  r.value = kn_over_e;
  r.value_text = "kn = " + num(kn_over_e) + "·E, h = " + format_rough(s.mesh_size, 6) + " m, 0.3 s";
  r.exact = sigma * 1.0 / e;
  nmm::reference::load_joint_specimen(s, sigma, 0);
  r.out = timed_run(s, "tight joint", [&](nmm::solve::TimeStepper& st, RunResult& o) {
    const nmm::Outcome status = run_steps(st, 0.3, o);
    o.computed = st.view().state.measure[1].displacement()[1] - st.view().state.measure[0].displacement()[1];
    return status;
  });
  return r;
}

// ---- a wave crossing a joint (reference/wave_bar.h) -----------------------------------------
// The bar of data/joint_wave.json at mesh size h and time step Δt. The error is the RMS of the
// transmitted displacement history against the closed form, relative to its peak; the table's
// value column is the peak particle velocity after the joint.
Row joint_wave(const std::string& setting, double h, double dt) {
  nmm::reference::JointWaveSetup w;
  w.h = h;
  w.dt = dt;
  Row r;
  r.case_name = "joint_wave";
  r.setting = setting;
  r.value = setting == "mesh_size" ? h : dt;
  r.value_text = "h = " + format_rough(h, 6) + " m, Δt = " + num(dt) + " s";
  const nmm::reference::JointWaveClosedForm cf(w);
  r.exact = cf.transmitted_peak() / cf.impedance();
  const SceneDef s = nmm::reference::joint_wave_scene(w);
  r.out = timed_run(s, "joint wave", [&](nmm::solve::TimeStepper& st, RunResult& o) {
    const nmm::studies::JointWaveHistory hist =
        nmm::studies::run_joint_wave(st, s, [&o](std::int64_t n) { o.steps = n; });
    const nmm::studies::JointWaveErrors e = nmm::studies::joint_wave_errors(w, hist);
    o.computed = e.peak_velocity;
    o.own_error = e.after_rms;
    return hist.outcome;
  });
  return r;
}

// The wave against the closed form in detail, for τ = 2 ms (kn = 1.37 GPa/m) and 0.5 ms
// (5.48 GPa/m) at h = 0.5 and 0.25 m (--quick: 0.5 m), Δt = 25 µs: joint_wave_tables.md (the
// read-off of studies/joint_wave.h: RMS of the displacement histories, half-rise time and peak
// particle velocity after the joint) and joint_wave.svg (particle velocity before and after the
// joint at h = 0.5 m, the runs as dots against the closed form as lines).
void write_wave_outputs(const std::string& out, bool quick) {
  nmm::PlotSpec spec{"A half-sine pulse crossing a joint: nmm (dots) against the "
                     "displacement-discontinuity model (lines)",
                     "time, ms", "particle velocity, m/s", false, false, {}};
  std::ostringstream md;
  md << "<!-- made by nmm-study" << (quick ? " --quick" : "") << " -->\n\n"
     << "### joint_wave: the runs against the closed form\n\n"
     << "| run | incident alone, RMS | incident + reflected, RMS | transmitted, RMS | "
        "half-rise, ms (closed form) | half-rise error, ms | peak velocity, mm/s (closed form) | "
        "peak velocity error |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
  const std::vector<std::pair<double, std::string>> joints = {{1.37e9, "#1f77b4"},
                                                             {5.48e9, "#d62728"}};
  for (std::size_t j = 0; j < joints.size(); ++j)
    for (double h : quick ? std::vector<double>{0.5} : std::vector<double>{0.5, 0.25}) {
      nmm::reference::JointWaveSetup w;
      w.kn = joints[j].first;
      w.h = h;
      const nmm::reference::JointWaveClosedForm cf(w);
      const SceneDef s = nmm::reference::joint_wave_scene(w);
      const nmm::Mesh m = nmm::pre::build_mesh(s, "joint wave");
      const nmm::studies::JointWaveHistory hist = nmm::studies::run_joint_wave(m, s);
      if (!hist.outcome.ok()) throw nmm::RunError("joint wave: " + hist.outcome.status());
      const nmm::studies::JointWaveErrors e = nmm::studies::joint_wave_errors(w, hist);
      md << "| τ = " << format_rough(1e3 * cf.tau(), 2)
         << " ms (kn = " << format_rough(1e-9 * w.kn, 3) << " GPa/m), h = " << num(h)
         << " m, Δt = " << num(1e6 * w.dt) << " µs | " << format_fixed(100 * e.incident_rms, 2)
         << " % | " << format_fixed(100 * e.before_rms, 2) << " % | "
         << format_fixed(100 * e.after_rms, 2) << " % | "
         << format_fixed(1e3 * (e.half_rise_exact + e.half_rise), 3) << " ("
         << format_fixed(1e3 * e.half_rise_exact, 3) << ") | "
         << format_signed(1e3 * e.half_rise, 3) << " | " << format_fixed(1e3 * e.peak_velocity, 1)
         << " (" << format_fixed(1e3 * e.peak_velocity_exact, 1) << ") | "
         << format_signed(100 * e.peak_velocity_error(), 2) << " % |\n";
      if (h != 0.5) continue;
      const std::string tau = "τ = " + format_rough(1e3 * cf.tau(), 2) + " ms";
      const std::string kn = "kn = " + format_rough(1e-9 * w.kn, 3) + " GPa/m";
      auto add_point = [&](double x, const std::vector<double>& u, const std::string& where,
                           const std::string& colour) {
        nmm::PlotSeries run{"nmm, " + where + ", " + kn, {}, {}, colour, false, true};
        nmm::PlotSeries exact{"closed form, " + where + ", " + tau, {}, {}, colour, true, false};
        for (std::size_t k = 1; k < hist.time.size(); ++k) {
          const double t = 0.5 * (hist.time[k] + hist.time[k - 1]);
          if (t > cf.valid_until(x)) break;
          if (k % 2 == 0) {
            exact.x.push_back(1e3 * t);
            exact.y.push_back(cf.velocity(x, t));
          }
          if (k % 8 == 0) {  // every 8th step: the dots stay apart
            run.x.push_back(1e3 * t);
            run.y.push_back((u[k] - u[k - 1]) / (hist.time[k] - hist.time[k - 1]));
          }
        }
        spec.series.push_back(exact);
        spec.series.push_back(run);
      };
      // Before the joint: the incident wave, the same for both joints, and the reflection off
      // the softer one (drawn once).
      if (j == 0)
        add_point(w.before_x, hist.before, "x = " + num(w.before_x) + " m (incident, reflected)",
                  "#7f7f7f");
      add_point(w.after_x, hist.after, "x = " + num(w.after_x) + " m (transmitted)", joints[j].second);
    }
  nmm::write_svg_plot(spec, out + "/joint_wave.svg");
  nmm::write_file_atomically(out + "/joint_wave_tables.md", md.str());
}

// ---- fracture (docs/accuracy.md "Fracture") -------------------------------------------------
// Each fracture run builds its scene document (reference/), is timed as every run is, and is read
// by studies/fracture_readings.h; a run that reads two things (the bar's peak and its energy)
// gives a row for each, with the same wall time.

// The cohesive tension bar (reference/cohesive_bar.h) at mesh size h and time step dt (the support
// at 1 mm/s: dt·1 mm/s of travel a step), 0.26 mm of travel; with `softening` false the rock has no
// fracture energy. Rows: bar_peak (the peak stress at the neck, P/0.19 m, against σt) and
// bar_energy (what the cracks dissipated, energy.csv's fracture column, against G_f × 0.19 m) or,
// without softening, bar_energy_brittle (what the crack released, fracture + damped after the last
// intact step, against the elastic energy ½·P²·C the bar holds at P = σt·0.19 m).
std::vector<Row> tension_bar(const std::string& setting, double h, double dt, bool softening) {
  nlohmann::json doc = nmm::reference::cohesive_bar(h);
  if (!softening) doc["materials"]["rock"]["strength"].erase("fracture_energy");
  const double travel = 2.6e-4, v = 1e-3;  // m, m/s
  doc["solver"]["time_step"] = dt;
  doc["solver"]["steps"] = static_cast<long long>(std::llround(travel / v / dt));
  const SceneDef s = nmm::scene_from_json(doc, "tension bar");
  nmm::studies::FractureRun reading;
  const RunResult out = timed_run(s, "tension bar", [&](nmm::solve::TimeStepper& st, RunResult& o) {
    reading = nmm::studies::run_fracture(st, travel / v, 1, [&o](std::int64_t n) { o.steps = n; });
    o.computed = reading.peak;
    return reading.outcome;
  });
  const double neck = nmm::reference::kCohesiveBarNeck, st_ = nmm::reference::kCohesiveBarTensile;
  const double p_peak = st_ * neck, compliance = nmm::reference::cohesive_bar_compliance();
  const std::string text =
      "h = " + format_rough(h, 6) + " m, Δt = " + num(dt) + " s" + (softening ? "" : ", no softening");
  // The cracks and segments are the docs' read-off, not a table column (they are no setting).
  std::fprintf(stderr, "tension bar     %s: %d cracks, %d segments, fracture %.4g J/m, released %.4g J/m, "
               "stored %.4g J/m before the first crack (step %lld), residual %.3g J/m, %lld steps\n",
               text.c_str(), reading.cracks, reading.segments, reading.fracture, reading.released,
               reading.stored_intact, static_cast<long long>(reading.first_crack_step), reading.residual,
               static_cast<long long>(reading.steps));
  Row peak;
  peak.case_name = "bar_peak";
  peak.setting = setting;
  peak.value = setting == "time_step" ? dt : h;
  peak.value_text = text;
  peak.exact = st_;
  peak.out = out;
  peak.out.computed = reading.peak / neck;  // Pa at the neck
  Row energy = peak;
  energy.case_name = softening ? "bar_energy" : "bar_energy_brittle";
  energy.exact = softening ? nmm::reference::kCohesiveBarFractureEnergy * neck : 0.5 * p_peak * p_peak * compliance;
  energy.out.computed = softening ? reading.fracture : reading.released;
  if (!softening && reading.first_crack_step < 0) energy.out.computed = std::nan("");
  return {peak, energy};
}

// The Brazilian disc on rigid flats (reference/rock_tests.h disc_flats, static steps) at mesh size
// D/12, D/16, D/20 (size 0, 1, 2) and loading rate 0 (the closed-form load after 150 steps) or 1
// (75 steps): the load at its first crack — the top flat's reaction in the last intact state, as
// the fracturing matrix reads it (there from the mean stress) — against the rigid flat's
// D·σt·E(sinα)/cos2α, the load at which the centre's tension reaches σt. Not the peak: after
// the centre cracks the model's load goes on rising, to the run's end (1.2× the closed-form
// time) at D/12 and D/16, and to +44 … +92 % over hundreds of cracks in runs twice as long
// (docs/accuracy.md "Fracture").
Row disc_first_crack(const std::string& setting, int size, int rate) {
  nmm::reference::RockTestCase c;
  c.test = nmm::reference::RockTest::disc_flats;
  c.size = size;
  c.rate = rate;
  const nmm::reference::RockTestSpecimen sp = nmm::reference::rock_test(c);
  const SceneDef s = nmm::scene_from_json(sp.scene, "disc");
  const int steps_to_load = rate ? 75 : 150;
  Row r;
  r.case_name = "disc_first_crack";
  r.setting = setting;
  r.value = setting == "loading_rate" ? steps_to_load : sp.mesh_size;
  r.value_text = "h = D/" + std::to_string(size == 0 ? 12 : size == 1 ? 16 : 20) + ", the closed-form load in " +
                 std::to_string(steps_to_load) + " steps";
  r.exact = sp.closed_form;
  r.out = timed_run(s, "disc", [&](nmm::solve::TimeStepper& st, RunResult& o) {
    // The moving support is the last (the top flat).
    const nmm::studies::FractureRun f = nmm::studies::run_fracture(st, sp.end_time, sp.scene["supports"].size() - 1,
                                                                   [&o](std::int64_t n) { o.steps = n; });
    o.computed = f.first_crack_step >= 0 ? f.first_crack_load : std::nan("");
    // The peak and where it came are the docs' read-off.
    std::fprintf(stderr, "disc            %s: first crack at step %lld at %.4g MN/m (%+.2f %%), peak at step %lld, "
                 "%d cracks, %d segments\n",
                 r.value_text.c_str(), static_cast<long long>(f.first_crack_step), 1e-6 * f.first_crack_load,
                 100 * (f.first_crack_load / sp.closed_form - 1), static_cast<long long>(f.peak_step), f.cracks,
                 f.segments);
    return f.outcome;
  });
  return r;
}

// K_I of a crack in a plate under σ = 1 MPa (reference/crack_plate.h), one static equilibrium
// step: a centre crack 2a = 1 m in a plate 2 × 4 m (a/W 0.5, tips at lattice nodes) or an edge
// crack a = 0.3 m from the right side of a strip 1 × 4 m (a/b 0.3, tip at a node), against
// Tada's σ√(πa)·F. The value is the first tip's K_I (the centre crack's two are alike).
Row crack_k1(bool centre, double h) {
  const double a = centre ? 0.5 : 0.3, sigma = nmm::reference::kCrackPlateStress;
  const nlohmann::json doc = centre ? nmm::reference::crack_plate(-1, -2, 1, 2, {-a, 0}, {a, 0}, h)
                                    : nmm::reference::crack_plate(0, -2, 1, 2, {1, 0}, {1 - a, 0}, h);
  const SceneDef s = nmm::scene_from_json(doc, "crack plate");
  Row r;
  r.case_name = centre ? "centre_crack_k1" : "edge_crack_k1";
  r.setting = "mesh_size";
  r.value = h;
  r.value_text = "h = " + format_rough(h, 6) + " m (a/h = " + format_rough(a / h, 3) + ")";
  r.exact = sigma * std::sqrt(kPi * a) * (centre ? nmm::reference::tada_centre(a) : nmm::reference::tada_edge(a));
  r.out = timed_run(s, "crack plate", [](nmm::solve::TimeStepper& st, RunResult& o) {
    const nmm::Outcome status = run_steps(st, 1.0, o);
    nmm::solve::CrackTipFinder finder;
    const std::vector<nmm::solve::TipReading> tips = nmm::solve::read_crack_tips(st.view(), finder);
    o.computed = tips.empty() ? std::nan("") : tips.front().k1;
    return status;
  });
  return r;
}

// The critical load of the centre-cracked plate pulled by its top edge (reference/crack_plate.h
// pulled_crack_plate, K_Ic 1.5 MPa·√m) at mesh size h, the support at v (m/s) after a first step
// that brings the load to about 90 % of σ_c: the mean σyy of the step whose solution grows a tip
// against σ_c = K_Ic/(√(πa)·F). The load grows by about 0.5 % of σ_c a step per 2 µm/s.
Row critical_load(const std::string& setting, double h, double v) {
  const double k_ic = 1.5e6, a = 0.5;
  const SceneDef s = nmm::scene_from_json(nmm::reference::pulled_crack_plate(h, k_ic, v, 420e-6 / v), "pulled plate");
  Row r;
  r.case_name = "critical_load";
  r.setting = setting;
  r.value = setting == "loading_rate" ? v : h;
  r.value_text = "h = " + format_rough(h, 6) + " m, v = " + num(1e6 * v) + " µm/s";
  r.exact = k_ic / (std::sqrt(kPi * a) * nmm::reference::tada_centre(a));
  r.out = timed_run(s, "pulled plate", [](nmm::solve::TimeStepper& st, RunResult& o) {
    const nmm::studies::GrowthLoad g =
        nmm::studies::run_until_growth(st, 60.0, [&o](std::int64_t n) { o.steps = n; });
    o.computed = g.grew ? g.load : std::nan("");
    return g.outcome;
  });
  return r;
}

// ---- outputs -------------------------------------------------------------------------------
std::string csv_text(const std::vector<Row>& rows) {
  std::ostringstream os;
  os << "case,setting,value,error,wall_seconds\n";
  for (const Row& r : rows)
    if (r.out.ok())
      os << r.case_name << "," << r.setting << "," << format_rough(r.value, 6) << ","
         << format_scientific(r.error(), 7) << "," << format_fixed(r.wall(), 4) << "\n";
  return os.str();
}

std::string unit_of(const std::string& case_name) {
  return case_name == "cantilever" ? "tip deflection, mm"
         : case_name == "bar_peak"      ? "peak stress at the neck, MPa"
         : case_name == "bar_energy"    ? "dissipated, J/m"
         : case_name == "bar_energy_brittle" ? "released, J/m"
         : case_name == "disc_first_crack" ? "load at the first crack, MN/m"
         : case_name == "centre_crack_k1" ? "K_I of the centre crack, MPa·√m"
         : case_name == "edge_crack_k1" ? "K_I of the edge crack, MPa·√m"
         : case_name == "critical_load" ? "mean stress when a tip grows, MPa"
         : case_name == "kirsch"        ? "σθ at the side wall, MPa"
         : case_name == "sliding_block" ? "slide, m"
         : case_name == "bandis_barton" ? "closure, mm"
         : case_name == "tight_joint"   ? "shortening, mm"
         : case_name == "joint_wave"    ? "peak particle velocity after the joint, mm/s"
                                        : "slip, mm";
}

double shown(const std::string& case_name, double v) {
  if (case_name == "kirsch" || case_name == "bar_peak" || case_name == "disc_first_crack" ||
      case_name == "centre_crack_k1" || case_name == "edge_crack_k1" || case_name == "critical_load")
    return 1e-6 * v;  // MPa, MN/m, MPa·√m
  if (case_name == "bar_energy" || case_name == "bar_energy_brittle") return v;  // J/m
  return case_name == "sliding_block" ? v : 1e3 * v;  // m for the slide, mm otherwise
}

// "costliest run (…) is more accurate than the cheapest (…): e1 % against e2 %."
std::string judge(const Row& dear, const Row& cheap) {
  const bool same = std::abs(dear.error() - cheap.error()) <= 1e-3 * cheap.error();
  const bool better = !same && dear.error() < cheap.error();
  return "costliest run (" + dear.value_text + ", " + format_fixed(dear.wall(), 3) + " s) " +
         (same     ? "is **not** more accurate (equal within 0.1 % of the error)"
          : better ? "**is** more accurate"
                   : "is **not** more accurate") +
         " than the cheapest (" + cheap.value_text + ", " + format_fixed(cheap.wall(), 3) +
         " s): " + format_fixed(100 * dear.error(), 3) + " % against " +
         format_fixed(100 * cheap.error(), 3) + " %.";
}

std::string tables_text(const std::vector<Row>& rows, bool quick) {
  std::ostringstream md;
  md << "<!-- made by nmm-study" << (quick ? " --quick" : "") << " -->\n";
  std::vector<std::string> cases;
  for (const Row& r : rows)
    if (std::find(cases.begin(), cases.end(), r.case_name) == cases.end()) cases.push_back(r.case_name);
  for (const std::string& c : cases) {
    const Row* first = nullptr;
    for (const Row& r : rows)
      if (r.case_name == c) {
        first = &r;
        break;
      }
    md << "\n### " << c << "\n\nexact: " << format_rough(shown(c, first->exact), 6) << " ("
       << unit_of(c) << ")\n\n"
       << "| setting | run | " << unit_of(c) << " | "
       << (c == "kirsch"       ? "hoop RMS error along the wall"
           : c == "joint_wave" ? "transmitted u RMS error"
                               : "signed error")
       << " | wall s (mesh + run) | unknowns | steps | step cuts | contact solves |\n"
       << "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows) {
      if (r.case_name != c) continue;
      md << "| " << r.setting << " | " << r.value_text << " | ";
      if (r.out.ok() && std::isfinite(r.out.own_error))
        md << format_rough(shown(c, r.out.computed), 6) << " | "
           << format_fixed(100 * r.out.own_error, 3) << " %";
      else if (r.out.ok())
        md << format_rough(shown(c, r.out.computed), 6) << " | "
           << format_signed(100 * (r.out.computed - r.exact) / std::abs(r.exact), 3) << " %";
      else
        md << (!r.out.available ? "not available" : "did not complete") << " | –";
      md << " | " << format_fixed(r.wall(), 4) << " (" << format_fixed(r.out.mesh_seconds, 4)
         << " + " << format_fixed(r.out.run_seconds, 4) << ") | " << r.out.unknowns << " | "
         << r.out.steps << " | " << r.out.cuts << " | " << r.out.iterations << " |\n";
    }
    // Per sweep: does the costliest run beat the cheapest?
    std::vector<std::string> sweeps;
    for (const Row& r : rows)
      if (r.case_name == c && std::find(sweeps.begin(), sweeps.end(), r.setting) == sweeps.end())
        sweeps.push_back(r.setting);
    md << "\n";
    for (const std::string& sw : sweeps) {
      const Row *cheap = nullptr, *dear = nullptr;
      for (const Row& r : rows) {
        if (r.case_name != c || r.setting != sw || !r.out.ok()) continue;
        if (!cheap || r.wall() < cheap->wall()) cheap = &r;
        if (!dear || r.wall() > dear->wall()) dear = &r;
      }
      if (!cheap || cheap == dear) continue;
      if (dear->wall() < 1.25 * cheap->wall()) {
        // Within timing noise (docs/accuracy.md): which run is "costliest" would be chance.
        const Row* best = cheap;
        for (const Row& r : rows)
          if (r.case_name == c && r.setting == sw && r.out.ok() && r.error() < best->error()) best = &r;
        md << "- " << sw << ": the cost does not depend on it (" << format_fixed(cheap->wall(), 3)
           << "–" << format_fixed(dear->wall(), 3)
           << " s, within timing noise); the most accurate run is " << best->value_text << ": "
           << format_fixed(100 * best->error(), 3) << " %.\n";
        continue;
      }
      md << "- " << sw << ": " << judge(*dear, *cheap) << "\n";
    }
    const Row *cheap = nullptr, *dear = nullptr;
    for (const Row& r : rows) {
      if (r.case_name != c || !r.out.ok()) continue;
      if (!cheap || r.wall() < cheap->wall()) cheap = &r;
      if (!dear || r.wall() > dear->wall()) dear = &r;
    }
    if (cheap && dear && cheap != dear && dear->wall() >= 1.25 * cheap->wall())
      md << "- the whole case: " << judge(*dear, *cheap) << "\n";
  }
  std::ostringstream failed;
  for (const Row& r : rows)
    if (!r.out.ok())
      failed << "| " << r.case_name << " | " << r.value_text << " | " << format_fixed(r.wall(), 3)
             << " | " << r.out.reason() << " |\n";
  md << "\n### Runs that did not complete (not in the CSV or the picture)\n\n";
  if (failed.str().empty())
    md << "None.\n";
  else
    md << "| case | run | wall s | reason |\n|---|---|---:|---|\n" << failed.str();
  return md.str();
}

void write_plot(const std::vector<Row>& rows, const std::string& path) {
  // One curve per case and swept setting, its points joined in the order the settings were run
  // (cheapest first). The sweeps whose error does not move (the closure against Δt, the slip
  // against settling time past a few steps) stay in the tables and the CSV only.
  const std::vector<std::pair<std::pair<std::string, std::string>, std::string>> curves = {
      {{"cantilever", "mesh_size"}, "cantilever h"},
      {{"cantilever", "mesh_size_n1"}, "cantilever h, n = 1"},
      {{"cantilever", "mesh_size_n2"}, "cantilever h, n = 2"},
      {{"kirsch", "mesh_size"}, "Kirsch h"},
      {{"kirsch", "mesh_size_n1"}, "Kirsch h, n = 1"},
      {{"kirsch", "mesh_size_n2"}, "Kirsch h, n = 2"},
      {{"sliding_block", "cover_order"}, "block n = 0, 1, 2"},
      {{"sliding_block", "time_step"}, "block Δt"},
      {{"sliding_block", "penalty"}, "block kn"},
      {{"sliding_block", "contact_tolerance"}, "block τ"},
      {{"bandis_barton", "mesh_size"}, "closure h"},
      {{"bandis_barton", "settling_time"}, "closure t"},
      {{"hyperbolic_shear", "mesh_size"}, "shear h"},
      {{"bandis_barton", "contact_model"}, "closure model"},
      {{"hyperbolic_shear", "contact_model"}, "shear model"},
      {{"tight_joint", "penalty"}, "tight joint kn"},
      {{"joint_wave", "mesh_size"}, "joint wave h"},
      {{"joint_wave", "time_step"}, "joint wave Δt"},
      {{"bar_peak", "mesh_size"}, "bar peak h"},
      {{"bar_energy", "mesh_size"}, "bar G_f h"},
      {{"bar_energy", "time_step"}, "bar G_f Δt"},
      {{"bar_energy_brittle", "mesh_size_brittle"}, "bar no softening h"},
      {{"disc_first_crack", "mesh_size"}, "disc h"},
      {{"disc_first_crack", "loading_rate"}, "disc rate"},
      {{"centre_crack_k1", "mesh_size"}, "centre crack K_I h"},
      {{"edge_crack_k1", "mesh_size"}, "edge crack K_I h"},
      {{"critical_load", "mesh_size"}, "critical load h"},
      {{"critical_load", "loading_rate"}, "critical load rate"},
  };
  const std::vector<std::string> colours = {"#1f77b4", "#393b79", "#6b6ecf", "#d62728", "#ff7f0e",
                                            "#2ca02c", "#9467bd", "#17becf", "#8c564b", "#e377c2",
                                            "#7f7f7f", "#bcbd22", "#e7ba52", "#ad494a",
                                            "#637939", "#000000", "#c51b8a", "#fd8d3c",
                                            "#843c39", "#31a354", "#756bb1", "#e6550d", "#3182bd",
                                            "#636363", "#a55194", "#8ca252", "#de9ed6", "#6baed6"};
  nmm::PlotSpec spec{"Error against wall time, cheapest setting first",
                     "wall time, s (log)", "relative error (log)", true, true, {}};
  for (std::size_t i = 0; i < curves.size(); ++i) {
    nmm::PlotSeries ser{curves[i].second, {}, {}, colours[i % colours.size()], true, true};
    for (const Row& r : rows)
      if (r.out.ok() && r.case_name == curves[i].first.first && r.setting == curves[i].first.second) {
        ser.x.push_back(r.wall());
        ser.y.push_back(r.error());
      }
    if (!ser.x.empty()) spec.series.push_back(ser);
  }
  nmm::write_svg_plot(spec, path);
}

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  CLI::App app{"nmm-study: accuracy against run time on reference problems with known answers"};
  std::string out, data = "data";
  bool quick = false;
  app.add_option("outdir", out, "folder for accuracy_time.csv, accuracy_time.svg, accuracy_tables.md")
      ->required();
  app.add_option("--data", data, "folder holding single_joint.json");
  app.add_flag("--quick", quick, "fewer settings (under a minute, for tests)");
  std::vector<std::string> only;
  app.add_option("--only", only,
                 "run only these cases (cantilever, kirsch, sliding_block, bandis_barton, "
                 "hyperbolic_shear, tight_joint, joint_wave, bar_peak, bar_energy, bar_energy_brittle, disc_first_crack, "
                 "centre_crack_k1, edge_crack_k1, critical_load; the bar's three come from the same runs)");
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-study"); status >= 0)
    return status;
  try {
    nmm::prepare_output_folder(out);  // fails early on a bad folder
    const SceneDef joint = single_joint_scene(data + "/single_joint.json");

    std::vector<Row> rows;
    auto add = [&rows](Row r) {
      std::fprintf(
          stderr, "%-16s %-14s %-52s %s  %.3f s\n", r.case_name.c_str(), r.setting.c_str(),
          r.value_text.c_str(),
          r.out.ok() ? (format_fixed(100 * r.error(), 4) + " %").c_str() : r.out.reason().c_str(),
          r.wall());
      rows.push_back(std::move(r));
    };

    auto want = [&only](const char* c) {
      return only.empty() || std::find(only.begin(), only.end(), c) != only.end();
    };
    using V = std::vector<double>;
    if (want("cantilever")) {
      for (double h : quick ? V{0.5, 0.25, 0.125} : V{0.5, 0.25, 0.125, 0.0625, 0.03125, 0.015625})
        add(cantilever(h));
      // The order axis: linear (n = 1) and quadratic (n = 2) cover functions on the same meshes.
      for (double h : quick ? V{0.5, 0.25} : V{0.5, 0.25, 0.125, 0.0625}) add(cantilever(h, 1));
      for (double h : quick ? V{0.5} : V{0.5, 0.25, 0.125}) add(cantilever(h, 2));
    }
    if (want("kirsch")) {
      for (double h : quick ? V{0.4} : V{0.4, 0.2, 0.1}) add(kirsch(h, 0));
      for (double h : quick ? V{0.4} : V{0.4, 0.3, 0.2, 0.15}) add(kirsch(h, 1));
      for (double h : quick ? V{} : V{0.4, 0.3}) add(kirsch(h, 2));
    }

    if (want("sliding_block")) {
      for (double dt : quick ? V{4e-3, 2e-3, 1e-3} : V{8e-3, 4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4})
        add(sliding_block("time_step", dt, 20));
      for (double k : quick ? V{10, 20, 50} : V{5, 10, 20, 50, 100})
        add(sliding_block("penalty", 1e-3, k));
      // The order axis on a joint case: the same block at n = 0, 1, 2 (h = 0.5, Δt = 1 ms).
      for (int n : quick ? std::vector<int>{1} : std::vector<int>{0, 1, 2})
        add(sliding_block("cover_order", 1e-3, 20, n));
      // The contact solve's force tolerance (solver.contact_tolerance; docs/contact.md).
      for (double tau : quick ? V{1e-3, 1e-5} : V{1e-3, 1e-4, 1e-5, 1e-6, 1e-8, 1e-10})
        add(sliding_block("contact_tolerance", 1e-3, 20, 0, tau));
    }

    const double dt0 = joint.solver.time_step, h0 = joint.mesh_size;
    if (want("bandis_barton")) {
      for (double h : quick ? V{0.5, 0.25} : V{0.5, 0.25, 0.125, 0.0625})
        add(bandis_barton(joint, "mesh_size", h, dt0, 0.3));
      for (double t : quick ? V{0.002, 0.01, 0.1} : V{0.001, 0.002, 0.003, 0.005, 0.01, 0.03, 0.1, 0.3})
        add(bandis_barton(joint, "settling_time", h0, dt0, t));
      for (double dt : quick ? V{} : V{4e-3, 2e-3, 1e-3, 5e-4})
        add(bandis_barton(joint, "time_step", h0, dt, 0.3));
    }
    if (want("hyperbolic_shear")) {
      for (double h : quick ? V{0.5, 0.25, 0.125} : V{0.5, 0.25, 0.125, 0.0625})
        add(hyperbolic_shear(joint, "mesh_size", h, 0.4));
      for (double t : quick ? V{} : V{0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.4})
        add(hyperbolic_shear(joint, "settling_time", h0, t));
    }

    // The seed paper's point: constant springs against the joint laws, on the same mesh.
    for (bool law : {false, true}) {
      if (want("bandis_barton")) add(bandis_barton(joint, "contact_model", h0, dt0, 0.3, law));
      if (want("hyperbolic_shear")) add(hyperbolic_shear(joint, "contact_model", h0, 0.4, law));
    }
    if (want("tight_joint"))
      for (double k : quick ? V{1, 20, 1000} : V{1, 5, 20, 100, 1000, 1e4}) add(tight_joint(joint, k));

    if (want("joint_wave")) {
      for (double h : quick ? V{0.5} : V{1, 0.5, 0.25}) add(joint_wave("mesh_size", h, 2.5e-5));
      for (double dt : quick ? V{} : V{1e-4, 5e-5, 2.5e-5, 1.25e-5}) add(joint_wave("time_step", 0.5, dt));
      write_wave_outputs(out, quick);
    }

    // Fracture (docs/accuracy.md "Fracture"). The bar's runs give its three cases at once.
    if (want("bar_peak") || want("bar_energy") || want("bar_energy_brittle")) {
      auto add_bar = [&](const std::vector<Row>& rs) {
        for (const Row& r : rs)
          if (want(r.case_name.c_str())) add(r);
      };
      for (double h : quick ? V{0.1} : V{0.1, 0.05, 0.025}) add_bar(tension_bar("mesh_size", h, 1e-3, true));
      for (double h : quick ? V{0.1} : V{0.1, 0.05, 0.025}) add_bar(tension_bar("mesh_size_brittle", h, 1e-3, false));
      for (double dt : quick ? V{} : V{2e-3, 1e-3, 5e-4}) add_bar(tension_bar("time_step", 0.1, dt, true));
    }
    if (want("disc_first_crack")) {
      for (int size : quick ? std::vector<int>{0} : std::vector<int>{0, 1, 2}) add(disc_first_crack("mesh_size", size, 0));
      for (int rate : quick ? std::vector<int>{} : std::vector<int>{1, 0}) add(disc_first_crack("loading_rate", 1, rate));
    }
    if (want("centre_crack_k1"))
      for (double h : quick ? V{0.1, 0.05} : V{0.1, 0.05, 0.025}) add(crack_k1(true, h));
    if (want("edge_crack_k1"))
      for (double h : quick ? V{} : V{0.05, 0.025, 0.0125}) add(crack_k1(false, h));
    if (want("critical_load")) {
      for (double h : quick ? V{0.05} : V{0.1, 0.05, 0.025}) add(critical_load("mesh_size", h, 2e-6));
      for (double v : quick ? V{} : V{8e-6, 4e-6, 2e-6}) add(critical_load("loading_rate", 0.05, v));
    }

    nmm::write_file_atomically(out + "/accuracy_time.csv", csv_text(rows));
    write_plot(rows, out + "/accuracy_time.svg");
    const std::string md = tables_text(rows, quick);
    nmm::write_file_atomically(out + "/accuracy_tables.md", md);
    std::cout << md;
  } catch (const nmm::InputError& e) {
    std::cerr << e.what() << "\n";
    return nmm::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "nmm-study: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
