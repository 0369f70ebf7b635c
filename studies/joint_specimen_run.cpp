// The single-joint specimen's run and read-off (joint_specimen_run.h).
#include "studies/joint_specimen_run.h"

#include <algorithm>

#include "solver/stepping/time_stepper.h"

namespace nmm::studies {

JointSpecimenResult run_joint_specimen(const Mesh& mesh, const SceneDef& scene, double seconds) {
  solve::TimeStepper st(mesh, scene, "single joint");
  JointSpecimenResult r;
  r.outcome = st.run_until(seconds, [](std::int64_t) {});
  const auto a = st.view().state.measure[0].displacement();
  const auto b = st.view().state.measure[1].displacement();
  r.closure = b[1] - a[1];
  r.slip = a[0] - b[0];
  double n = 0;
  for (const solve::Contact& c : st.view().contacts.accepted())
    if (c.state != solve::ContactState::open) {
      n += c.normal_force;
      r.travel = std::max(r.travel, c.joint.travel);
    }
  r.normal_stress = n / 2.0;
  return r;
}

std::vector<double> run_closure_cycles(const Mesh& mesh, SceneDef scene,
                                       const std::vector<double>& targets, Outcome* outcome) {
  const double top = *std::max_element(targets.begin(), targets.end());
  TimeTable cycles;
  cycles.time = {0};
  cycles.value = {0};
  for (std::size_t k = 0; k < targets.size(); ++k) {
    cycles.time.insert(cycles.time.end(), {0.15 * static_cast<double>(k) + 0.05, 0.15 * static_cast<double>(k) + 0.15});
    cycles.value.insert(cycles.value.end(), {targets[k] / top, targets[k] / top});
  }
  scene.load_tables.assign(scene.loads.size(), cycles);
  solve::TimeStepper st(mesh, scene, "closure cycles");
  std::vector<double> closure;
  for (std::size_t k = 0; k < targets.size(); ++k) {
    *outcome = st.run_until(0.15 * static_cast<double>(k) + 0.15, [](std::int64_t) {});
    if (!outcome->ok()) return {};
    const auto a = st.view().state.measure[0].displacement();
    const auto b = st.view().state.measure[1].displacement();
    closure.push_back(b[1] - a[1]);
  }
  return closure;
}

}  // namespace nmm::studies
