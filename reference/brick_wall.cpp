// The staggered brick wall (brick_wall.h).
#include "brick_wall.h"

#include <string>

#include "scene_pieces.h"

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

}  // namespace nmm::reference
