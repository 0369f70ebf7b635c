// The single-joint specimen's run and read-off (joint_specimen_run.h).
#include "joint_specimen_run.h"

#include <algorithm>

#include "time_stepper.h"

namespace nmm::studies {

JointSpecimenResult run_joint_specimen(const Mesh& mesh, const SceneDef& scene, double seconds) {
  solve::TimeStepper st(mesh, scene, "single joint");
  JointSpecimenResult r;
  r.status = st.run_until(seconds, [](std::int64_t) {});
  const auto a = st.displacement_at(st.measure_points()[0]);
  const auto b = st.displacement_at(st.measure_points()[1]);
  r.closure = b[1] - a[1];
  r.slip = a[0] - b[0];
  double n = 0;
  for (const solve::Contact& c : st.contacts().accepted())
    if (c.state != solve::ContactState::open) {
      n += c.normal_force;
      r.travel = std::max(r.travel, c.joint.travel);
    }
  r.normal_stress = n / 2.0;
  return r;
}

}  // namespace nmm::studies
