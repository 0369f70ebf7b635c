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

#include <algorithm>
#include <cmath>

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

/// A cheap screen before rock_failure, for the elements a quiet step leaves far inside their
/// strength: the same ratio max(r_t, r_s) with √(a² + b²) for the radius instead of std::hypot and
/// no directions (no atan2, sin, cos), against 1 less what rounding can make of the difference.
/// Both ratios are the same sums and products of σxx, σyy, σxy, Nφ and the strengths; they differ
/// only by the rounding of each operation (the radius by at most 3ε of it, each other operation by
/// ε of its result, ε = 2⁻⁵²), so with S = |σxx| + |σyy| + |σxy| ≥ |σ1|, |σ2|, radius
///     |ratio − rock_failure(...).ratio| ≤ 10·(1 + Nφ)·ε·S / min(σt, UCS) + 2ε,
/// and the screen keeps a margin of 1e-13·(1 + Nφ)·S / min(σt, UCS) + 1e-12, over 40 times that.
/// Where the screen says "holds", rock_failure's ratio is below 1 as well; every other element
/// goes to rock_failure, so the rule (fracture.h) sees the same ratios ≥ 1 and the same
/// decisions bit for bit.
class StrengthScreen {
 public:
  StrengthScreen() = default;  ///< screens nothing: every stress goes to rock_failure
  explicit StrengthScreen(const StrengthDef& strength);
  /// True when the stress surely lies inside the strength (rock_failure's ratio < 1).
  bool surely_holds(double sxx, double syy, double sxy) const {
    if (!usable_) return false;
    const double mean = 0.5 * (sxx + syy), half = 0.5 * (sxx - syy);
    const double radius = std::sqrt(half * half + sxy * sxy);
    const double s1 = mean + radius, s2 = mean - radius;
    const double ratio = std::max(s1 / tensile_, (n_phi_ * s1 - s2) / ucs_);
    return ratio < 1 - 1e-12 - slack_ * (std::abs(sxx) + std::abs(syy) + std::abs(sxy));
  }

 private:
  bool usable_ = false;  // positive σt and UCS (else rock_failure's own special cases decide)
  double tensile_ = 0;   // Pa, σt
  double n_phi_ = 0;     // –, Nφ = (1 + sinφ)/(1 − sinφ)
  double ucs_ = 0;       // Pa, 2c·cosφ/(1 − sinφ)
  double slack_ = 0;     // 1/Pa, 1e-13·(1 + Nφ)/min(σt, UCS): the margin per Pa of S
};

}  // namespace nmm::solve
