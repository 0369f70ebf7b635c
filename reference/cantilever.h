// The cantilever, the continuum's reference problem: a beam of length L and depth H clamped at
// x = 0, loaded by P at its free end's mid-depth. Timoshenko's tip deflection (bending plus
// shear, shear coefficient κ = 5/6 for a rectangle; Timoshenko & Goodier, Theory of Elasticity):
//   δ = P L³ / (3 E I) + P L / (κ G H),   I = H³/12,  G = E / (2(1 + ν))
// Constant-strain elements approach it from below as the mesh is refined
// (tests/test_solver_physics.cpp; nmm-study's mesh-size and cover-order sweeps, docs/accuracy.md).
#pragma once

#include "common/scene.h"

namespace nmm::reference {

/// The problem's numbers: L = 10 m, H = 1 m, P = 1e5 N (per m of thickness), E = 10 GPa,
/// ν = 0.25, ρ = 2500 kg/m³, plane stress.
constexpr double kCantileverLength = 10;     ///< m, L
constexpr double kCantileverDepth = 1;       ///< m, H
constexpr double kCantileverLoad = 1e5;      ///< N/m, P (down)
constexpr double kCantileverYoung = 1e10;    ///< Pa, E
constexpr double kCantileverPoisson = 0.25;  ///< –, ν

/// A beam of length L and depth H (m) along x from the origin, at mesh size h (m): the rock
/// (ρ = 2500 kg/m³, E = 10 GPa, ν = 0.25), plane stress; no supports, loads or settings.
SceneDef beam(double length, double depth, double h);

/// Clamps the beam's end x = 0 by fixed points every h/2 over its depth H.
void clamp_left_end(SceneDef& s, double depth, double h);

/// The scene at mesh size h (m) and cover order `order`: clamped by fixed points every h/2
/// along x = 0, P down at (L, H/2), measure point 0 there; static equilibrium (K d = F, one
/// step of 1 s gives the elastic answer).
SceneDef cantilever(double h, int order = 0);

/// m, Timoshenko's tip deflection δ above for the problem's numbers (downwards positive).
double timoshenko_tip_deflection();

}  // namespace nmm::reference
