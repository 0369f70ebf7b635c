#include "joint_specimen.h"

#include "time_stepper.h"

namespace nmm::solve {

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
  return r;
}

}  // namespace nmm::solve
