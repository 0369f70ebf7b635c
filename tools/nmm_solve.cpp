// nmm-solve MESH.nmm -o OUTDIR [--config VARIANT.json] [--set PATH=VALUE]... [--quiet]
//           [--restart STATE.nmmstate]
//
// --restart continues from a checkpoint (OUTDIR/checkpoint.nmmstate of an earlier run on the
// same mesh): solver.steps more steps, step numbers and times going on from the checkpoint's,
// with the run's variants (friction, joint laws, loads, supports, time step, `excavate`); a
// damaged checkpoint or one of another mesh is bad input (exit status 2).
//           [--pictures [--picture-field displacement|sxx|syy|sxy] [--exaggerate F]] [--text-frames] [--contacts-every N]
//           [--contacts-gzip]
//
// Loads a mesh file (every check of the reader), applies the run's variants to the embedded
// scene (run_config.h) and runs the time stepping (time_stepper.h), with a progress line
// (progress.h) and SIGINT/SIGTERM ending the run after the current step (interrupt.h). With
// --pictures it draws the last state (result.svg, result_picture.h) and writes the run report
// (history.svg, run_history.svg, index.html: run_report.h). Exit status: 0 done, 2 bad input
// (one line on stderr), 3 the run could not go on (summary.json says why; the one stderr line
// adds the likely cause, failure_cause.h), 130 interrupted.
// The last line on stderr gives the status beside the equilibrium verdict (at_rest / moving,
// equilibrium_indicator.h); step numbers, there and in run_history.csv, count as history.csv
// does (after --restart, on from the checkpoint's).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "common/command_line.h"
#include "solver/discretisation/blas_info.h"
#include "solver/output/energy.h"
#include "report/failure_cause.h"
#include "common/error.h"
#include "solver/stepping/interrupt.h"
#include "common/mesh_file.h"
#include "nmm_version.h"
#include "solver/output/output_writer.h"
#include "solver/output/progress.h"
#include "report/result_picture.h"
#include "common/run_config.h"
#include "solver/output/run_driver.h"
#include "solver/reinforcement/bolt_readout.h"
#include "report/run_report.h"
#include "solver/stepping/time_stepper.h"
#include "common/atomic_file.h"

namespace {

// --pictures: result.svg of the last state (result_picture.h) and the run's report
// (run_report.h).
nmm::report::ReportFiles write_pictures(const nmm::solve::RunView& run, const nmm::SceneDef& scene,
                                        const nmm::Outcome& outcome, const std::string& out_dir,
                                        double exaggerate, nmm::report::PictureField field) {
  nmm::report::PictureState state;
  state.time = run.state.time;
  state.status = outcome.status();
  state.stop = outcome.code;
  state.loop_xy = &run.state.loop_xy;
  const std::vector<double> mean_stress = nmm::solve::mean_stress(run);  // [3·me] at any order
  state.stress = &mean_stress;
  for (const nmm::solve::Contact& c : run.contacts.contacts())
    if (c.state != nmm::solve::ContactState::open)
      state.contacts.push_back({run.state.loop_xy[2 * c.at.vertex], run.state.loop_xy[2 * c.at.vertex + 1],
                                static_cast<int>(c.state), c.at.vertex, c.at.edge});
  for (const nmm::solve::TrackedPoint& p : run.state.measure) {
    state.measure_points.push_back({p.x, p.y});
    // x − (x − x0): what nmm-report computes from history.csv (x, ux), so its redraw of an
    // exaggerated picture is this one byte for byte.
    state.measure_start.push_back({p.x - (p.x - p.x0), p.y - (p.y - p.y0)});
  }
  for (std::size_t b = 0; b < run.state.bolts.size(); ++b) {
    nmm::report::PictureBolt pb;
    pb.broken = run.state.bolts[b].broken != 0;
    for (const nmm::solve::BoltReading& r : nmm::solve::bolt_readout(scene.bolts[b], run.state.bolts[b])) {
      pb.points.push_back({r.x, r.y});
      pb.start.push_back({r.x - r.ux, r.y - r.uy});  // as nmm-report computes it from bolts.csv
      pb.axial.push_back(r.axial);
    }
    state.bolts.push_back(std::move(pb));
  }
  state.exaggeration = exaggerate;
  state.excavated_body = run.state.body_removed;
  nmm::write_file_atomically(out_dir + "/result.svg",
                             nmm::report::result_svg(run.mesh, scene, state, field));
  return nmm::report::make_run_report(out_dir);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nmm-solve: NMM time stepping with contacts on a preprocessed mesh"};
  std::string mesh_path, out_dir, config_path, restart_path, field_name = "displacement";
  std::vector<std::string> sets;
  bool quiet = false, pictures = false, text_frames = false, contacts_gzip = false;
  int threads = 0;
  int contacts_every = 1;
  double exaggerate = 0;  // 0: automatic (result_picture.h)
  app.add_option("mesh", mesh_path, "mesh file written by nmm-preprocess")->required();
  app.add_option("-o,--output", out_dir, "output folder")->required();
  app.add_option("--config", config_path, "JSON merge patch applied to the embedded scene");
  app.add_option("--set", sets, "PATH=VALUE: set one scene field (VALUE is JSON), repeatable");
  app.add_option("--restart", restart_path,
                 "continue from a checkpoint (checkpoint.nmmstate) written by an earlier run");
  app.add_flag("-q,--quiet", quiet, "no progress line");
  app.add_flag("--pictures", pictures,
               "draw the last state (result.svg) and write history.svg, run_history.svg, index.html");
  app.add_flag("--text-frames", text_frames,
               "write frames as ASCII .vtu (default: binary, zlib-compressed)");
  app.add_option("--contacts-every", contacts_every,
                 "contacts.csv keeps every N-th output step (and the last); default 1")
      ->check(CLI::PositiveNumber);
  app.add_option("--threads", threads,
                 "threads of the factorisation (0: one below 150k unknowns, all cores above)")
      ->check(CLI::Range(0, 256));
  app.add_flag("--contacts-gzip", contacts_gzip,
               "write contacts.csv.gz (the same CSV, gzip-compressed, about a third of the size)");
  app.add_option("--picture-field", field_name,
                 "what colours result.svg: displacement, sxx, syy or sxy");
  app.add_option("--exaggerate", exaggerate,
                 "draw result.svg's displacements F times larger (1: true scale); default: "
                 "automatic when the largest displacement is under 1 % of the model size")
      ->check(CLI::PositiveNumber);
  app.set_version_flag("--version", std::string("nmm-solve ") + NMM_VERSION + " (" + NMM_COMPILER + ")\n" +
                                        nmm::solve::blas_line(nmm::solve::blas_info()));
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-solve"); status >= 0)
    return status;
  nmm::report::PictureField field;
  if (!nmm::report::parse_picture_field(field_name, field)) {
    std::cerr << "nmm-solve: --picture-field: '" << field_name
              << "' is not one of displacement, sxx, syy, sxy\n";
    return nmm::kExitBadInput;
  }
  try {
    const nmm::Mesh mesh = nmm::read_mesh_file(mesh_path);
    const nmm::solve::RunScene run = nmm::solve::make_run_scene(mesh, mesh_path, config_path, sets);
    nmm::solve::TimeStepper stepper(mesh, run.scene, run.name);
    stepper.set_threads(threads);
    if (!restart_path.empty()) stepper.restart_from(restart_path);
    nmm::solve::OutputWriter out(out_dir, text_frames ? nmm::solve::FrameFormat::text
                                                       : nmm::solve::FrameFormat::compressed);
    out.set_contacts_every(contacts_every);
    out.set_contacts_gzip(contacts_gzip);
    {
      // What this run was made from, so nmm-report can redraw any frame (result_redraw.h).
      auto absolute = [](const std::string& p) {
        return p.empty() ? nlohmann::json(nullptr)
                         : nlohmann::json(std::filesystem::absolute(p).lexically_normal().string());
      };
      out.set_run_inputs({{"mesh", absolute(mesh_path)},
                          {"config", absolute(config_path)},
                          {"set", sets},
                          {"restart", absolute(restart_path)},
                          {"picture_field", field_name},
                          {"exaggerate", exaggerate > 0 ? nlohmann::json(exaggerate)
                                                        : nlohmann::json(nullptr)},
                          {"contacts_every", contacts_every},
                          {"contacts_gzip", contacts_gzip},
                          {"text_frames", text_frames}});
    }

    nmm::solve::install_interrupt_handlers();
    stepper.set_stop_check(nmm::solve::interrupt_requested);
    const nmm::SolverDef& sv = run.scene.solver;
    const double t_start = stepper.view().state.time;  // 0, or the checkpoint's time
    const double t_end = t_start + static_cast<double>(sv.steps) * sv.time_step;
    nmm::solve::ProgressLine progress(nmm::solve::ProgressLine::choose(quiet), t_end);
    // Slow BLAS kernels: said once, with the progress (blas_info.h); summary.json's blas says it always.
    progress.set_warning(nmm::solve::blas_warning(nmm::solve::blas_info()));
    // Energy terms after every step, a row per output step (energy.h, energy.csv).
    const nmm::solve::RunView view = stepper.view();
    nmm::solve::EnergyMeter energy(view.model, &view.space);
    energy.after_step(view.state, view.contacts.contacts(), true);
    std::vector<nmm::report::StepRecord> effort;
    // Per-step counts from the running totals, which a restart brings from the checkpoint.
    std::size_t iterations = view.state.iterations, cuts = view.state.cuts;
    double t_prev = t_start;
    // After every accepted step, in this order: the run history's row (run_history.csv), the
    // energy terms, the progress line (the frames and the checkpoint come first: run_driver.h).
    nmm::solve::StepFunction run_history([&](const nmm::solve::RunView& st, std::int64_t, bool) {
      const double t = st.state.time;
      // Step numbers as history.csv counts them: after --restart they go on from the checkpoint's.
      const nmm::solve::EquilibriumSample& eq = st.equilibrium;
      effort.push_back({st.state.step, t, t - t_prev,
                        static_cast<std::int64_t>(st.state.iterations - iterations),
                        static_cast<std::int64_t>(st.state.cuts - cuts),
                        static_cast<std::int64_t>(st.contacts.totals().closed),
                        eq.max_ratio, eq.mean_ratio, eq.max_velocity});
      iterations = st.state.iterations;
      cuts = st.state.cuts;
      t_prev = t;
    });
    nmm::solve::StepFunction energy_terms([&](const nmm::solve::RunView& st, std::int64_t n, bool) {
      energy.after_step(st.state, st.contacts.contacts(), n % sv.output_every == 0);
    });
    nmm::solve::StepFunction progress_line([&](const nmm::solve::RunView& st, std::int64_t, bool) {
      progress.update(st.state.step, st.state.time);
    });
    nmm::solve::RunDriver driver(stepper, out);
    driver.add(run_history);
    driver.add(energy_terms);
    driver.add(progress_line);
    const nlohmann::json summary = driver.run();
    const nmm::Outcome& outcome = driver.outcome();
    const std::string status = outcome.status();
    const std::string verdict = nmm::solve::equilibrium_line(summary["equilibrium"]);
    progress.finish(stepper.view().state.step, stepper.view().state.time, outcome.ok(),
                    status + ", " + verdict +
                        (summary["stopped_by"] == "stop_at_ratio" ? ", stopped by stop_at_ratio" : ""));
    nmm::report::write_run_history(out_dir, effort);
    energy.keep_last();
    energy.write_csv(out_dir);

    if (pictures) {
      const nmm::report::ReportFiles files =
          write_pictures(stepper.view(), run.scene, outcome, out_dir, exaggerate, field);
      if (!quiet)
        std::cerr << "nmm-solve: pictures in " << out_dir << ": result.svg"
                  << (files.png ? " (and .png)" : "") << ", open " << out_dir << "/index.html\n";
    }
    if (outcome.code == nmm::StopCode::interrupted) {
      std::cerr << "nmm-solve: interrupted after " << summary["steps_completed"].get<long long>()
                << " steps at t = " << stepper.view().state.time << " s (" << verdict
                << "); history.csv, summary.json and checkpoint.nmmstate written (continue with --restart)\n";
      return nmm::solve::kExitInterrupted;
    }
    if (outcome.failed()) {
      const std::string cause = nmm::report::likely_failure_cause(mesh, run.scene, outcome.code);
      std::cerr << "nmm-solve: stopped after " << summary["steps_completed"].get<long long>()
                << " steps: " << status << (cause.empty() ? "" : "; likely cause: " + cause)
                << "; equilibrium at the last step: " << verdict << "\n";
      return nmm::kExitRunFailed;
    }
  } catch (const std::bad_alloc&) {
    std::cerr << mesh_path << ": out of memory\n";
    return nmm::kExitRunFailed;
  } catch (...) {
    return nmm::exit_status_of_current_exception("nmm-solve");
  }
  return nmm::kExitOk;
}
