// Cohesive softening of new cracks (Hillerborg, Modéer & Petersson 1976; mixed mode after
// Camacho & Ortiz 1996; docs/physics.md "Fracture mechanics", docs/fracture.md).
//
// Normal traction t (tension positive) against the opening w of the faces (the contact's gap),
// with k the crack set's normal stiffness per unit length (Pa/m: kn·L/L, the penalty kn/L):
//     w ≤ w_e:        t = k_e·w                      (the faces held together, elastic)
//     w_e ≤ w ≤ w_c:  t = σt·(w_c − w)/(w_c − w_e)   (linear softening to zero)
//     w ≥ w_c:        t = 0
// w_e = min(σt/k, w_c/2), k_e = σt/w_e: the envelope rises on the crack set's own stiffness to σt
// and the softening line ends at w_c = 2·G_f/σt, so the area under the whole curve is
// ½·σt·w_c = G_f whatever k (a stiff k makes w_e negligible: the crack's elastic compliance adds
// σ/k to the opening). The damage κ is the largest effective opening reached at an accepted
// state; below it the faces unload and reload along the secant through the origin,
//     t = s(κ)·w,  s(κ) = t_env(κ)/κ   (s = k_e while κ ≤ w_e),
// and they never heal (κ never falls). In compression the crack set's normal law acts as for any
// joint.
//
// Mixed mode (Camacho & Ortiz 1996; Ortiz & Pandolfi 1999): one damage for both directions,
// driven by the effective opening
//     λ = √(⟨w_n⟩² + β²·w_s²),   β = 1,
// w_s the tangential jump of the faces since the crack formed (the shear spring's shear and the
// plastic slip). An open face (w_n > 0) carries the shear traction β²·s(κ)·w_s on the same secant
// (no stiffer than the crack set's shear spring), so its traction is parallel to the faces'
// relative displacement and reaches at most β·t_env(κ); a closed face (compression) has the crack
// set's friction and the softened cohesion β·σt·t_env(κ)/σt on top of it, its slip plastic. In
// pure shear either way the face does the work G_f (to within w_e/w_c for the closed one, whose
// cohesion holds in full over the elastic opening's share of slip). β = 1: the faces' shear
// strength is their tensile strength (Camacho and Ortiz's ratio of the two); with β ≠ 1 the
// traction of an open face leans off its opening, and a pull across a crack that kinks from
// element to element shears it.
// Closing (the faces meet, δ = −w > 0). The crack set's spring k against the secant s(κ) < k of a
// damaged face in tension would put a kink into the normal law at w = 0: the Newton iterates of a
// face unloaded to a gap of nanometres then switched between the two tangents every iteration and
// cycled (Petersson's beam, docs/notes/2026-11-cohesive.md). The stiffness instead rises from s to
// k over the elastic opening b = w_e as the faces come into contact,
//     σ(δ) = s·δ + (k − s)·δ²/(2b)  (0 ≤ δ ≤ b),   σ_joint(δ − (1 − s/k)·b/2)  (δ > b),
// continuous with its tangent at δ = 0 and (for a constant kn) at b; the faces interpenetrate at
// most (1 − s/k)·b/2 ≤ w_e/2 more under a compressive load than the crack set's law alone allows.
// An undamaged face (s = k) keeps the crack set's law. The shear spring of a damaged face is its
// secant β²·s(κ) (capped at the crack set's ks) whether open or closed, so that its shear force is
// continuous through closing too: at δ = 0 the closed face's strength is its cohesion β·t_env(κ),
// which the open face's secant traction β²·s(κ)·w_s reaches only on the envelope (β·w_s ≤ λ ≤ κ).
//
// Dissipated energy per unit length of crack at damage κ (the work to κ on the envelope less the
// elastic energy the secant gives back), a function of κ alone:
//     D(κ) = 0 (κ ≤ w_e),   ½·(σt·κ − t_env(κ)·w_e) (w_e < κ < w_c),   G_f = ½·σt·w_c (κ ≥ w_c)
// Hillerborg's characteristic length l_ch = E·G_f/σt²: a bar of length L pulled at its end is
// stable after its peak while L < 2·l_ch; beyond, its elastic energy exceeds what the crack can
// dissipate and the static path snaps back (Bažant & Planas 1998, ch. 2).
#include "solver/contact/cohesive_law.h"

#include <algorithm>
#include <cmath>

namespace nmm::solve {

CohesiveLaw cohesive_law(const StrengthDef& s) {
  CohesiveLaw law;
  if (!s.present || !(s.fracture_energy > 0) || !(s.tensile > 0)) return law;
  law.tensile = s.tensile;
  law.beta = cohesive_beta();
  law.cohesion = law.beta * s.tensile;
  law.w_c = 2 * s.fracture_energy / s.tensile;
  return law;
}

namespace {
double elastic_opening(const CohesiveLaw& law, double k) {
  return k > 0 ? std::min(law.tensile / k, 0.5 * law.w_c) : 0.5 * law.w_c;
}
double envelope(const CohesiveLaw& law, double we, double kappa) {  // Pa, t_env(κ ≥ w_e)
  return kappa >= law.w_c ? 0.0 : law.tensile * (law.w_c - kappa) / (law.w_c - we);
}
}  // namespace

CohesiveState cohesive_state(const CohesiveLaw& law, double k, double kappa) {
  CohesiveState s;
  if (!law.on()) return s;
  const double we = elastic_opening(law, k);
  if (kappa <= we) return {law.tensile / we, 1.0};
  const double t = envelope(law, we, kappa);
  return {t / kappa, t / law.tensile};
}

double effective_opening(const CohesiveLaw& law, double opening, double slip) {
  const double wn = std::max(opening, 0.0), ws = law.beta * slip;
  return std::sqrt(wn * wn + ws * ws);
}

CohesiveTraction cohesive_traction(const CohesiveLaw& law, double k, double kappa0, double opening, double slip) {
  CohesiveTraction t;
  if (!law.on()) return t;
  const double g = std::max(opening, 0.0), lambda = effective_opening(law, g, slip);
  t.kappa = std::max(kappa0, lambda);
  const CohesiveState st = cohesive_state(law, k, t.kappa);
  t.traction = st.secant * g;
  const double we = elastic_opening(law, k);
  t.stiffness = t.kappa <= we ? law.tensile / we : lambda < kappa0 ? st.secant : 0.0;
  return t;
}

CohesiveClosure cohesive_closure(const CohesiveLaw& law, double k, double kappa, double closure) {
  CohesiveClosure c;
  c.closure = closure;
  if (!law.on() || !(k > 0)) return c;
  const double b = elastic_opening(law, k), s = cohesive_state(law, k, kappa).secant;
  if (!(s < k) || !(b > 0)) return c;
  if (closure < b) {
    c.band = true;
    c.stress = s * closure + (k - s) * closure * closure / (2 * b);
    c.stiffness = s + (k - s) * closure / b;
    return c;
  }
  c.closure = closure - (1 - s / k) * 0.5 * b;
  return c;
}

double cohesive_elastic_opening(const CohesiveLaw& law, double k) { return elastic_opening(law, k); }

double cohesive_shear_secant(const CohesiveLaw& law, double k, double kappa) {
  return law.beta * law.beta * cohesive_state(law, k, kappa).secant;
}

double cohesive_dissipation(const CohesiveLaw& law, double k, double kappa) {
  if (!law.on()) return 0;
  const double we = elastic_opening(law, k);
  if (kappa <= we) return 0;
  return 0.5 * (law.tensile * std::min(kappa, law.w_c) - envelope(law, we, kappa) * we);
}

double characteristic_length(double young, const StrengthDef& s) {
  const CohesiveLaw law = cohesive_law(s);
  return law.on() ? young * s.fracture_energy / (s.tensile * s.tensile) : 0.0;
}

}  // namespace nmm::solve
