// A joint set's laws as a scene gives them: see joint_laws.h. The Barton–Bandis relations that
// derive a closure curve from JRC, JCS and UCS, and Bandis' scale corrections, are written out
// where they are applied below (docs/physics.md §4).
#include "common/scene/joint_laws.h"

#include <cmath>
#include <string>

#include "common/scene/json_reader.h"

namespace nmm {

NormalLawDef read_normal_law(const JsonReader& r) {
  r.expect_object();
  NormalLawDef law;
  // constant: kn in Pa/m (per unit joint length); penalty: DDA's kn in N/m per contact point.
  const std::size_t model = r["model"].as_choice({"constant", "bandis_barton", "penalty"}, "normal model");
  // A joint set may hold the parameters of both models, so that a run can switch models with
  // --set joint_sets.NAME.normal.model=... on the same mesh; the model picks which are needed.
  r.check_keys({"model", "kn", "kni", "vm", "jrc", "jcs", "ucs", "hysteresis", "reload"}, "");
  // Used by the bandis_barton closure only (kept, like kni and vm, when a run switches models).
  if (r.has("hysteresis")) law.hysteresis = r["hysteresis"].as_bool();
  if (const auto reload = r.optional("reload")) {
    // Bandis' later load cycles: a hyperbola of their own (joint_law.cpp), which needs the
    // largest closure the hysteresis remembers.
    reload->expect_object();
    reload->check_keys({"kni", "vm"}, "");
    law.reload_kni = reload->number("kni", kStiffness);
    law.reload_vm = reload->number("vm", interval(0, false, kMaxClosure, true));
    if (r.has("hysteresis") && !law.hysteresis)
      r["hysteresis"].fail("the reloading cycle (reload) needs the hysteresis: true or leave it out");
    law.hysteresis = true;
  }
  if (r.has("kn")) law.kn = r.number("kn", kStiffness);
  if (model == 0 || model == 2) {
    law.model = model == 0 ? NormalModel::constant : NormalModel::penalty;
    law.kn = r.number("kn", kStiffness);
  } else if (r.has("jrc") || r.has("jcs") || r.has("ucs")) {
    // Barton–Bandis empirical relations (Barton, Bandis & Bakhtar 1985; docs/physics.md §4), with
    // JCS and σc in MPa and lengths in mm inside the formulas:
    //   a_j = (JRC/5)(0.2·σc/JCS − 0.1)           initial aperture, mm
    //   Kni = −7.15 + 1.75·JRC + 0.02·JCS/a_j      MPa/mm = GPa/m
    //   Vm  = −0.2960 − 0.0056·JRC + 2.2410·(JCS/a_j)^−0.2450   mm (first load cycle)
    if (r.has("kni") || r.has("vm"))
      r.fail("give either kni and vm, or jrc, jcs and ucs, not both");
    law.model = NormalModel::bandis_barton;
    law.jrc = r.number("jrc", interval(0, false, 20, true));
    law.jcs = r.number("jcs", kStrength);
    law.ucs = r.number("ucs", kStrength);
    const double jcs_mpa = law.jcs / 1e6, ucs_mpa = law.ucs / 1e6;
    const double aj = (law.jrc / 5.0) * (0.2 * ucs_mpa / jcs_mpa - 0.1);  // mm
    if (!(aj > 0))
      r.fail("JRC, JCS and UCS give a non-positive initial aperture (needs UCS > 0.5·JCS)");
    const double kni_gpa = -7.15 + 1.75 * law.jrc + 0.02 * jcs_mpa / aj;
    const double vm_mm = -0.2960 - 0.0056 * law.jrc + 2.2410 * std::pow(jcs_mpa / aj, -0.2450);
    if (!(kni_gpa > 0) || !(vm_mm > 0))
      r.fail("JRC, JCS and UCS lie outside the range of the Barton–Bandis relations (Kni = " +
             std::to_string(kni_gpa) + " GPa/m, Vm = " + std::to_string(vm_mm) + " mm)");
    law.aperture = aj * 1e-3;
    law.kni = kni_gpa * 1e9;
    law.vm = vm_mm * 1e-3;
  } else {
    law.model = NormalModel::bandis_barton;
    law.kni = r.number("kni", kStiffness);
    law.vm = r.number("vm", interval(0, false, kMaxClosure, true));
  }
  return law;
}

ShearLawDef read_shear_law(const JsonReader& r) {
  r.expect_object();
  ShearLawDef law;
  // constant: ks in Pa/m (per unit joint length); penalty: DDA's ks in N/m per contact point.
  const std::size_t model =
      r["model"].as_choice({"constant", "hyperbolic", "penalty", "barton_bandis"}, "shear model");
  // Every model's parameters may be given side by side (runs switch models with --set).
  r.check_keys({"model", "ks", "ksi", "rf", "jrc", "jcs", "length", "lab_length", "strength_factor"}, "");
  if (r.has("ks")) law.ks = r.number("ks", kStiffness);
  if (model == 0 || model == 2) {
    law.model = model == 0 ? ShearModel::constant : ShearModel::penalty;
    law.ks = r.number("ks", kStiffness);
  } else if (model == 3) {
    // Barton–Bandis shear (solver/contact/barton_bandis.h): the elastic spring ks (Pa/m), JRC and JCS,
    // the joint length L_n for the peak displacement, and — if JRC and JCS were measured on a
    // sample of length L_0 — Bandis' scale corrections (Barton & Bandis 1982):
    //   JRC_n = JRC_0·(L_n/L_0)^(−0.02·JRC_0),   JCS_n = JCS_0·(L_n/L_0)^(−0.03·JRC_0)
    law.model = ShearModel::barton_bandis;
    law.ks = r.number("ks", kStiffness);
    law.jrc = r.number("jrc", interval(0, true, 20, true));
    law.jcs = r.number("jcs", kStrength);
    law.length = r.number("length", interval(0, false, kMaxCoordinate, true));
    law.lab_length = r.optional_number("lab_length", 0, interval(0, false, kMaxCoordinate, true));
    // Strength reduction (nmm-fos): τ = σn·tan(φr + JRC_mob·log10(JCS/σn)) / F at every σn.
    law.strength_factor = r.optional_number("strength_factor", 1, interval(1e-3, true, 1e3, true));
    if (law.lab_length > 0) {
      const double ratio = law.length / law.lab_length, jrc0 = law.jrc;
      law.jrc = jrc0 * std::pow(ratio, -0.02 * jrc0);
      law.jcs = law.jcs * std::pow(ratio, -0.03 * jrc0);
    }
  } else {
    law.model = ShearModel::hyperbolic;
    law.ksi = r.number("ksi", kStiffness);
    law.rf = r.number("rf", interval(0, false, 1, true));
  }
  return law;
}

}  // namespace nmm
