// The sliding block: scenes and closed form (sliding_block.h has the equation).
#include "reference/sliding_block.h"

#include <cmath>

#include "common/math_constants.h"
#include "reference/scene_pieces.h"

namespace nmm::reference {

namespace {
constexpr double kG = 9.81;  // m/s²
}  // namespace

double sliding_distance(double alpha_deg, double friction_deg, double t) {
  const double alpha = alpha_deg * kPi / 180, phi = friction_deg * kPi / 180;
  if (friction_deg >= alpha_deg) return 0;
  return 0.5 * kG * (std::sin(alpha) - std::cos(alpha) * std::tan(phi)) * t * t;
}

SceneDef sliding_block_tilted(double alpha_deg, double friction_deg, double h, int order,
                              double dt, double kn_over_e) {
  SceneDef s = interface_scene(h, friction_deg, order);
  const double a = alpha_deg * kPi / 180;
  s.gravity = {kG * std::sin(a), -kG * std::cos(a)};
  // Shi's multiples of E, as DDA codes state them (20·E: interface_scene's 2e11 N/m).
  const double young = s.materials[0].young;
  s.joint_sets[0].normal.kn = kn_over_e * young;
  s.joint_sets[0].shear.ks = kn_over_e * young / 2.5;
  s.solver.time_step = dt;
  s.bodies = {box(0, 0, 12, 1), box(1, 1, 3, 2)};
  s.fixed_points = held_along(0.1, 11.9, 0.1);
  s.measure_points = {{2, 1.5}};
  return s;
}

SceneDef sliding_block_incline(double alpha_deg, double friction_deg, double h, int order,
                               double margin) {
  SceneDef s = interface_scene(h, friction_deg, order);
  const double a = alpha_deg * kPi / 180;
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

}  // namespace nmm::reference
