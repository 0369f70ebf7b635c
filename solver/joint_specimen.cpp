#include "joint_specimen.h"

#include <algorithm>

#include "time_stepper.h"

namespace nmm::solve {

SceneDef joint_specimen_scene(const JointSetDef& joint, double young, double h) {
  SceneDef s;
  s.materials.push_back({"rock", 2650, young, 0.25});
  s.joint_sets.push_back(joint);
  s.interface_set = 0;
  s.mesh_size = h;
  s.plane = PlaneKind::stress;
  BodyDef base, top;
  base.material = top.material = 0;
  base.outer = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  top.outer = {{0, 1}, {2, 1}, {2, 2}, {0, 2}};
  s.bodies = {base, top};
  for (double x = 0.05; x < 2; x += 0.1) s.fixed_points.push_back({x, 0.02});
  s.measure_points = {{1.0, 1.0001}, {1.0, 0.9999}};
  s.solver.time_step = 1e-3;
  s.solver.dynamic_factor = 0;  // quasi-static: settles to equilibrium
  s.solver.max_displacement_ratio = 0.01;
  return s;
}

void load_joint_specimen(SceneDef& s, double sigma_n, double tau) {
  s.loads.clear();
  const int n = 20;
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 0.5 : 1.0;
    s.loads.push_back({{2.0 * i / n, 2.0}, {0, -sigma_n * 2.0 / n * w}});
  }
  if (tau != 0)
    for (int i = 0; i < 10; ++i) s.loads.push_back({{0.1 + 0.2 * i, 1.02}, {tau * 2.0 / 10, 0}});
}

JointSpecimenResult run_joint_specimen(const Mesh& mesh, const SceneDef& scene, double seconds) {
  TimeStepper st(mesh, scene, "single joint");
  JointSpecimenResult r;
  r.status = st.run_until(seconds, [](std::int64_t) {});
  const auto a = st.displacement_at(st.measure_points()[0]);
  const auto b = st.displacement_at(st.measure_points()[1]);
  r.closure = b[1] - a[1];
  r.slip = a[0] - b[0];
  double n = 0;
  for (const Contact& c : st.contacts().accepted())
    if (c.state != ContactState::open) {
      n += c.normal_force;
      r.travel = std::max(r.travel, c.joint.travel);
    }
  r.normal_stress = n / 2.0;
  return r;
}

}  // namespace nmm::solve
