// Cohesive softening of a new crack's faces (docs/fracture.md "Cohesive softening"; equations in
// cohesive_law.cpp): a crack cut into rock of fracture energy G_f keeps a tensile traction that
// falls linearly with the opening to zero at w_c = 2·G_f/σt, unloads towards the origin and never
// heals. A contact of the crack set carries the damage (the largest effective opening reached at
// an accepted state) in its history (CohesiveMemory) over re-cuts and checkpoints.
#pragma once

#include "common/scene.h"

namespace nmm::solve {

/// The cohesive law of one material's new cracks (all zero: the material has no fracture energy).
struct CohesiveLaw {
  double tensile = 0;   ///< Pa, σt: the traction at the start of softening
  double cohesion = 0;  ///< Pa, β·σt: the shear cohesion at the start of softening
  double w_c = 0;       ///< m, 2·G_f/σt: the opening at which the traction is gone
  double beta = 0;      ///< –, the weight of slip in the effective opening (cohesive_beta())
  bool on() const { return w_c > 0; }
};
/// –, Camacho and Ortiz's β, the ratio of the faces' shear to tensile strength: 1, so that the
/// traction of an open face is parallel to the faces' relative displacement.
constexpr double cohesive_beta() { return 1.0; }
/// The law of a material's strength (off without fracture_energy or tensile strength).
CohesiveLaw cohesive_law(const StrengthDef& strength);

/// What a cohesive contact carries from one accepted step to the next (ContactHistory, the
/// checkpoint's CONTACT section).
struct CohesiveMemory {
  bool on = false;         ///< the contact is a face of a crack cut during the run
  double opening_max = 0;  ///< m, κ: the largest effective opening reached at an accepted state
  double slip = 0;         ///< m, the plastic slip of its faces since the crack formed, |Σ|
};

/// The law at one damage κ, for a contact whose elastic tension stiffness is k (Pa/m).
struct CohesiveState {
  double secant = 0;    ///< Pa/m, t/w on the unloading line through the origin (0: no traction)
  double factor = 0;    ///< –, the share of σt and c the faces still carry at the envelope
};
CohesiveState cohesive_state(const CohesiveLaw& law, double k, double kappa);

/// The normal traction of a face of damage κ0 (at the step's start) at an opening and a plastic
/// slip (m): the damage they make, κ = max(κ0, λ), the traction on the secant of κ, and the
/// stiffness the Newton matrix takes for it — the elastic one on the rising branch, the secant
/// unloading, none softening (the envelope's negative slope would make the matrix indefinite: the
/// line search finds the point instead).
struct CohesiveTraction {
  double traction = 0;   ///< Pa, tension positive
  double stiffness = 0;  ///< Pa/m, ≥ 0
  double kappa = 0;      ///< m
};
CohesiveTraction cohesive_traction(const CohesiveLaw& law, double k, double kappa0, double opening, double slip);

/// A face of damage κ closing by δ > 0 (m): the normal stress (Pa, compression positive) and its
/// tangent (Pa/m) run from the unloading secant s(κ) at δ = 0 to the crack set's stiffness k over a
/// band b = w_e (the elastic opening σt/k),
///     σ = s·δ + (k − s)·δ²/(2b)   (δ < b),   the crack set's own law at δ − (1 − s/k)·b/2 beyond,
/// so force and tangent are continuous where the face closes (cohesive_law.cpp). `band`: δ < b;
/// beyond it the caller evaluates the crack set's law at `closure` (the shifted δ). An undamaged
/// face (s = k) gets its law at δ itself.
struct CohesiveClosure {
  bool band = false;     ///< within the band: stress and stiffness hold
  double stress = 0;     ///< Pa, compression positive
  double stiffness = 0;  ///< Pa/m
  double closure = 0;    ///< m, the closure the crack set's law sees beyond the band
};
CohesiveClosure cohesive_closure(const CohesiveLaw& law, double k, double kappa, double closure);

/// Pa/m, the tangential secant of a face of damage κ, β²·s(κ): the shear stiffness of an open face,
/// and of a closed damaged one below its strength (one spring either side of closing).
double cohesive_shear_secant(const CohesiveLaw& law, double k, double kappa);

/// m, w_e = min(σt/k, w_c/2): the opening at which the faces reach σt on the crack set's spring k.
double cohesive_elastic_opening(const CohesiveLaw& law, double k);

/// m, λ = √(⟨w_n⟩² + β²·w_s²): the effective opening of an opening w_n and a plastic slip w_s.
double effective_opening(const CohesiveLaw& law, double opening, double slip);

/// J/m², what a face of damage κ has dissipated since it formed: the work of its traction to κ
/// on the envelope less the elastic energy it would give back unloading along the secant.
double cohesive_dissipation(const CohesiveLaw& law, double k, double kappa);

/// m, Hillerborg's characteristic length E·G_f/σt² of a material (0 without cohesive softening).
double characteristic_length(double young, const StrengthDef& strength);

}  // namespace nmm::solve
