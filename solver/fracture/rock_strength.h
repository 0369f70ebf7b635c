// Intact rock's strength at a manifold element's stress: the tension cut-off and Mohr–Coulomb
// (Ning, An & Ma 2011 apply both per manifold element in the NMM; docs/fracture.md).
//
// In-plane principal stresses, tension positive: σ1 ≥ σ2, σ1 at angle θ1 from x with
//     σ1,2 = (σxx + σyy)/2 ± √(((σxx − σyy)/2)² + σxy²),   tan 2θ1 = 2σxy / (σxx − σyy).
// Tension cut-off: the rock breaks where σ1 ≥ σt, across σ1 (the crack runs along σ2's direction).
// Mohr–Coulomb with compression positive, p1 = −σ2 ≥ p3 = −σ1 (major and minor compression):
//     p1 ≥ Nφ·p3 + 2c·√Nφ,   Nφ = (1 + sinφ)/(1 − sinφ),   2c·√Nφ = 2c·cosφ/(1 − sinφ) (the UCS);
// the failure plane's normal makes 45° + φ/2 with the major compression, so the crack runs at
// 45° − φ/2 from it, on either side (two conjugate planes). The ratios that rank elements:
//     r_t = σ1 / σt,    r_s = (p1 − Nφ·p3) / (2c·√Nφ)        (≥ 1: the element breaks)
// and the mode is tensile where r_t ≥ 1 (also when both are), shear otherwise.
// The out-of-plane stress of plane strain, σz = ν(σxx + σyy), is not a principal stress of the
// criterion: in the tests and examples it lies between σ1 and σ2, where Mohr–Coulomb ignores it
// (the intermediate principal stress), and a plane-strain element never cracks across the plane.
#pragma once

#include "common/scene.h"
#include "common/vec2.h"

namespace nmm::solve {

enum class CrackMode : unsigned char { tensile, shear };

struct RockFailure {
  double ratio = 0;            ///< –, max(r_t, r_s): ≥ 1 breaks
  CrackMode mode = CrackMode::tensile;
  Vec2 direction;              ///< unit, the crack's direction (current configuration)
  Vec2 conjugate;              ///< unit, shear's other plane (= direction for tensile)
};

/// The strength check of a stress σxx, σyy, σxy (Pa, tension positive).
RockFailure rock_failure(const StrengthDef& strength, double sxx, double syy, double sxy);

}  // namespace nmm::solve
