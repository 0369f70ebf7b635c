// The pictures of a run held in memory: see run_pictures.h.
#include "report/run_pictures.h"

#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "solver/reinforcement/bolt_readout.h"
#include "solver/stepping/fracture_effect.h"

namespace nmm::report {

ReportFiles write_run_pictures(const solve::RunView& run, const SceneDef& scene, const Outcome& outcome,
                               const std::string& dir, double exaggerate, PictureField field) {
  PictureState state;
  state.time = run.state.time;
  state.status = outcome.status();
  state.stop = outcome.code;
  state.loop_xy = &run.state.loop_xy;
  const std::vector<double> mean_stress = solve::mean_stress(run);  // [3·me] at any order
  state.stress = &mean_stress;
  for (const solve::Contact& c : run.contacts.contacts())
    if (c.state != solve::ContactState::open)
      state.contacts.push_back({run.state.loop_xy[2 * c.at.vertex], run.state.loop_xy[2 * c.at.vertex + 1],
                                static_cast<int>(c.state), c.at.vertex, c.at.edge});
  for (const solve::TrackedPoint& p : run.state.measure) {
    state.measure_points.push_back({p.x, p.y});
    // x − (x − x0): what nmm-report computes from history.csv (x, ux), so its redraw of an
    // exaggerated picture is this one byte for byte.
    state.measure_start.push_back({p.x - (p.x - p.x0), p.y - (p.y - p.y0)});
  }
  state.exaggeration = exaggerate;
  for (std::size_t b = 0; b < run.state.bolts.size(); ++b) {
    PictureBolt pb;
    pb.broken = run.state.bolts[b].broken != 0;
    for (const solve::BoltReading& r : solve::bolt_readout(scene.bolts[b], run.state.bolts[b])) {
      pb.points.push_back({r.x, r.y});
      pb.start.push_back({r.x - r.ux, r.y - r.uy});  // as nmm-report computes it from bolts.csv
      pb.axial.push_back(r.axial);
    }
    state.bolts.push_back(std::move(pb));
  }
  state.excavated_body = run.state.body_removed;
  // The flow network as the frame's part "flow" holds it (the effects' frame_parts), so that
  // nmm-report's redraw from frames/flow_<step>.vtu is this picture byte for byte.
  if (field == PictureField::pressure) {
    solve::OutputTables unused;
    const solve::OutputStep out{0, run.state.time, run.mesh, run.state, unused, run.model, run.space, run.effects};
    std::vector<solve::FramePart> parts;
    for (const solve::Effect* e : run.effects) e->frame_parts(out, parts);
    for (const solve::FramePart& part : parts)
      if (part.name == "flow") state.flow = flow_segments_of(part.grid);
    if (parts.empty())
      throw InputError("--picture-field", "", "pressure: the run has no flow (no \"flow\" block in its scene)");
  }
  // A cracked run: its mesh has the cracks as joints after the scene's, and its scene with them.
  const std::vector<solve::CrackSegment>& cracks = fracture_of(run).segments();
  if (!cracks.empty()) {
    state.joint_crack.assign(scene.joints.size(), 0);
    for (const solve::CrackSegment& c : cracks) state.joint_crack.push_back(c.mode == solve::CrackMode::tensile ? 1 : 2);
  }
  write_file_atomically(dir + "/result.svg", result_svg(run.mesh, cracks.empty() ? scene : run.model.scene(), state, field));
  return make_run_report(dir);
}

}  // namespace nmm::report
