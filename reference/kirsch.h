// The Kirsch opening, the rock-engineering reference problem (docs/physics.md §5; Brady & Brown,
// "Rock Mechanics for Underground Mining", §7.2): a circular opening of radius a excavated in
// elastic rock under far-field compression p_x, p_y: the scene and the closed form. Used by
// tests/test_rock_setups.cpp (excavation against Kirsch at each cover order) and nmm-study (the
// order axis on the accuracy-against-time chart, docs/accuracy.md); studies/kirsch_opening.h
// reads a solved model's wall against it.
//
// Closed form (compression positive, θ from x, P = (p_x + p_y)/2, Q = (p_x − p_y)/2):
//   σr  = P(1 − a²/r²) + Q(1 − 4a²/r² + 3a⁴/r⁴)cos2θ
//   σθ  = P(1 + a²/r²) − Q(1 + 3a⁴/r⁴)cos2θ
//   τrθ = −Q(1 + 2a²/r² − 3a⁴/r⁴)sin2θ
// and the inward displacement the excavation causes (plane strain, shear modulus G)
//   u_r = a²/(4Gr)·[(p_x + p_y) + (p_x − p_y)(4(1 − ν) − a²/r²)cos2θ].
// At the wall σθ(a, θ) = 2P − 4Q·cos2θ: 3p_y − p_x at the side wall (θ = 0), 3p_x − p_y at the
// crown (θ = 90°).
//
// The model: a = 1 m, p_y = 10 MPa, p_x = K0·p_y, E = 10 GPa, ν = 0.25, plane strain; a quarter
// model (rollers on the symmetry lines x = 0 and y = 0) with outer sides at b from the centre
// loaded by the in-situ traction; the opening's wall a polygon of 48 sides per quarter. The core
// is a second body touching the rock along the wall (the interface set, as data/tunnel.json
// has it), excavated at the start of a static equilibrium run and released at once (one step
// K d = F gives the elastic answer). Without the core (`with_core` false) the rock is a single
// body with a free opening under the same initial stress: the same K d = F, without contacts.
#pragma once

#include "common/scene.h"

namespace nmm::reference {

struct KirschSetup {
  double h = 0.2;          ///< m, mesh size
  double k0 = 1;           ///< –, p_x / p_y
  double b_over_a = 20;    ///< –, outer sides of the quarter model at b = (b/a)·a
  int order = 0;           ///< cover order n (solver.cover_order)
  bool with_core = true;   ///< the core as a second body, excavated (else a free opening)
};

constexpr double kKirschRadius = 1;      ///< m, a
constexpr double kKirschPressure = 10e6;  ///< Pa, p_y (compression)
constexpr double kKirschYoung = 1e10;     ///< Pa
constexpr double kKirschPoisson = 0.25;   ///< –

/// The scene (static equilibrium, one step; body 0 the rock, body 1 the core if any).
SceneDef kirsch_scene(const KirschSetup& k);

/// Kirsch's hoop stress (Pa, compression positive) at (r, θ) for far-field p_x, p_y.
double kirsch_hoop(double px, double py, double r, double theta);
/// Kirsch's inward radial displacement (m) at (r, θ), plane strain with G and ν.
double kirsch_radial_displacement(double px, double py, double g, double nu, double r, double theta);

}  // namespace nmm::reference
