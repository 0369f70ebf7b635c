// nmm-joint-study OUTDIR [--data DIR] [--quick]
//
// The seed paper's validation, rerun with this solver (docs/joint-studies.md is made from it):
//  (a) data/single_joint.json: one joint loaded normally (σn from 0.5 to 10 MPa) and in direct
//      shear at σn = 5 MPa (10 % to 95 % of the strength), against the closed forms;
//  (b) the same joint under a shear load ramped past its strength, constant springs against the
//      joint laws: slip against load, and the load at which sliding sets in;
//  (c) data/tunnel.json, constant springs against the joint laws: the spread of the contacts'
//      normal and shear stiffness.
// Beside the seed's laws, each study runs the full model too: Barton–Bandis shear (mobilised
// roughness, peak, softening, dilation) on Bandis' closure with its load cycles (`reload`), and
// (a) adds the joint sheared under displacement control through and past the peak, and a load
// cycle of its closure.
// Writes CSV, Markdown tables and SVG plots into OUTDIR. Exit status 2 on bad input.
#include <CLI/CLI.hpp>

#include <filesystem>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/command_line.h"
#include "preprocess/cover_cutter.h"
#include "reference/direct_shear.h"
#include "studies/direct_shear_run.h"
#include "common/error.h"
#include "reference/joint_specimen.h"
#include "studies/joint_specimen_run.h"
#include "common/math_constants.h"
#include "common/number_format.h"
#include "common/scene.h"
#include "common/svg_plot.h"
#include "solver/stepping/time_stepper.h"
#include "common/vtk_writer.h"
#include "solver/discretisation/blas_kernels.h"

namespace {

using nmm::SceneDef;
using nmm::format_fixed;
using nmm::format_rough;
using nmm::format_signed;
using nmm::kPi;

// Closure and slip (m) of the single-joint scene under σn and τ (Pa) after `seconds`.
std::pair<double, double> joint_response(SceneDef s, const nmm::Mesh& m, double sigma, double tau,
                                         double seconds, nmm::Outcome* outcome) {
  nmm::reference::load_joint_specimen(s, sigma, tau);
  const nmm::studies::JointSpecimenResult r = nmm::studies::run_joint_specimen(m, s, seconds);
  *outcome = r.outcome;
  return {r.closure, r.slip};
}

void use_constant(SceneDef& s) {
  for (auto& js : s.joint_sets) {
    js.normal.model = nmm::NormalModel::constant;
    js.shear.model = nmm::ShearModel::constant;
  }
}

void use_joint_laws(SceneDef& s) {
  for (auto& js : s.joint_sets) {
    js.normal.model = nmm::NormalModel::bandis_barton;
    js.shear.model = nmm::ShearModel::hyperbolic;
  }
}

// The full model (docs/joint-studies.md): Bandis' closure with its later cycles (Kni2 = 3·Kni,
// Vm2 = 0.485·Vm: stated, not derived; the Barton–Bandis relations give the first cycle only) and
// Barton–Bandis shear on the joint set's JRC and JCS, φ taken as φr, ks = Ksi, for blocks of
// length `block_length` (m).
void use_full_model(SceneDef& s, double block_length) {
  for (auto& js : s.joint_sets) {
    js.normal.model = nmm::NormalModel::bandis_barton;
    js.normal.hysteresis = true;
    js.normal.reload_kni = 3 * js.normal.kni;
    js.normal.reload_vm = 0.485 * js.normal.vm;
    js.shear.model = nmm::ShearModel::barton_bandis;
    js.shear.ks = js.shear.ksi;
    js.shear.jrc = js.normal.jrc;
    js.shear.jcs = js.normal.jcs;
    js.shear.length = block_length;
  }
}

// The tables' numbers: a relative error as a signed percentage, everything else to four digits.
std::string pct(double v) { return format_signed(100 * v, 2) + " %"; }
std::string num(double v) { return format_rough(v, 4); }

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  CLI::App app{"nmm-joint-study: the seed paper's validation studies, rerun"};
  std::string out, data = "data";
  bool quick = false;
  app.add_option("outdir", out, "folder for CSV, Markdown and SVG")->required();
  app.add_option("--data", data, "folder holding single_joint.json and tunnel.json");
  app.add_flag("--quick", quick, "fewer points and steps (for tests)");
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-joint-study"); status >= 0)
    return status;
  try {
    nmm::prepare_output_folder(out);  // fails early on a bad folder
    std::ostringstream md;

    // ---- (a) the constitutive curves through the solver ------------------------------------
    const SceneDef joint = nmm::reference::joint_specimen_scene(data + "/single_joint.json");
    const nmm::Mesh jm = nmm::pre::build_mesh(joint, data + "/single_joint.json");
    const auto& law = joint.joint_sets[0];
    const double kni = law.normal.kni, vm = law.normal.vm, ksi = law.shear.ksi, rf = law.shear.rf;
    const double tanphi = std::tan(law.friction_deg * kPi / 180), sn = 5e6, tf = sn * tanphi;
    std::vector<double> sig = quick ? std::vector<double>{1e6, 5e6}
                                    : std::vector<double>{0.5e6, 1e6, 2e6, 3e6, 5e6, 7e6, 10e6};
    std::vector<double> frac = quick ? std::vector<double>{0.3, 0.9}
                                     : std::vector<double>{0.1, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95};
    std::ostringstream csv;  // written atomically at the end
    csv << "test,load_pa,solver_m,closed_form_m,error\n";
    md << "### (a) One joint through the solver against the closed forms\n\n"
       << "Kni = " << num(kni / 1e9) << " GPa/m, Vm = " << num(vm * 1e3) << " mm (from JRC "
       << law.normal.jrc << ", JCS " << law.normal.jcs / 1e6 << " MPa, σc " << law.normal.ucs / 1e6
       << " MPa); Ksi = " << num(ksi / 1e9) << " GPa/m, Rf = " << rf << ", φ = " << law.friction_deg
       << "°.\n\n| test | load | solver | closed form | error |\n|---|---:|---:|---:|---:|\n";
    nmm::PlotSeries ns_s{"solver", {}, {}, "#d62728", false, true}, ns_c{"Bandis–Barton", {}, {}, "#1f77b4"};
    for (double s : sig) {
      nmm::Outcome st;
      const double d = joint_response(joint, jm, s, 0, 0.3, &st).first;
      const double want = s * vm / (kni * vm + s);
      csv << "normal," << s << "," << d << "," << want << "," << (d - want) / want << "\n";
      md << "| normal | σn " << num(s / 1e6) << " MPa | δn " << num(d * 1e3) << " mm | "
         << num(want * 1e3) << " mm | " << pct((d - want) / want) << " |\n";
      ns_s.x.push_back(d * 1e3);
      ns_s.y.push_back(s / 1e6);
    }
    const double s_top = 1.2 * sig.back();  // the curve over the loaded range
    const double d_top = s_top * vm / (kni * vm + s_top);
    for (int i = 0; i <= 60; ++i) {
      const double d = d_top * i / 60;
      ns_c.x.push_back(d * 1e3);
      ns_c.y.push_back(kni * d / (1 - d / vm) / 1e6);
    }
    nmm::write_svg_plot({"Normal closure of one joint: solver against Bandis–Barton", "closure δn, mm",
                         "σn, MPa", false, false, {ns_c, ns_s}},
                        out + "/joint_normal.svg");
    nmm::PlotSeries ss_s{"solver", {}, {}, "#d62728", false, true}, ss_c{"hyperbola", {}, {}, "#1f77b4"};
    for (double f : frac) {
      nmm::Outcome st;
      const double u = joint_response(joint, jm, sn, f * tf, 0.4, &st).second;
      const double want = f * tf / (ksi * (1 - rf * f));
      csv << "shear," << f * tf << "," << u << "," << want << "," << (u - want) / want << "\n";
      md << "| shear, σn 5 MPa | τ " << format_fixed(100 * f, 0) << " % of τf | us " << num(u * 1e3)
         << " mm | " << num(want * 1e3) << " mm | " << pct((u - want) / want) << " |\n";
      ss_s.x.push_back(u * 1e3);
      ss_s.y.push_back(f * tf / 1e6);
    }
    for (int i = 0; i <= 60; ++i) {
      const double t = 0.97 * tf * i / 60;
      ss_c.x.push_back(t / (ksi * (1 - rf * t / tf)) * 1e3);
      ss_c.y.push_back(t / 1e6);
    }
    nmm::write_svg_plot({"Direct shear of one joint at σn = 5 MPa: solver against the hyperbola",
                         "shear displacement us, mm", "τ, MPa", false, false, {ss_c, ss_s}},
                        out + "/joint_shear.svg");

    // ---- (a) continued: the full model, sheared through the peak, and a closure cycle -------
    SceneDef full = joint;
    use_full_model(full, 2.0);
    const auto& fl = full.joint_sets[0];
    const nmm::reference::BartonJoint bj{fl.shear.jrc, fl.shear.jcs, fl.friction_deg,
                                         2.0 / 500 * std::pow(fl.shear.jrc / 2.0, 0.33)};
    const double dp = bj.peak_slip, tau_p = nmm::reference::barton_shear_stress(bj, sn, dp);
    md << "\n### (a) continued: direct shear through the peak, seed's law and full model\n\n"
       << "σn = 5 MPa held by the loads, the upper block pushed at "
       << format_fixed(dp / 0.34 * 1e3, 1) << " mm/s (δp/340 per 1 ms step). Full model: JRC "
       << fl.shear.jrc << ", JCS " << fl.shear.jcs / 1e6 << " MPa, φr " << fl.friction_deg
       << "°, block length 2 m: δp = " << num(dp * 1e3) << " mm, τp = " << num(tau_p / 1e6)
       << " MPa, d_mob at the peak " << num(0.5 * fl.shear.jrc * std::log10(fl.shear.jcs / sn))
       << "°; seed: τf = σn·tan φ = " << num(tf / 1e6) << " MPa.\n\n"
       << "| test | model | τ, solver | closed form | error | opening, solver | closed form |\n"
       << "|---|---|---:|---:|---:|---:|---:|\n";
    std::ostringstream dcsv;  // written atomically at the end
    dcsv << "model,slip_m,shear_stress_pa,normal_stress_pa,closure_m\n";
    nmm::PlotSeries dh{"seed's law (solver)", {}, {}, "#1f77b4", false, true},
        df{"full model (solver)", {}, {}, "#d62728", false, true},
        dhc{"hyperbola", {}, {}, "#1f77b4"}, dfc{"Barton's model", {}, {}, "#d62728"};
    const int shear_steps = quick ? 600 : 2000;  // to 1.8·δp or 5.9·δp
    const double closed0 = sn * vm / (kni * vm + sn);  // the closure under σn alone
    for (int model = 0; model < 2; ++model) {
      const SceneDef s = nmm::reference::direct_shear_scene(model ? fl : law, sn, dp / 0.34);
      const nmm::studies::DirectShearRun run =
          nmm::studies::run_direct_shear(nmm::pre::build_mesh(s, "direct shear"), s, shear_steps, 1);
      const char* name = model ? "full model" : "seed's law";
      for (std::size_t i = 0; i < run.samples.size(); i += 5) {  // every 0.1 mm
        const auto& r = run.samples[i];
        dcsv << (model ? "full" : "seed") << "," << r.slip << "," << r.shear_stress << ","
             << r.normal_stress << "," << r.closure << "\n";
        if (i % 25 != 0) continue;  // markers every 0.5 mm
        (model ? df : dh).x.push_back(r.slip * 1e3);
        (model ? df : dh).y.push_back(r.shear_stress / 1e6);
      }
      for (double d : {0.5e-3, 1e-3, 2e-3, dp, 10e-3, 20e-3, 40e-3}) {
        if (d > run.samples.back().slip) continue;
        std::size_t i = 1;
        while (i + 1 < run.samples.size() && run.samples[i].slip < d) ++i;
        const auto& a = run.samples[i - 1];
        const auto& b = run.samples[i];
        const double t = (d - a.slip) / (b.slip - a.slip);
        const double tau = a.shear_stress + t * (b.shear_stress - a.shear_stress);
        const double s_n = a.normal_stress + t * (b.normal_stress - a.normal_stress);
        const double open = closed0 - (a.closure + t * (b.closure - a.closure));
        const double tf_n = s_n * tanphi;  // over the overlap, as the solver's stresses
        const double want = model ? nmm::reference::barton_shear_stress(bj, s_n, d)
                                  : std::min(d / (1 / ksi + rf * d / tf_n), tf_n);
        const std::string test = "δ " + (d == dp ? num(d * 1e3) + " mm (δp)" : num(d * 1e3) + " mm");
        md << "| " << test << " | " << name << " | " << num(tau / 1e6) << " MPa | "
           << num(want / 1e6) << " MPa | " << pct(tau / want - 1) << " | " << num(open * 1e3)
           << " mm | "
           << (model ? num(nmm::reference::barton_opening(bj, sn, d) * 1e3) + " mm" : std::string("0 mm"))
           << " |\n";
      }
      if (!run.outcome.ok()) md << "\n(" << name << ": the run stopped: " << run.outcome.status() << ")\n";
    }
    const double d_end = std::max(dh.x.empty() ? 0.0 : dh.x.back(), df.x.empty() ? 0.0 : df.x.back()) * 1e-3;
    for (int k = 0; k <= 200; ++k) {
      const double d = d_end * k / 200;
      dhc.x.push_back(d * 1e3);
      dhc.y.push_back(std::min(d / (1 / ksi + rf * d / tf), tf) / 1e6);
      dfc.x.push_back(d * 1e3);
      dfc.y.push_back(nmm::reference::barton_shear_stress(bj, sn, d) / 1e6);
    }
    nmm::write_svg_plot({"Direct shear under displacement control, σn = 5 MPa: seed's law and full model",
                         "shear displacement, mm", "τ, MPa", false, false, {dhc, dfc, dh, df}},
                        out + "/direct_shear_models.svg");
    // A closure cycle: the seed's closure retraces its curve; the full model's stays closed.
    const std::vector<double> cyc = {5e6, 10e6, 5e6, 1e6, 0.5e6, 5e6, 10e6};
    md << "\n### (a) continued: a closure cycle, seed's law and full model\n\n"
       << "Full model: Kni2 = " << num(fl.normal.reload_kni / 1e9) << " GPa/m, Vm2 = "
       << num(fl.normal.reload_vm * 1e3) << " mm for the later cycles.\n\n"
       << "| test | closure, seed's law | closed form | closure, full model | closed form |\n"
       << "|---|---:|---:|---:|---:|\n";
    SceneDef seed_cycle = joint, full_cycle = full;
    nmm::reference::load_joint_specimen(seed_cycle, 10e6, 0);
    nmm::reference::load_joint_specimen(full_cycle, 10e6, 0);
    nmm::Outcome st1, st2;
    const std::vector<double> c_seed = nmm::studies::run_closure_cycles(jm, seed_cycle, cyc, &st1);
    const std::vector<double> c_full = nmm::studies::run_closure_cycles(jm, full_cycle, cyc, &st2);
    if (c_seed.size() == cyc.size() && c_full.size() == cyc.size()) {
      const double k2 = fl.normal.reload_kni, v2 = fl.normal.reload_vm;
      double smax = 0;
      for (std::size_t k = 0; k < cyc.size(); ++k) {
        const double s = cyc[k], seed_want = s * vm / (kni * vm + s);
        const bool virgin = s >= smax;
        smax = std::max(smax, s);
        const double d0 = smax * vm / (kni * vm + smax) - smax * v2 / (k2 * v2 + smax);
        const double full_want = virgin ? seed_want : d0 + s * v2 / (k2 * v2 + s);
        md << "| " << k + 1 << ": " << (k == 0 || cyc[k] > cyc[k - 1] ? "load to " : "unload to ")
           << num(s / 1e6) << " MPa | " << num(c_seed[k] * 1e3) << " mm | " << num(seed_want * 1e3)
           << " mm | " << num(c_full[k] * 1e3) << " mm | " << num(full_want * 1e3) << " mm |\n";
      }
    } else {
      md << "\n(the cycle runs stopped: " << st1.status() << " / " << st2.status() << ")\n";
    }

    // ---- (b) shear ramp past the strength: constant springs against the joint laws --------
    md << "\n### (b) Shear load ramped past the strength (σn = 5 MPa)\n\n"
       << "| τ/τf | slip, constant springs | slip, joint laws | slip, full model |\n|---:|---:|---:|---:|\n";
    SceneDef constant = joint;
    use_constant(constant);
    std::vector<double> ramp = quick ? std::vector<double>{0.5, 1.05}
                                     : std::vector<double>{0.2, 0.4, 0.6, 0.8, 0.9, 0.95, 0.98, 1.02, 1.05, 1.1};
    nmm::PlotSeries rc{"constant springs", {}, {}, "#1f77b4", true, true},
        rl{"joint laws", {}, {}, "#d62728", true, true}, rf_{"full model", {}, {}, "#2ca02c", true, true};
    std::ostringstream rcsv;  // written atomically at the end
    rcsv << "tau_over_tf,slip_constant_m,slip_joint_laws_m,slip_full_model_m\n";
    for (double f : ramp) {
      nmm::Outcome s1, s2;
      const double uc = joint_response(constant, jm, sn, f * tf, 0.3, &s1).second;
      const double ul = joint_response(joint, jm, sn, f * tf, 0.3, &s2).second;
      const double uf = joint_response(full, jm, sn, f * tf, 0.3, &s2).second;
      rcsv << f << "," << uc << "," << ul << "," << uf << "\n";
      md << "| " << f << " | " << num(uc * 1e3) << " mm | " << num(ul * 1e3) << " mm | "
         << num(uf * 1e3) << " mm |\n";
      rc.x.push_back(f), rc.y.push_back(std::max(uc, 1e-9) * 1e3);
      rl.x.push_back(f), rl.y.push_back(std::max(ul, 1e-9) * 1e3);
      rf_.x.push_back(f), rf_.y.push_back(std::max(uf, 1e-9) * 1e3);
    }
    nmm::write_svg_plot({"Slip after 0.3 s under a shear load, σn = 5 MPa", "τ / τf",
                         "slip, mm (log)", false, true, {rc, rl, rf_}},
                        out + "/shear_ramp.svg");

    // ---- (c) a jointed tunnel: the spread of contact stiffness -----------------------------
    md << "\n### (c) Tunnel in jointed rock: contact stiffness, constant against joint laws\n\n";
    SceneDef tun = nmm::reference::scene_with_joint_laws(data + "/tunnel.json");
    tun.solver.steps = quick ? 10 : 100;
    const nmm::Mesh tm = nmm::pre::build_mesh(tun, data + "/tunnel.json");
    std::ostringstream kcsv;  // written atomically at the end
    kcsv << "model,contact,closure_m,kn_n_per_m,ks_n_per_m,length_m\n";
    md << "| model | closed contacts | kn per contact, N/m (min – max) | kn per metre of joint, Pa/m "
          "(min – median – max) | ks per metre, Pa/m (min – max) |\n|---|---:|---:|---:|---:|\n";
    nmm::PlotSeries scatter{"contacts (joint laws)", {}, {}, "#d62728", false, true};
    const double kni_t = tun.joint_sets[0].normal.kni, vm_t = tun.joint_sets[0].normal.vm;
    const char* variants[] = {"constant springs", "joint laws", "full model"};
    for (int variant = 0; variant < 3; ++variant) {
      SceneDef s = tun;
      if (variant == 0) use_constant(s); else if (variant == 1) use_joint_laws(s); else use_full_model(s, 1.0);
      nmm::solve::TimeStepper st(tm, s, "tunnel");
      const std::string status =
          st.run_until(static_cast<double>(s.solver.steps) * s.solver.time_step, [](std::int64_t) {}).status();
      std::vector<double> kn_point, kn_m, ks_m;
      std::size_t i = 0;
      for (const auto& c : st.view().contacts.contacts()) {
        if (c.state == nmm::solve::ContactState::open) continue;
        kcsv << (variant == 2 ? "full_model" : variant ? "joint_laws" : "constant") << "," << i++ << "," << -c.gap << ","
             << c.kn_now << "," << c.ks_now << "," << c.length << "\n";
        kn_point.push_back(c.kn_now);
        const double L = std::max(c.length, 1e-12);
        kn_m.push_back(c.kn_now / L);
        if (c.ks_now > 0) ks_m.push_back(c.ks_now / L);
        if (variant == 1 && c.law < static_cast<int>(s.joint_sets.size())) {
          scatter.x.push_back(-c.gap * 1e3);
          scatter.y.push_back(c.kn_now / L / 1e9);
        }
      }
      for (auto* v : {&kn_point, &kn_m, &ks_m}) std::sort(v->begin(), v->end());
      if (kn_point.empty()) continue;
      md << "| " << variants[variant] << " (" << status.substr(0, 2)
         << ") | " << kn_point.size() << " | " << num(kn_point.front()) << " – "
         << num(kn_point.back()) << " | "
         << num(kn_m.front()) + " – " + num(kn_m[kn_m.size() / 2]) + " – " + num(kn_m.back())
         << " | "
         << (!ks_m.empty() ? num(ks_m.front()) + " – " + num(ks_m.back()) : std::string("–"))
         << " |\n";
    }
    nmm::PlotSeries curve{"Kni/(1 − δ/Vm)²", {}, {}, "#1f77b4"};
    double dmax = 0;
    for (double d : scatter.x) dmax = std::max(dmax, d * 1e-3);
    for (int k = 0; k <= 50; ++k) {
      const double d = std::min(1.05 * dmax, 0.95 * vm_t) * k / 50;
      curve.x.push_back(d * 1e3);
      curve.y.push_back(kni_t / ((1 - d / vm_t) * (1 - d / vm_t)) / 1e9);
    }
    md << "\n(Constant springs have one kn per metre of joint whatever the closure, and each "
          "contact's spring is kn times its tributary length; below kn per metre only where a "
          "contact touches with almost no force, inside the ±τ skin of the normal spring. With the "
          "joint laws each contact's normal stiffness per metre of joint follows its own closure, "
          "Kni/(1 − δ/Vm)², and its shear stiffness its own shear.)\n";
    nmm::write_svg_plot({"Tunnel, joint laws: normal stiffness of each closed contact against its closure",
                         "closure δ, mm", "kn per metre of joint, GPa/m", false, false, {curve, scatter}},
                        out + "/tunnel_stiffness.svg");
    nmm::write_file_atomically(out + "/joint_curves.csv", csv.str());
    nmm::write_file_atomically(out + "/shear_ramp.csv", rcsv.str());
    nmm::write_file_atomically(out + "/direct_shear_models.csv", dcsv.str());
    nmm::write_file_atomically(out + "/tunnel_stiffness.csv", kcsv.str());
    nmm::write_file_atomically(out + "/joint_studies_tables.md", md.str());
    std::cout << md.str();
  } catch (const nmm::InputError& e) {
    std::cerr << e.what() << "\n";
    return nmm::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "nmm-joint-study: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
