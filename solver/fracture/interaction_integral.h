// Stress intensity factors at a crack tip by the interaction integral in its domain form
// (docs/crack-tips.md; the equations are at the top of interaction_integral.cpp).
//
// The field is the run's: each manifold element's stress and displacement gradient, integrated
// over the elements of a ring around the tip where the weight q falls from 1 (mesh nodes within
// the radius) to 0 (nodes beyond it). The auxiliary fields are Williams' leading terms of a
// straight crack in a homogeneous body; the crack's faces inside the ring are taken as free of
// traction unless the caller names the faces that carry it (closed contacts: their traction,
// that of the element beside them, adds the faces' term; a fluid's pressure in an open crack).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "common/vec2.h"

namespace nmm::solve {

/// Elastic constants as the crack-tip fields need them.
struct TipElasticity {
  double shear_modulus = 0;  ///< Pa, μ = E/(2(1 + ν))
  double kolosov = 0;        ///< –, κ: 3 − 4ν (plane strain), (3 − ν)/(1 + ν) (plane stress)
  double e_prime = 0;        ///< Pa, E' = E/(1 − ν²) (plane strain), E (plane stress)
  double young = 0;          ///< Pa
  double poisson = 0;        ///< –
  bool plane_strain = true;
};
TipElasticity tip_elasticity(const MaterialDef& m, PlaneKind plane);

/// Williams' field of a unit K (1 Pa·√m) in mode I or II at (r, θ) of the tip's frame (x1 along
/// the crack ahead of the tip, x2 to its left; θ in (−π, π], the faces at ±π): the displacement
/// gradient ∂u_i/∂x_j (m/m, [i][j]) and the stress σ11, σ22, σ12 (Pa) from it through D.
struct TipField {
  std::array<std::array<double, 2>, 2> grad{};  ///< ∂u_i/∂x_j
  std::array<double, 3> stress{};                ///< Pa: σ11, σ22, σ12
  std::array<double, 2> u{};                     ///< m, the displacement (for tests)
};
TipField williams_field(const TipElasticity& el, int mode, double r, double theta);

/// The tip and where its domain integral reaches.
struct TipDomain {
  Vec2 tip;             ///< m, as cut (the mesh's reference configuration)
  Vec2 direction;       ///< unit: the crack's direction at the tip, pointing ahead of it
  double radius = 0;    ///< m, q = 1 at the mesh nodes nearer the tip than this, 0 beyond
  std::int32_t body = -1;  ///< the body whose elements the integral runs over
  /// m, the crack from the tip backwards (CrackTip::behind; null or one point: straight behind
  /// the tip). Where it turns away from the line behind the tip inside the ring, the auxiliary
  /// fields take their cut along it rather than along that line, and its faces there add the
  /// terms of faces that do not lie on the line (interaction_integral.cpp).
  const std::vector<Vec2>* behind = nullptr;
};

/// K_I, K_II (Pa·√m; K_I > 0 opens the crack) of the field given by each element's stress
/// `stress` ([3·me] Pa, σxx σyy τxy) and displacement since the start (`loop_u` [2·v] m per loop
/// vertex: its gradient is fitted over the element's loop, exact at cover order 0); elements
/// with `skip` [me] 1 (excavated, debris; may be empty) are left out. `near`: the elements that
/// may reach within the radius of the tip (null: all of them are looked at). `loaded` [v] 1: the
/// loop edge v → next is a crack face that carries traction (a closed contact on it), t = σ·n of
/// its element (null: every face is free). `face_pressure` [2·v] Pa: the fluid pressure at the start
/// and end of each open crack face edge v → next (flow_network.h face_pressures; null or 0: none),
/// a traction −p·n on that face.
struct StressIntensity {
  double k1 = 0;  ///< Pa·√m
  double k2 = 0;  ///< Pa·√m
  int elements = 0;  ///< elements in the ring (where q varies)
  Vec2 tip_u;        ///< m, the displacement of the loop vertex at the tip (nearest it within the radius)
};
StressIntensity interaction_integral(const Mesh& mesh, const TipDomain& domain, const TipElasticity& el,
                                     const std::vector<double>& stress, const std::vector<double>& loop_u,
                                     const std::vector<std::uint8_t>& skip,
                                     const std::vector<std::int32_t>* near = nullptr,
                                     const std::vector<std::uint8_t>* loaded = nullptr,
                                     const std::vector<double>* face_pressure = nullptr);

/// rad, the direction of maximum tangential stress (Erdogan & Sih 1963) from the crack's own
/// direction: θ = 2·atan((K_I − √(K_I² + 8K_II²))/(4K_II)), 0 for K_II = 0.
double mts_angle(double k1, double k2);

}  // namespace nmm::solve
