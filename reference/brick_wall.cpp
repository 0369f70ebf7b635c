// The staggered brick wall (brick_wall.h).
#include "brick_wall.h"

#include <string>

#include "scene_pieces.h"

namespace nmm::reference {

SceneDef brick_wall(int n, bool dynamic) {
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

}  // namespace nmm::reference
