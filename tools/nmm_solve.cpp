// nmm-solve MESH.nmm -o OUTDIR [--config VARIANT.json] [--set PATH=VALUE]... [--quiet]
//           [--restart STATE.nmmstate]
//
// --restart continues from a checkpoint (OUTDIR/checkpoint.nmmstate of an earlier run on the
// same mesh): solver.steps more steps, step numbers and times going on from the checkpoint's,
// with the run's variants (friction, joint laws, loads, supports, time step, `excavate`); a
// damaged checkpoint or one of another mesh is bad input (exit status 2).
//           [--pictures [--picture-field displacement|sxx|syy|sxy|pressure] [--exaggerate F]] [--text-frames] [--contacts-every N]
//           [--contacts-gzip]
//
// Loads a mesh file (every check of the reader) and runs it as solve_run.h makes a run (the
// run's variants applied to the embedded scene, the time stepping, the outputs, the progress
// line: the Python module runs the same), with SIGINT/SIGTERM ending the run after the current
// step (interrupt.h). With --pictures it draws the last state and writes the run report
// (run_pictures.h: result.svg, history.svg, run_history.svg, index.html). Exit status: 0 done, 2 bad input
// (one line on stderr), 3 the run could not go on (summary.json says why; the one stderr line
// adds the likely cause, failure_cause.h), 130 interrupted.
// The last line on stderr gives the status beside the equilibrium verdict (at_rest / moving,
// equilibrium_indicator.h); step numbers, there and in run_history.csv, count as history.csv
// does (after --restart, on from the checkpoint's).
#include <CLI/CLI.hpp>

#include <iostream>
#include <string>
#include <vector>

#include "common/command_line.h"
#include "common/error.h"
#include "common/mesh_file.h"
#include "common/run_config.h"
#include "nmm_version.h"
#include "report/failure_cause.h"
#include "report/run_pictures.h"
#include "solver/discretisation/blas_info.h"
#include "solver/output/solve_run.h"
#include "solver/stepping/equilibrium_indicator.h"
#include "solver/stepping/interrupt.h"
#include "solver/discretisation/blas_kernels.h"

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
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
                 "what colours result.svg: displacement, sxx, syy, sxy, or pressure (the flow network's "
                 "joints by their water pressure; a scene with \"flow\")");
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
              << "' is not one of displacement, sxx, syy, sxy, pressure\n";
    return nmm::kExitBadInput;
  }
  try {
    const nmm::Mesh mesh = nmm::read_mesh_file(mesh_path);
    nmm::solve::SolveOptions options;
    options.config_path = config_path;
    options.sets = sets;
    options.restart_path = restart_path;
    options.threads = threads;
    options.out_dir = out_dir;
    options.frame_format = text_frames ? nmm::solve::FrameFormat::text : nmm::solve::FrameFormat::compressed;
    options.contacts_every = contacts_every;
    options.contacts_gzip = contacts_gzip;
    options.progress = nmm::solve::ProgressLine::choose(quiet);
    // What this run was made from, so nmm-report can redraw any frame (result_redraw.h).
    options.inputs = nmm::solve::run_inputs(mesh_path, options, field_name,
                                            exaggerate > 0 ? nlohmann::json(exaggerate) : nlohmann::json(nullptr));
    // Before the output folder is made: a picture of what the run cannot have is bad input.
    if (field == nmm::report::PictureField::pressure &&
        !nmm::solve::make_run_scene(mesh, mesh_path, config_path, sets).scene.flow.present)
      throw nmm::InputError("--picture-field", "",
                            "pressure: the scene has no \"flow\" block, so no water flows in this run");
    nmm::solve::SolveRun run(mesh, mesh_path, options);
    nmm::solve::install_interrupt_handlers();
    run.set_stop_check(nmm::solve::interrupt_requested);
    const nlohmann::json summary = run.run();
    const nmm::Outcome& outcome = run.outcome();
    const std::string status = outcome.status();
    const std::string verdict = nmm::solve::equilibrium_line(summary["equilibrium"]);

    // Not where the output could not be written: the pictures would fail as it did.
    if (pictures && outcome.code != nmm::StopCode::output_failed) {
      try {
        const nmm::report::ReportFiles files =
            nmm::report::write_run_pictures(run.view(), run.scene().scene, outcome, out_dir, exaggerate, field);
        if (!quiet)
          std::cerr << "nmm-solve: pictures in " << out_dir << ": result.svg"
                    << (files.png ? " (and .png)" : "") << ", open " << out_dir << "/index.html\n";
      } catch (const nmm::WriteError& e) {
        // The run's results are written (summary.json says how it ended); its pictures are not.
        std::cerr << "nmm-solve: the run's files are written but its pictures are not: " << e.what() << "\n";
        return nmm::kExitRunFailed;
      }
    }
    if (outcome.code == nmm::StopCode::interrupted) {
      std::cerr << "nmm-solve: interrupted after " << summary["steps_completed"].get<long long>()
                << " steps at t = " << run.view().state.time << " s (" << verdict
                << "); history.csv, summary.json and checkpoint.nmmstate written (continue with --restart)\n";
      return nmm::solve::kExitInterrupted;
    }
    if (outcome.failed()) {
      const std::string cause = nmm::report::likely_failure_cause(mesh, run.scene().scene, outcome.code);
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
