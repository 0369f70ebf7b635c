// The cantilever: scene and Timoshenko's tip deflection (cantilever.h has the equation).
#include "reference/cantilever.h"

#include <cmath>

namespace nmm::reference {

SceneDef beam(double length, double depth, double h) {
  SceneDef s;
  s.materials.push_back({"rock", 2500, kCantileverYoung, kCantileverPoisson, {}});
  BodyDef b;
  b.material = 0;
  b.outer = {{0, 0}, {length, 0}, {length, depth}, {0, depth}};
  s.bodies.push_back(b);
  s.mesh_size = h;
  s.plane = PlaneKind::stress;
  return s;
}

void clamp_left_end(SceneDef& s, double depth, double h) {
  const int n = static_cast<int>(std::ceil(depth / (0.5 * h)));
  for (int i = 0; i <= n; ++i) s.fixed_points.push_back({0, depth * i / n});
}

SceneDef cantilever(double h, int order) {
  const double L = kCantileverLength, H = kCantileverDepth, P = kCantileverLoad;
  SceneDef s = beam(L, H, h);
  s.solver.cover_order = order;
  clamp_left_end(s, H, h);
  s.loads.push_back({{L, H / 2}, {0, -P}});
  s.measure_points.push_back({L, H / 2});
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::equilibrium;  // a continuum held by fixed points: one step
  return s;
}

double timoshenko_tip_deflection() {
  const double L = kCantileverLength, H = kCantileverDepth, P = kCantileverLoad;
  const double E = kCantileverYoung, nu = kCantileverPoisson;
  const double I = H * H * H / 12, G = E / (2 * (1 + nu));
  return P * L * L * L / (3 * E * I) + P * L / (5.0 / 6.0 * G * H);
}

}  // namespace nmm::reference
