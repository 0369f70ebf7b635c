// The cohesive tension bar (docs/fracture.md "Cohesive softening"): the scene of
// tests/test_cohesive.cpp and of nmm-study's tension-bar case (docs/accuracy.md "Fracture").
//
// A bar of length L, 0.2 m wide at its ends and 0.19 m at its middle (a straight taper, so that
// it cracks there), E 10 GPa, ν 0.2, plane stress, σt 1 MPa, G_f 100 J/m² (w_c = 2·G_f/σt =
// 200 µm, Hillerborg's l_ch = E·G_f/σt² = 1 m); its left end held in x (a fixed point at its
// middle), its right end pulled by a support at 1 mm/s, 1 µm a static step of 1 ms (260 steps);
// crack faces kn 1e13 Pa/m (w_e = σt/kn = 0.1 µm), ks 4e12 Pa/m, φ 30°. Measure points 1 mm in
// from each end on the axis.
//
// Closed forms (Hillerborg, Modéer & Petersson 1976): the peak P = σt·0.19 m; the end's
// displacement after the peak u = P·C + w_c(1 − σ/σt), σ = P/0.19 m, with the taper's
// compliance C = ∫dx/(E·b(x)) = L/(E·0.01 m)·ln(0.2/0.19) (each half tapers by 0.01 m over L/2);
// the energy a crack across the middle dissipates G_f × 0.19 m = 19 J/m; the elastic energy the
// bar holds at the peak ½·P²·C (9.3 J/m at L = 1 m).
#pragma once

#include <nlohmann/json.hpp>

namespace nmm::reference {

constexpr double kCohesiveBarYoung = 1e10;         ///< Pa, E
constexpr double kCohesiveBarTensile = 1e6;        ///< Pa, σt
constexpr double kCohesiveBarFractureEnergy = 100;  ///< J/m², G_f
constexpr double kCohesiveBarNeck = 0.19;          ///< m, the width at the middle: the crack's area per m

/// The bar (header) at mesh size `size` (m) and length `length` (m); scene document.
nlohmann::json cohesive_bar(double size, double length = 1.0);

/// m per N/m, the bar's elastic compliance end to end, ∫0^L dx/(E·b(x)).
double cohesive_bar_compliance(double length = 1.0);

}  // namespace nmm::reference
