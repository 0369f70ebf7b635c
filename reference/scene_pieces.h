// Small scene pieces the reference problems are built from (and tests that build their own
// variants of them): a rectangular body, a base held like a rigid foundation, the rock and
// interface set of the contact problems.
#pragma once

#include <vector>

#include "common/scene.h"

namespace nmm::reference {

/// Axis-aligned rectangular body of material 0, m.
inline BodyDef box(double x0, double y0, double x1, double y1) {
  BodyDef b;
  b.material = 0;
  b.outer = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  return b;
}

/// Fixed points every 0.25 m along y = y0 from x0 to x1: a base held like a rigid foundation.
inline std::vector<Vec2> held_along(double x0, double x1, double y0) {
  std::vector<Vec2> p;
  for (double x = x0; x <= x1 + 1e-9; x += 0.25) p.push_back({x, y0});
  return p;
}

/// Rock and one interface set for contact scenes: E = 10 GPa, ν = 0.25, ρ = 2650 kg/m³, DDA's
/// point penalty (model "penalty": the reference problems are DDA's, and their results are
/// compared with DDA codes at Shi's penalties) kn = 20·E·(1 m) = 2e11 N/m per contact point,
/// ks = kn/2.5, friction φ (degrees); mesh size h (m); gravity 9.81 m/s² down; Δt = 1e-3 s;
/// cover order `order`.
inline SceneDef interface_scene(double h, double friction_deg, int order = 0) {
  SceneDef s;
  s.materials.push_back({"rock", 2650, 1e10, 0.25, {}});
  JointSetDef js;
  js.name = "interface";
  js.friction_deg = friction_deg;
  js.normal.model = NormalModel::penalty;
  js.shear.model = ShearModel::penalty;
  js.normal.kn = 2e11;
  js.shear.ks = 8e10;
  s.joint_sets.push_back(js);
  s.interface_set = 0;
  s.mesh_size = h;
  s.has_gravity = true;
  s.gravity = {0, -9.81};
  s.solver.time_step = 1e-3;
  s.solver.cover_order = order;
  return s;
}

}  // namespace nmm::reference
