// A wave crossing one joint: the run and its read-off (joint_wave.h).
#include "studies/joint_wave.h"

#include <algorithm>
#include <cmath>

#include "solver/stepping/time_stepper.h"

namespace nmm::studies {

JointWaveHistory run_joint_wave(const Mesh& mesh, const SceneDef& scene) {
  solve::TimeStepper st(mesh, scene, scene.name);
  return run_joint_wave(st, scene, [](std::int64_t) {});
}

JointWaveHistory run_joint_wave(solve::TimeStepper& st, const SceneDef& scene,
                                const std::function<void(std::int64_t)>& on_step) {
  JointWaveHistory h;
  auto sample = [&]() {
    h.time.push_back(st.view().state.time);
    h.before.push_back(st.view().state.measure[0].displacement()[0]);
    h.after.push_back(st.view().state.measure[1].displacement()[0]);
  };
  sample();
  const double t_end = static_cast<double>(scene.solver.steps) * scene.solver.time_step;
  h.outcome = st.run_until(t_end * (1 - 1e-12), [&](std::int64_t n) {
    sample();
    on_step(n);
  });
  return h;
}

JointWaveErrors joint_wave_errors(const reference::JointWaveSetup& s, const JointWaveHistory& h) {
  const reference::JointWaveClosedForm cf(s);
  JointWaveErrors e;
  auto rms = [&](double x, const std::vector<double>& u, double t1) {
    const double t0 = x / cf.speed();
    double sum = 0, peak = 0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < h.time.size(); ++k) {
      if (h.time[k] < t0 || h.time[k] > t1) continue;
      const double exact = cf.displacement(x, h.time[k]);
      sum += (u[k] - exact) * (u[k] - exact);
      peak = std::max(peak, std::abs(exact));
      ++n;
    }
    return n == 0 || peak == 0 ? std::nan("") : std::sqrt(sum / static_cast<double>(n)) / peak;
  };
  e.before_rms = rms(s.before_x, h.before, cf.valid_until(s.before_x));
  e.incident_rms = rms(s.before_x, h.before, (2 * s.joint_x - s.before_x) / cf.speed());
  e.after_rms = rms(s.after_x, h.after, cf.valid_until(s.after_x));

  const double t1 = cf.valid_until(s.after_x), half = 0.5 * cf.final_displacement();
  e.half_rise_exact = cf.half_rise_time(s.after_x);
  double rise = std::nan("");
  for (std::size_t k = 1; k < h.time.size() && h.time[k] <= t1; ++k) {
    const double v = (h.after[k] - h.after[k - 1]) / (h.time[k] - h.time[k - 1]);
    e.peak_velocity = std::max(e.peak_velocity, v);
    if (std::isnan(rise) && h.after[k] >= half)
      rise = h.time[k - 1] + (half - h.after[k - 1]) / (h.after[k] - h.after[k - 1]) *
                                 (h.time[k] - h.time[k - 1]);
  }
  e.half_rise = rise - e.half_rise_exact;
  e.peak_velocity_exact = cf.transmitted_peak() / cf.impedance();
  return e;
}

}  // namespace nmm::studies
