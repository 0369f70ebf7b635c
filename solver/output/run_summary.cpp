// summary.json of a run: see run_summary.h.
#include "solver/output/run_summary.h"

#include "nmm_version.h"
#include "solver/discretisation/blas_info.h"
#include "solver/discretisation/blas_kernels.h"

namespace nmm::solve {

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
  // The effects' own parts (effect_output.h summarise).
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
                        {"output", t.output}};
  // The parts the effects book under names of their own (StepTimings::effects).
  for (const Effect* e : st.effects)
    for (const std::string& name : e->timing_names()) summary["timings"][name] = t.effect(name);
  for (const MeshChange* c : st.changes)
    for (const std::string& name : c->timing_names()) summary["timings"][name] = t.effect(name);
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
  summary["tool_version"] = NMM_VERSION;
  // What the last bits of the results depend on besides the inputs (tests/state_hashes.py), and
  // what the factorisation's speed depends on (docs/performance.md "BLAS kernels").
  summary["compiler"] = NMM_COMPILER;
  const BlasInfo blas = blas_info();
  summary["blas"] = {{"library", blas.library},
                     {"core", blas.core},
                     {"chosen", chosen_blas_kernels()},
                     {"config", blas.config},
                     {"threads", blas.threads},
                     {"cpu_avx2", blas.cpu_avx2},
                     {"slow_kernels", blas.slow_kernels()},
                     {"warning", blas_warning(blas)}};
  return summary;
}

}  // namespace nmm::solve
