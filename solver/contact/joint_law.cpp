// Joint laws on contact springs (seed paper; docs/physics.md §4).
//
// A contact point stands for a tributary length L of joint (contact_set.cpp, tributary_length.cpp: half of each of the
// contact vertex's candidate edges that face the contacted edge). Its spring force is the joint
// stress times L, so the *force* follows the constitutive curve exactly (a secant relation),
// while the matrix gets the tangent stiffness (Newton's method in the open–close iteration).
//
// Normal, Bandis–Barton closure (Bandis, Lumsden & Barton 1983), closure δ ≥ 0:
//     σn = Kni·δ / (1 − δ/Vm)                 ⇔  δ = σn·Vm / (Kni·Vm + σn)
//     kn = dσn/dδ · L = Kni·L / (1 − δ/Vm)²    (rises steeply as δ → Vm)
//   Guard: δ is held at 0.99·Vm; beyond, the force grows linearly with the tangent there, so it
//   stays finite and monotonic (the contact is reported as capped). In tension (δ < 0) the
//   spring uses Kni·L, and opens beyond the tensile strength as with a constant spring.
//   Unloading retraces the loading curve: closure is nonlinear elastic here (real joints show
//   hysteresis between load cycles, which the first-cycle law does not describe) — unless the
//   joint set asks for hysteresis: below the largest closure so far δmax (the contact's memory)
//   the joint unloads and reloads along the tangent there (ours; Bandis, Lumsden & Barton 1983
//   measured unloading curves much stiffer than loading, with a permanent set):
//     σn = max(0, σmax − kt·(δmax − δ)),  σmax = σn(δmax),  kt = Kni/(1 − δmax/Vm)²
//   so the joint keeps the permanent closure δmax − σmax/kt = δmax²/Vm at zero stress,
//   and loading beyond δmax continues on the virgin curve (force and tangent continuous there).
//   With the reloading cycle's parameters (Kni2, Vm2: "reload"), Bandis, Lumsden & Barton's
//   (1983) cycle curves instead: each later cycle is a hyperbola of its own, measured from the
//   permanent closure δ0 the earlier loading left,
//     σn = Kni2·x / (1 − x/Vm2),  x = δ − δ0,   kn = Kni2·L/(1 − x/Vm2)²
//   through the largest stress reached, σ(δmax) = σmax, which fixes the permanent closure:
//     δ0 = δmax − σmax·Vm2/(Kni2·Vm2 + σmax)
//   Unloading and reloading follow it (the narrow loop between them in each of Bandis' later
//   cycles is left out); beyond δmax the virgin curve goes on (force continuous). A reloading
//   curve softer than the first loading's secant (δ0 < 0) is taken from δ0 = 0 and scaled to
//   σmax at δmax: no permanent closure. Guard as on the virgin curve: x held at 0.99·Vm2, the
//   force linear beyond with the tangent there (δ0 found on the guarded curve, so the force
//   stays continuous at δmax even after the virgin curve's cap).
// Shear, hyperbolic (Kulhawy 1975; Duncan–Chang form), elastic shear u ≥ 0, strength
// τf = c + σn·tanφ, i.e. T_f = tanφ·N + c·L on the contact (c → the residual cohesion c_r once
// the contact is broken: it reached its peak at an accepted step or opened, contact_problem.cpp;
// c_r = 0 unless the joint set gives one):
//     τ = u / (1/Ksi + Rf·u/τf)              ⇔  u = τ / (Ksi·(1 − Rf·τ/τf))
//     ks = dτ/du · L = Ksi·L·(1 − Rf·τ/τf)²   (falls as u grows)
//   The contact slips (Mohr–Coulomb) when the force reaches T_f, which the curve does at
//   u = τf/(Ksi(1 − Rf)) (for Rf = 1 only asymptotically: slip then comes from the limit check
//   at 99.9 % of T_f). Guards: ks ≥ 1e-3·Ksi·L; with no strength (τf = 0) there is no shear
//   force and no division: the contact slides. Unloading (u shrinking) follows the same curve.
// Barton–Bandis (barton_bandis.cpp): an elastic spring ks (Pa/m, like the constant law) capped at
//   L·σn·tan(φr + JRC_mob(δ)·log10(JCS/σn)), σn = N/L the effective normal stress and δ the
//   contact's shear travel (forward; sliding back toward its start position the dilation's share
//   of the roughness turns against it); its dilation enters the normal spring through the
//   contact's gap.
// Constant (a joint stiffness, like the laws above): σn = kn·δ, τ = ks·u with kn, ks in Pa/m;
//   force kn·L·δ, stiffness kn·L. A joint closes by σn/kn whatever the mesh size, because the
//   tributary lengths of the contacts along it add up to its length.
// Penalty (Shi's DDA point spring): force = k·x, stiffness k (N/m per contact point). The joint's
//   stiffness is then k times the contact points per metre of joint, which grows as 1/h: kept by
//   name for DDA habits and comparisons with DDA codes.
#include "solver/contact/joint_law.h"

#include <algorithm>
#include <cmath>

#include "common/math_constants.h"

namespace nmm::solve {

namespace {
ContactLaw joint_set_law(const JointSetDef& js) {
  ContactLaw law;
  law.normal = js.normal.model;
  law.kn = js.normal.kn;
  law.kni = js.normal.kni;
  law.vm = js.normal.vm;
  law.shear = js.shear.model;
  law.ks = js.shear.ks;
  law.ksi = js.shear.ksi;
  law.rf = js.shear.rf;
  law.tan_phi = std::tan(js.friction_deg * kPi / 180.0);
  law.cohesion = js.cohesion;
  law.residual_cohesion = js.residual_cohesion;
  law.tensile = js.tensile_strength;
  law.hysteresis = js.normal.hysteresis;
  law.reload_kni = js.normal.reload_kni;
  law.reload_vm = js.normal.reload_vm;
  if (js.shear.model == ShearModel::barton_bandis)
    law.bb = {js.shear.jrc, js.shear.jcs, js.friction_deg,
              peak_shear_displacement(js.shear.jrc, js.shear.length), js.shear.strength_factor};
  return law;
}

}  // namespace

ContactLaws contact_laws(const SceneDef& scene, double interface_kn, double interface_ks) {
  ContactLaws c;
  for (const JointSetDef& js : scene.joint_sets) c.laws.push_back(joint_set_law(js));
  for (const JointDef& j : scene.joints) c.joint_law.push_back(j.set);
  if (scene.interface_set >= 0) {
    c.interface_law = scene.interface_set;
  } else {
    // The default interface of touching bodies is numerical, not a joint (model.h
    // PenaltyDefaults): a scene with a real joint between bodies gives an interface_set.
    ContactLaw law;
    law.kn = interface_kn;
    law.ks = interface_ks;
    c.laws.push_back(law);
    c.interface_law = static_cast<int>(c.laws.size()) - 1;
  }
  return c;
}

SpringState normal_spring(const ContactLaw& law, double closure, double length, double closure_max) {
  SpringState s;
  if (law.normal != NormalModel::bandis_barton) {
    s.stiffness = initial_normal_stiffness(law, length);
    s.force = s.stiffness * closure;
    return s;
  }
  const double k0 = law.kni * length;
  if (closure <= 0) {  // tension: the initial stiffness
    s.force = k0 * closure;
    s.stiffness = k0;
    return s;
  }
  const double cap = 0.99 * law.vm;
  if (law.hysteresis && closure < closure_max && law.reload_kni > 0) {  // Bandis' later cycles
    const double smax = normal_spring(law, closure_max, length).force / length;  // Pa
    const double k2 = law.reload_kni, v2 = law.reload_vm;
    // The later cycles' curve with the virgin curve's guard: x held at 0.99·Vm2, linear beyond.
    const double xc = 0.99 * v2, rc = 1 - xc / v2, scap = k2 * xc / rc, kcap = k2 / (rc * rc);
    auto stress = [&](double x) { return x <= xc ? k2 * x / (1 - x / v2) : scap + kcap * (x - xc); };
    const double xmax = smax <= scap ? smax * v2 / (k2 * v2 + smax) : xc + (smax - scap) / kcap;
    double d0 = closure_max - xmax, scale = 1;
    if (d0 < 0) {
      d0 = 0;
      scale = smax / stress(closure_max);
    }
    const double x = closure - d0;
    if (x <= 0) return s;
    const double r = 1 - std::min(x, xc) / v2;
    s.force = scale * length * stress(x);
    s.stiffness = scale * k2 * length / (r * r);
    s.capped = x > xc;
    return s;
  }
  if (law.hysteresis && closure < closure_max) {  // the unloading / reloading line
    const SpringState top = normal_spring(law, closure_max, length);
    s.force = top.force - top.stiffness * (closure_max - closure);
    s.stiffness = top.stiffness;
    if (s.force <= 0) s = SpringState{};
    return s;
  }
  const double d = std::min(closure, cap);
  const double r = 1.0 - d / law.vm;
  s.force = k0 * d / r;
  s.stiffness = k0 / (r * r);
  if (closure > cap) {
    s.force += s.stiffness * (closure - cap);
    s.capped = true;
  }
  return s;
}

double initial_normal_stiffness(const ContactLaw& law, double length) {
  switch (law.normal) {
    case NormalModel::constant: return law.kn * length;
    case NormalModel::penalty: return law.kn;
    case NormalModel::bandis_barton: break;
  }
  return law.kni * length;
}

double shear_strength(const ContactLaw& law, double normal_force, double length, bool broken,
                      const JointMemory& start, double step_shear) {
  const double c = broken ? law.residual_cohesion : law.cohesion;
  const double n = std::max(normal_force, 0.0);
  const double friction = law.shear == ShearModel::barton_bandis && length > 0
                              ? length * barton_bandis_strength(law.bb, n / length, {start.travel, start.dilation, start.position},
                                                               step_shear)
                              : law.tan_phi * n;
  return std::max(0.0, friction + c * length);
}

double initial_shear_stiffness(const ContactLaw& law, double length) {
  switch (law.shear) {
    case ShearModel::constant:
    case ShearModel::barton_bandis: return law.ks * length;
    case ShearModel::penalty: return law.ks;
    case ShearModel::hyperbolic: break;
  }
  return law.ksi * length;
}

bool linear_shear(const ContactLaw& law) { return law.shear != ShearModel::hyperbolic; }

SpringState shear_spring(const ContactLaw& law, double shear, double strength, double length) {
  SpringState s;
  if (linear_shear(law)) {
    s.stiffness = initial_shear_stiffness(law, length);
    s.force = s.stiffness * shear;
    return s;
  }
  const double k0 = law.ksi * length;
  if (!(strength > 0)) {  // no strength: no shear force (the contact slides)
    s.stiffness = 1e-3 * k0;
    return s;
  }
  const double u = std::abs(shear);
  const double t = u / (1.0 / k0 + law.rf * u / strength);  // force, N
  const double ratio = std::min(law.rf * t / strength, 1.0);
  s.force = shear < 0 ? -t : t;
  s.stiffness = std::max(k0 * (1.0 - ratio) * (1.0 - ratio), 1e-3 * k0);
  return s;
}

double shear_at_force(const ContactLaw& law, double force, double strength, double length) {
  const double f = std::abs(force);
  if (linear_shear(law)) return f / initial_shear_stiffness(law, length);
  const double k0 = law.ksi * length;
  if (!(strength > 0)) return 0;
  const double t = std::min(f, 0.999 * strength / std::max(law.rf, 1e-12));
  return t / (k0 * (1.0 - law.rf * t / strength));
}

}  // namespace nmm::solve

namespace nmm::solve {

JointMemory advance_joint_memory(const ContactLaw& law, JointMemory m, double normal_force,
                                 double length, double step_shear, double closure) {
  if (law.normal == NormalModel::bandis_barton && law.hysteresis)
    m.closure_max = std::max(m.closure_max, closure);
  if (law.shear == ShearModel::barton_bandis && length > 0) {
    const JointTravel t = advance_barton_bandis(law.bb, {m.travel, m.dilation, m.position},
                                                std::max(normal_force, 0.0) / length, step_shear);
    m.travel = t.travel;
    m.dilation = t.dilation;
    m.position = t.position;
  }
  return m;
}

JointLawOutput joint_law_output(const ContactLaw& law, double normal_force, double length,
                                const JointMemory& memory) {
  JointLawOutput o;
  if (law.shear != ShearModel::barton_bandis || !(length > 0)) return o;
  o.jrc_mob = barton_bandis_state(law.bb, std::max(normal_force, 0.0) / length, memory.travel).jrc_mob;
  o.dilation = memory.dilation;
  return o;
}

}  // namespace nmm::solve
