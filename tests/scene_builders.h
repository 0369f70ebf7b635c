// Small scene pieces and reference problems shared by the contact tests and bench/ (the brick
// wall is built here for tests/test_static_analysis.cpp and the benchmarks).
#pragma once

#include <string>
#include <vector>

#include "scene.h"

namespace nmm::test {

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

/// Reference problem: a staggered brick wall of n × n bricks (1 m × 0.5 m, odd rows shifted by
/// half a brick, every brick touching its neighbours) on a base 1 m thick held by fixed points
/// every 0.5 m along y = −0.9; E = 10 GPa, ν = 0.25, ρ = 2650 kg/m³; one interface set
/// (penalty kn = 20·E·1 m = 2e11 N/m, ks = kn/2.5, φ = 35°); mesh size 0.5 m; gravity; Δt = 1e-3 s.
/// `dynamic`: false gives the static (DDA) analysis.
inline SceneDef brick_wall(int n, bool dynamic) {
  SceneDef s;
  s.name = "brick wall " + std::to_string(n) + " x " + std::to_string(n);
  s.materials.push_back({"rock", 2650, 1e10, 0.25});
  JointSetDef js;
  js.name = "mortar";
  js.friction_deg = 35;
  js.normal.kn = 2e11;
  js.shear.ks = 8e10;
  s.joint_sets.push_back(js);
  s.interface_set = 0;
  s.mesh_size = 0.5;
  s.has_gravity = true;
  s.gravity = {0, -9.81};
  s.bodies.push_back(box(-1, -1, n + 1.5, 0));
  for (double x = -0.9; x < n + 1.4; x += 0.5) s.fixed_points.push_back({x, -0.9});
  for (int row = 0; row < n; ++row) {
    const double shift = (row % 2) ? 0.5 : 0.0;
    for (int i = 0; i < n; ++i)
      s.bodies.push_back(box(i + shift, 0.5 * row, i + shift + 1, 0.5 * row + 0.5));
  }
  s.solver.time_step = 1e-3;
  s.solver.dynamic = dynamic;
  return s;
}

}  // namespace nmm::test
