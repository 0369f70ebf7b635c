// Plates with a straight crack and the handbook closed forms of their stress intensity factors
// (docs/crack-tips.md): the scenes of tests/test_crack_tips.cpp and of nmm-study's fracture
// cases (docs/accuracy.md "Fracture").
//
// The plate [x0, x1] × [y0, y1] (plane strain, E 10 GPa, ν 0.25) has its crack p–q as a joint
// of constant springs (kn 1e12 Pa/m, ks 4e11 Pa/m, φ 30°) that opens freely in tension, is
// pulled by a traction σ = 1 MPa on its top and bottom and held statically determinately (a
// fixed point at the middle of its bottom, 0.01h above it; a roller on 0.5h of the bottom at
// the right corner); one static equilibrium step of 1 s.
//
// Closed forms (Tada, Paris & Irwin, The Stress Analysis of Cracks Handbook, 3rd ed.), K_I =
// σ√(πa)·F:
//   centre crack 2a in a strip of width 2W (2.1), α = a/W, within 0.1 % for any α:
//     F = (1 − 0.025α² + 0.06α⁴)·√sec(πα/2);
//   single edge crack a in a strip of width b (2.10), α = a/b, within 0.5 % for any α:
//     F = √(tan(πα/2)/(πα/2))·(0.752 + 2.02α + 0.37(1 − sin(πα/2))³)/cos(πα/2).
//
// The pulled plate (growth by toughness): the centre-cracked plate 2 × 4 m (a/W 0.5) whose top
// edge is a support moving up (held in x and y) and whose bottom is on rollers, the rock's
// toughness K_Ic and a strength it never reaches. The support moves `ramp` times its speed in
// the first 1 s step, then at its speed: the first step brings the mean σyy to about 90 % of
// σ_c = K_Ic/(√(πa)·F) at h = 0.05 m and v = 2 µm/s, each further step adds about 0.5 % of σ_c.
#pragma once

#include <nlohmann/json.hpp>

#include "common/vec2.h"

namespace nmm::reference {

constexpr double kCrackPlateYoung = 1e10;  ///< Pa, E of the cracked plates
constexpr double kCrackPlatePoisson = 0.25;  ///< –, ν
constexpr double kCrackPlateStress = 1e6;  ///< Pa, σ: the traction on the top and bottom

/// The plate [x0, x1] × [y0, y1] with the straight crack p–q, pulled by σ on its top and bottom,
/// mesh size h (m); scene document (header).
nlohmann::json crack_plate(double x0, double y0, double x1, double y1, Vec2 p, Vec2 q, double h);

/// –, Tada's F of a centre crack, α = a/W (W the half-width).
double tada_centre(double alpha);
/// –, Tada's F of a single edge crack, α = a/b (b the strip's width).
double tada_edge(double alpha);

/// The centre-cracked plate 2 × 4 m (a = 0.5 m) pulled by its top edge (header): mesh size h (m),
/// toughness k_ic (Pa·√m), the support's speed v (m/s) after a first step at ramp·v.
nlohmann::json pulled_crack_plate(double h, double k_ic, double v = 2e-6, double ramp = 210);

}  // namespace nmm::reference
