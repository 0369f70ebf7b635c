// The staggered brick wall (brick_wall.h).
#include "reference/brick_wall.h"

#include <string>

#include "reference/scene_pieces.h"

namespace nmm::reference {

SceneDef brick_wall(int n, bool dynamic) {
  // The contact problems' rock and interface (DDA's point penalty), φ = 35°, h = 0.5 m.
  SceneDef s = interface_scene(0.5, 35);
  s.name = "brick wall " + std::to_string(n) + " x " + std::to_string(n);
  s.joint_sets[0].name = "mortar";
  s.bodies.push_back(box(-1, -1, n + 1.5, 0));
  for (double x = -0.9; x < n + 1.4; x += 0.5) s.fixed_points.push_back({x, -0.9});
  for (int row = 0; row < n; ++row) {
    const double shift = (row % 2) ? 0.5 : 0.0;
    for (int i = 0; i < n; ++i)
      s.bodies.push_back(box(i + shift, 0.5 * row, i + shift + 1, 0.5 * row + 0.5));
  }
  s.solver.dynamic = dynamic;
  return s;
}

SceneDef peer_wall(int nx, int ny, bool dynamic, double h) {
  // The contact problems' scene pieces with the DDA code's rock and penalty: E = 10 MPa,
  // ρ = 2500 kg/m³, kn = 50·E·(1 m), ks = kn/2.5, φ = 30°.
  const double e = 1e7;
  SceneDef s = interface_scene(h, 30);
  s.name = "peer wall " + std::to_string(nx) + " x " + std::to_string(ny);
  s.materials[0] = {"rock", 2500, e, 0.25, {}};
  s.joint_sets[0].name = "mortar";
  s.joint_sets[0].normal.kn = 50 * e;
  s.joint_sets[0].shear.ks = 50 * e / 2.5;
  s.bodies.push_back(box(-1, -1, nx + 1, 0));
  s.fixed_points = {{-0.5, -0.5}, {0.5 * nx, -0.5}, {nx + 0.5, -0.5}};
  for (int row = 0; row < ny; ++row) {
    const double y0 = 0.5 * row, y1 = y0 + 0.5;
    double x = 0;
    if (row % 2) {
      s.bodies.push_back(box(0, y0, 0.5, y1));
      x = 0.5;
    }
    for (; x + 1 <= nx + 1e-9; x += 1) s.bodies.push_back(box(x, y0, x + 1, y1));
    if (x < nx - 1e-9) s.bodies.push_back(box(x, y0, nx, y1));
  }
  s.solver.dynamic = dynamic;
  return s;
}

}  // namespace nmm::reference
