// summary.json of a run: see run_summary.h.
#include "solver/output/run_summary.h"

#include <algorithm>
#include <cmath>

#include "nmm_version.h"
#include "solver/contact/cohesive_law.h"
#include "solver/discretisation/blas_info.h"

namespace nmm::solve {

namespace {
// Cohesive softening (docs/fracture.md "Snap-back"): Hillerborg's length l_ch = E·G_f/σt² of the
// rock that softens (the smallest), the longest body of it (the larger side of its outer
// boundary's bounding box), whether that is longer than 2·l_ch — a bar that long snaps back
// after its peak when pulled — and what the run measured: accepted steps in which a face's
// damage grew by w_c/4 or more at once (the static path could not follow the softening), and
// attempts cut because a softening crack found no balance.
nlohmann::json snap_back(const RunView& st) {
  const SceneDef& scene = st.model.scene();
  double lch = 0, longest = 0;
  for (const BodyDef& b : scene.bodies) {
    const MaterialDef& m = scene.materials[static_cast<std::size_t>(b.material)];
    const double l = characteristic_length(m.young, m.strength);
    if (!(l > 0) || b.outer.empty()) continue;
    if (lch == 0 || l < lch) lch = l;
    double x0 = b.outer[0].x, x1 = x0, y0 = b.outer[0].y, y1 = y0;
    for (const Vec2& p : b.outer) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    longest = std::max({longest, x1 - x0, y1 - y0});
  }
  return {{"characteristic_length_m", lch},
          {"longest_body_m", longest},
          {"snap_back_possible", lch > 0 && longest > 2 * lch},
          {"snap_back_steps", st.contact_solve.snap_back_steps},
          {"snap_back_cuts", st.contact_solve.cohesive_unsettled}};
}
}  // namespace

nlohmann::json run_summary(const RunView& st, const RunRecord& o) {
  const SolverDef& sv = st.model.scene().solver;
  const RunState& s = st.state;
  StepTimings t = st.timings;
  t.output = o.output_seconds;
  nlohmann::json summary;
  summary["status"] = o.outcome.status();
  // The same, as a stable code to branch on (common/outcome.h), and when it happened.
  summary["stop_code"] = stop_code_name(o.outcome.code);
  summary["stop_time"] = o.outcome.time;
  // Why the run ended: all its steps, solver.stop_at_ratio met, an interrupt, or an error
  // (status then says which).
  summary["stopped_by"] = o.outcome.code == StopCode::interrupted ? "interrupt"
                          : o.outcome.failed()                    ? "error"
                          : st.stopped_at_ratio                   ? "stop_at_ratio"
                                                                  : "steps";
  summary["equilibrium"] = equilibrium_verdict(st.equilibrium, sv.dynamic);
  if (sv.stop_at_ratio > 0) summary["equilibrium"]["stop_at_ratio"] = sv.stop_at_ratio;
  summary["steps_completed"] = o.done;
  summary["first_step"] = o.first_step;  // steps before this run (a restart from a checkpoint)
  summary["step"] = s.step;      // steps since step 0 of the first run
  summary["state_hash"] = state_hash(st);
  summary["simulated_time"] = s.time;
  summary["wall_seconds"] = o.wall_seconds;
  summary["effects"] = run_effects(st);
  // Bodies removed by excavation so far (cumulative across restarts) and the step each went:
  // nmm-report leaves them out of a redrawn frame as nmm-solve --pictures does.
  summary["excavated_bodies"] = nlohmann::json::array();
  for (std::size_t b = 0; b < s.body_removed.size(); ++b)
    if (s.body_removed[b])
      summary["excavated_bodies"].push_back({{"body", b}, {"step", s.body_removed_at[b]}});
  // The effects' own parts (effect_output.h summarise: the bolts').
  for (const Effect* e : st.effects) e->summarise(s, summary);
  for (const MeshChange* c : st.changes) c->summarise(s, summary);
  summary["analysis"] = sv.dynamic                                ? "dynamic"
                        : sv.static_mode == StaticMode::dda ? "static_dda"
                                                                       : "static_equilibrium";
  summary["open_close_iterations"] = s.iterations;
  summary["time_step_cuts"] = s.cuts;
  summary["steps_with_unsettled_friction"] = s.friction_unsettled;
  summary["max_penetration"] = s.max_penetration;
  summary["matrix"] = {{"unknowns", st.space.unknowns()},
                       {"nonzeros_lower", st.system.nonzeros()},
                       {"factor_nonzeros", st.system.factor_nonzeros()},
                       {"factor_flops", st.system.factor_flops()},
                       {"ordering", st.system.ordering()},
                       {"factorisations", t.factorisations}};
  summary["timings"] = {{"contact_detection", t.contact_detection},
                        {"assembly", t.assembly},
                        {"factorisation", t.factorisation},
                        {"solves", t.solves},
                        {"geometry_update", t.geometry_update},
                        {"output", t.output},
                        {"fracture", t.fracture}};
  summary["unknowns"] = st.space.unknowns();
  summary["threads"] = st.threads;
  summary["physical_covers"] = st.mesh.cover_count();
  summary["tied_sliver_covers"] = st.space.ties().tied;
  summary["cover_order"] = st.space.order();
  summary["dofs_per_cover"] = st.space.dofs_per_cover();
  summary["manifold_elements"] = st.mesh.element_count();
  summary["symbolic_analyses"] = st.system.analyses();
  summary["time_step"] = sv.time_step;
  summary["max_step_displacement"] = s.max_step_displacement;
  summary["fixed_point_stiffness"] = st.model.fixed_point_stiffness();
  if (!st.model.scene().supports.empty()) summary["support_stiffness"] = st.model.support_stiffness();
  if (st.fracture.active()) {
    // Intact rock that breaks (docs/fracture.md): the cracks so far.
    const std::vector<CrackSegment>& cracks = st.fracture.segments();
    double length = 0;
    long tensile = 0;
    for (const CrackSegment& c : cracks) {
      length += std::hypot(c.b.x - c.a.x, c.b.y - c.a.y);
      tensile += c.mode == CrackMode::tensile;
    }
    summary["fracture"] = {{"segments", cracks.size()},
                           {"cracks", st.fracture.crack_count()},
                           {"length_m", length},
                           {"tensile_segments", tensile},
                           {"shear_segments", static_cast<long>(cracks.size()) - tensile},
                           {"first_crack_step", cracks.empty() ? nlohmann::json(nullptr) : nlohmann::json(cracks.front().step)},
                           {"elements", st.mesh.element_count()},
                           // Splinters the cracks cut off, taken out of the model (fracture.h).
                           {"debris_blocks", st.fracture.debris_blocks()},
                           {"debris_area_m2", st.fracture.debris_area()},
                           // Steps taken again because their solution broke the rock.
                           {"steps_resolved", st.fracture.resolves()}};
    if (st.contacts.cohesive()) summary["fracture"].update(snap_back(st));
  }
  summary["tool_version"] = NMM_VERSION;
  // What the last bits of the results depend on besides the inputs (tests/state_hashes.py), and
  // what the factorisation's speed depends on (docs/performance.md "BLAS kernels").
  summary["compiler"] = NMM_COMPILER;
  const BlasInfo blas = blas_info();
  summary["blas"] = {{"library", blas.library},
                     {"core", blas.core},
                     {"config", blas.config},
                     {"threads", blas.threads},
                     {"cpu_avx2", blas.cpu_avx2},
                     {"slow_kernels", blas.slow_kernels()},
                     {"warning", blas_warning(blas)}};
  return summary;
}

}  // namespace nmm::solve
