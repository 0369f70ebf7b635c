// The displacement-controlled direct shear run and read-off (direct_shear_run.h).
#include "studies/direct_shear_run.h"

#include <cmath>

#include "solver/stepping/time_stepper.h"

namespace nmm::studies {

namespace {
DirectShearSample read(const solve::TimeStepper& st) {
  DirectShearSample r;
  r.time = st.view().state.time;
  const auto a = st.view().state.measure[0].displacement();
  const auto b = st.view().state.measure[1].displacement();
  r.closure = b[1] - a[1];
  r.slip = a[0] - b[0];
  double n = 0, t = 0, travel = 0, gap_length = 0, length = 0;
  int closed = 0;
  for (const solve::Contact& c : st.view().contacts.accepted())
    if (c.state != solve::ContactState::open) {
      n += c.normal_force;
      t += c.shear_force;
      travel += c.joint.travel;
      ++closed;
      // The gap is net of the dilation at the start of the step (contact.h): the faces stand
      // apart by that more.
      gap_length += c.length * (c.gap + c.joint.dilation - c.dilation_step);
      length += c.length;
    }
  r.face_gap = length > 0 ? gap_length / length : 0;
  // The specimen's faces are 2 m long; the upper one overhangs by the slip, and the tributary
  // lengths cover only the overlap (docs/contact.md), so the stresses are over that.
  const double overlap = 2.0 - std::abs(r.slip);
  r.shear_stress = std::abs(t) / overlap;
  r.normal_stress = n / overlap;
  r.travel = closed > 0 ? travel / closed : 0;
  return r;
}
}  // namespace

DirectShearRun run_direct_shear(const Mesh& mesh, const SceneDef& scene, int steps, int every) {
  solve::TimeStepper st(mesh, scene, "direct shear");
  DirectShearRun run;
  run.samples.push_back(read(st));
  const double dt = scene.solver.time_step;
  for (int n = every; n <= steps; n += every) {
    run.outcome = st.run_until(n * dt, [](std::int64_t) {});
    if (!run.outcome.ok()) return run;
    run.samples.push_back(read(st));
  }
  return run;
}

}  // namespace nmm::studies
