// A joint set's laws (joint_sets.NAME.normal and .shear): how a joint closes under normal
// stress and how it resists shear. The parameters of several models may stand side by side in
// one set, so that a run switches models with --set on the same mesh; "model" picks which are
// read. The laws themselves are solver/contact/joint_law.h and solver/contact/barton_bandis.h.
#pragma once

namespace nmm {

class JsonReader;

/// constant: kn in Pa/m (joint stress per unit closure, integrated over each contact's tributary
/// length); bandis_barton: the closure curve (Pa/m, m); penalty: DDA's point spring, kn in N/m
/// per contact point (so the joint's stiffness grows with the number of contact points).
enum class NormalModel { constant, bandis_barton, penalty };
struct NormalLawDef {
  NormalModel model = NormalModel::constant;
  double kn = 0;   ///< Pa/m (constant model) or N/m per contact point (penalty)
  double kni = 0;  ///< Pa/m, initial normal stiffness (Bandis–Barton)
  double vm = 0;   ///< m, maximum closure (Bandis–Barton)
  bool hysteresis = false;  ///< Bandis–Barton: unload and reload along the tangent at the largest closure
  /// Bandis–Barton cycles ("reload"): below the largest closure the joint unloads and reloads on
  /// the reloading cycle's hyperbola, initial stiffness reload_kni (Pa/m) and maximum closure
  /// reload_vm (m), from the permanent closure (0: not given; then `hysteresis` is the tangent)
  double reload_kni = 0;
  double reload_vm = 0;
  // Given instead of kni and vm, these derive them (Barton–Bandis empirical relations):
  double jrc = 0;       ///< –, joint roughness coefficient (0 if not given)
  double jcs = 0;       ///< Pa, joint wall compressive strength
  double ucs = 0;       ///< Pa, uniaxial compressive strength of the intact rock (σc)
  double aperture = 0;  ///< m, initial aperture a_j derived from them
};

/// constant: ks in Pa/m (shear stress per unit shear displacement); hyperbolic: the curve (Pa/m,
/// –); penalty: DDA's point spring, ks in N/m per contact point; barton_bandis: Barton's peak
/// strength, mobilised roughness and dilation (solver/contact/barton_bandis.h) on an elastic spring ks
/// in Pa/m, the joint set's friction_deg being the residual friction angle φr.
enum class ShearModel { constant, hyperbolic, penalty, barton_bandis };
struct ShearLawDef {
  ShearModel model = ShearModel::constant;
  double ks = 0;   ///< Pa/m (constant and barton_bandis) or N/m per contact point (penalty)
  double ksi = 0;  ///< Pa/m, initial shear stiffness (hyperbolic)
  double rf = 0;   ///< –, failure ratio in (0, 1] (hyperbolic)
  // Barton–Bandis shear (field scale after the scale corrections when lab_length is given):
  double jrc = 0;         ///< –, joint roughness coefficient JRC_n at the joint length
  double jcs = 0;         ///< Pa, joint wall compressive strength JCS_n at the joint length
  double length = 0;      ///< m, joint (block) length L_n: peak displacement δp = L_n/500·(JRC_n/L_n)^0.33
  double lab_length = 0;  ///< m, L_0 of the sample JRC and JCS were measured on (0: no scale correction)
  double strength_factor = 1;  ///< –, the frictional strength is divided by it (strength reduction, nmm-fos)
};

/// joint_sets.NAME.normal: {model: constant | bandis_barton | penalty, kn, kni, vm, jrc, jcs,
/// ucs, hysteresis, reload: {kni, vm}}.
NormalLawDef read_normal_law(const JsonReader& r);

/// joint_sets.NAME.shear: {model: constant | hyperbolic | penalty | barton_bandis, ks, ksi, rf,
/// jrc, jcs, length, lab_length, strength_factor}.
ShearLawDef read_shear_law(const JsonReader& r);

}  // namespace nmm
