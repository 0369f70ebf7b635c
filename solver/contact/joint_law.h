// Rock-joint constitutive laws for contact springs (the seed paper's modified contact model):
// Bandis–Barton closure for the normal direction, the hyperbolic law for shear, constant joint
// stiffnesses (Pa/m), or DDA's point penalty (N/m per contact point). See joint_law.cpp for the
// equations and the mapping onto contact points.
#pragma once

#include "solver/contact/barton_bandis.h"
#include <vector>

#include "common/scene.h"

namespace nmm::solve {

/// One joint set's contact law (or the default interface's).
struct ContactLaw {
  NormalModel normal = NormalModel::constant;
  ShearModel shear = ShearModel::constant;
  double kn = 0;        ///< Pa/m (constant normal) or N/m per contact point (penalty)
  double kni = 0;       ///< Pa/m, initial normal stiffness (Bandis–Barton)
  double vm = 0;        ///< m, maximum closure (Bandis–Barton)
  bool hysteresis = false;  ///< Bandis–Barton: unload and reload below the largest closure
  double reload_kni = 0;    ///< Pa/m, the reloading cycle's Kni (0: the tangent at the largest closure)
  double reload_vm = 0;     ///< m, the reloading cycle's Vm
  double ks = 0;        ///< Pa/m (constant shear) or N/m per contact point (penalty)
  double ksi = 0;       ///< Pa/m, initial shear stiffness (hyperbolic)
  double rf = 1;        ///< –, failure ratio (hyperbolic)
  double tan_phi = 0;   ///< –, friction coefficient
  double cohesion = 0;  ///< Pa
  double residual_cohesion = 0;  ///< Pa, cohesion of a broken contact (0: brittle)
  double tensile = 0;   ///< Pa, tensile strength
  BartonBandis bb;      ///< Barton–Bandis shear strength and dilation (shear == barton_bandis)
};

/// The laws of a run's contacts (derived once from the scene, owned by the ContactSet).
struct ContactLaws {
  std::vector<ContactLaw> laws;  ///< every joint set's law, then (without interface_set) the default interface's
  std::vector<int> joint_law;    ///< [joint] index into laws
  int interface_law = 0;         ///< the law of faces between blocks that are not on a joint
};
/// The scene's laws; the default interface (no interface_set) has kn and ks given (Pa/m).
ContactLaws contact_laws(const SceneDef& scene, double interface_kn, double interface_ks);

/// What a joint law remembers of a contact's past, carried from step to step with the contact
/// (ContactHistory) and saved in checkpoints.
struct JointMemory {
  double travel = 0;       ///< m, δ: shear travel so far, either direction (Barton–Bandis)
  double dilation = 0;     ///< m, v: opening from shearing over the asperities (Barton–Bandis)
  double closure_max = 0;  ///< m, largest closure so far (Bandis–Barton hysteresis)
  double position = 0;     ///< m, u: signed shear displacement from the start (Barton–Bandis)
};

/// The memory after an accepted step in which a closed contact carried the normal force N (N,
/// effective: the spring's), sheared by Δu (m) and ended at closure δ (m), tributary length L.
JointMemory advance_joint_memory(const ContactLaw& law, JointMemory m, double normal_force,
                                 double length, double step_shear, double closure);

/// What the joint law's state shows in the output (contacts.csv).
struct JointLawOutput {
  double jrc_mob = 0;   ///< –, mobilised JRC (Barton–Bandis shear; 0 for the other laws)
  double dilation = 0;  ///< m, opening from shearing (Barton–Bandis; 0 for the other laws)
};
JointLawOutput joint_law_output(const ContactLaw& law, double normal_force, double length,
                                const JointMemory& memory);

/// Force and tangent stiffness of a contact spring at one state.
struct SpringState {
  double force = 0;      ///< N, compression (normal) or shear force, along the displacement
  double stiffness = 0;  ///< N/m, tangent dForce/dDisplacement
  bool capped = false;   ///< the closure was held below Vm (Bandis–Barton)
};

/// Normal spring at closure δ ≥ 0 (m) for a contact of tributary length L (m) whose largest
/// closure so far is δmax (m; used by the Bandis–Barton hysteresis only).
SpringState normal_spring(const ContactLaw& law, double closure, double length, double closure_max = 0);

/// Normal stiffness used in tension and for judging opening (N/m): kn·L, Kni·L, or the penalty kn.
double initial_normal_stiffness(const ContactLaw& law, double length);

/// Shear strength of a contact, N: tanφ·N + c·L, with the residual cohesion c_r in place of c once
/// the contact is broken (it reached its peak at an accepted step, or opened; c_r = 0 by
/// default: brittle). A Barton–Bandis joint
/// has L·τ + c·L instead of tanφ·N, τ its strength at σn = N/L after sliding by Δu (m, signed)
/// from its memory `start` (barton_bandis_strength: travel, direction, position).
double shear_strength(const ContactLaw& law, double normal_force, double length, bool broken,
                      const JointMemory& start = {}, double step_shear = 0);

/// True if the shear spring is linear (constant or penalty): its force is ks·s up to the strength.
bool linear_shear(const ContactLaw& law);

/// Shear spring at signed elastic shear s (m), with strength `strength` (N, ≥ 0) and length L.
SpringState shear_spring(const ContactLaw& law, double shear, double strength, double length);

/// Initial shear stiffness (N/m): ks·L, Ksi·L, or the penalty ks.
double initial_shear_stiffness(const ContactLaw& law, double length);

/// Elastic shear (m, ≥ 0) at which the shear spring carries `force` (N) below its strength:
/// the inverse of shear_spring (used to leave a sliding contact's spring loaded at the limit).
double shear_at_force(const ContactLaw& law, double force, double strength, double length);

}  // namespace nmm::solve
