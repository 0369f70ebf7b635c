// Small scene pieces and reference problems shared by the contact tests and bench/ (the brick
// wall is built here for tests/test_static_analysis.cpp and the benchmarks).
#pragma once

#include <cmath>
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

/// Rock and one interface set for contact scenes: E = 10 GPa, ν = 0.25, ρ = 2650 kg/m³, DDA's
/// point penalty (model "penalty": the reference problems are DDA's, and their results are
/// compared with DDA codes at Shi's penalties) kn = 20·E·(1 m) = 2e11 N/m per contact point,
/// ks = kn/2.5, friction φ (degrees); mesh size h (m); gravity 9.81 m/s² down; Δt = 1e-3 s;
/// cover order `order`.
inline SceneDef interface_scene(double h, double friction_deg, int order = 0) {
  SceneDef s;
  s.materials.push_back({"rock", 2650, 1e10, 0.25});
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

/// Reference problem: the sliding block with the slope made by tilting gravity by α (degrees):
/// a 2 m × 1 m block placed touching a 12 m × 1 m base held along its bottom; it slides along +x
/// by ½g(sin α − cos α tan φ)t² when φ < α. Measure point 0: the block's centre (2, 1.5).
inline SceneDef sliding_block_tilted(double alpha_deg, double friction_deg, double h = 0.5,
                                     int order = 0) {
  SceneDef s = interface_scene(h, friction_deg, order);
  const double a = alpha_deg * 3.14159265358979323846 / 180;
  s.gravity = {9.81 * std::sin(a), -9.81 * std::cos(a)};
  s.bodies = {box(0, 0, 12, 1), box(1, 1, 3, 2)};
  s.fixed_points = held_along(0.1, 11.9, 0.1);
  s.measure_points = {{2, 1.5}};
  return s;
}

/// Reference problem: the sliding block on a real incline of α (degrees) cut by the mesh at an
/// angle (data/block_on_incline.json at α = 30°): a 2 m × 1 m block touching the incline, the
/// base held along its bottom. Measure point 0: the block's centre. Down the slope is
/// (−cos α, −sin α). `margin` > 0 (m): a compact base instead, the incline reaching `margin`
/// beyond the block on each side and standing 1 m above the base's held bottom at its low end
/// (the same incline line, so the mesh cuts it the same way).
inline SceneDef sliding_block_incline(double alpha_deg, double friction_deg, double h = 0.5,
                                      int order = 0, double margin = -1) {
  SceneDef s = interface_scene(h, friction_deg, order);
  const double a = alpha_deg * 3.14159265358979323846 / 180;
  const double c = std::cos(a), sn = std::sin(a), y0 = 0.144338;
  const Vec2 p0{10 * c, 10 * sn + y0}, p1{12 * c, 12 * sn + y0};
  BodyDef base;
  base.material = 0;
  base.outer = {{0, 0}, {19.9, 0}, {19.9, 19.9 * sn / c + y0}, p1, p0, {0, y0}};
  s.fixed_points = held_along(0.1, 19.8, 0.05);
  if (margin > 0) {
    const double xa = p0.x - margin * c, xb = p1.x + margin * c;
    const double ya = xa * sn / c + y0, yb = xb * sn / c + y0, y_bottom = ya - 1;
    base.outer = {{xa, y_bottom}, {xb, y_bottom}, {xb, yb}, p1, p0, {xa, ya}};
    s.fixed_points = held_along(xa + 0.1, xb - 0.1, y_bottom + 0.05);
  }
  BodyDef block;
  block.material = 0;
  block.outer = {p0, p1, {p1.x - sn, p1.y + c}, {p0.x - sn, p0.y + c}};
  s.bodies = {base, block};
  s.measure_points = {{0.5 * (p0.x + p1.x) - 0.5 * sn, 0.5 * (p0.y + p1.y) + 0.5 * c}};
  return s;
}

/// Reference problem: a staggered brick wall of n × n bricks (1 m × 0.5 m, odd rows shifted by
/// half a brick, every brick touching its neighbours) on a base 1 m thick held by fixed points
/// every 0.5 m along y = −0.9; E = 10 GPa, ν = 0.25, ρ = 2650 kg/m³; one interface set
/// (DDA's point penalty, model "penalty": kn = 20·E·1 m = 2e11 N/m per contact point, ks = kn/2.5,
/// φ = 35°: the wall is the DDA code's benchmark); mesh size 0.5 m; gravity; Δt = 1e-3 s.
/// `dynamic`: false gives the static (DDA) analysis.
inline SceneDef brick_wall(int n, bool dynamic) {
  SceneDef s;
  s.name = "brick wall " + std::to_string(n) + " x " + std::to_string(n);
  s.materials.push_back({"rock", 2650, 1e10, 0.25});
  JointSetDef js;
  js.name = "mortar";
  js.friction_deg = 35;
  js.normal.model = NormalModel::penalty;
  js.shear.model = ShearModel::penalty;
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
