// The staggered brick wall exactly as the DDA peer (ntdda) is given it by its wall generator, so
// nmm and the DDA code are timed on one problem (docs/performance.md "Against a DDA code"):
//   a rectangle nx m × ny·0.5 m cut by bed joints every 0.5 m and head joints every 1 m, odd rows
//   offset by half a brick (so they end in two half bricks): nx·ny + ⌊ny/2⌋ blocks;
//   on a base block (−1, −1)–(nx + 1, 0) held by three fixed points at y = −0.5
//   (x = −0.5, nx/2, nx + 0.5);
//   E = 10 MPa, ν = 0.25, ρ = 2500 kg/m³, gravity 9.81 m/s²;
//   DDA's point penalty: kn = 50·E·(1 m) = 5e8 N/m per contact point, ks = kn/2.5, φ = 30°, no
//   cohesion or tension; Δt = 1e-3 s; mesh size 0.5 m (about 22 unknowns per brick, DDA: 6).
#pragma once

#include <string>

#include "scene.h"

namespace nmm::bench {

inline SceneDef peer_wall(int nx, int ny, bool dynamic) {
  SceneDef s;
  s.name = "peer wall " + std::to_string(nx) + " x " + std::to_string(ny);
  const double e = 1e7;
  s.materials.push_back({"rock", 2500, e, 0.25});
  JointSetDef js;
  js.name = "mortar";
  js.friction_deg = 30;
  js.normal.model = NormalModel::penalty;
  js.shear.model = ShearModel::penalty;
  js.normal.kn = 50 * e;
  js.shear.ks = 50 * e / 2.5;
  s.joint_sets.push_back(js);
  s.interface_set = 0;
  s.mesh_size = 0.5;
  s.has_gravity = true;
  s.gravity = {0, -9.81};
  const auto box = [](double x0, double y0, double x1, double y1) {
    BodyDef b;
    b.material = 0;
    b.outer = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    return b;
  };
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
  s.solver.time_step = 1e-3;
  s.solver.dynamic = dynamic;
  return s;
}

}  // namespace nmm::bench
