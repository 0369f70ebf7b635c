// nmm-solve MESH.nmm -o OUTDIR [--config VARIANT.json] [--set PATH=VALUE]... [--quiet]
//           [--restart STATE.nmmstate]
//
// --restart continues from a checkpoint (OUTDIR/checkpoint.nmmstate of an earlier run on the
// same mesh): solver.steps more steps, step numbers and times going on from the checkpoint's,
// with the run's variants (friction, joint laws, loads, supports, time step, `excavate`); a
// damaged checkpoint or one of another mesh is bad input (exit status 2).
//
// Loads a mesh file (every check of the reader), applies the run's variants to the embedded
// scene (run_config.h) and runs the time stepping (time_stepper.h). Exit status: 0 done, 2 bad
// input (one line on stderr), 3 the run could not go on (summary.json says why).
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "command_line.h"
#include "error.h"
#include "mesh_file.h"
#include "nmm_version.h"
#include "output_writer.h"
#include "run_config.h"
#include "time_stepper.h"

int main(int argc, char** argv) {
  CLI::App app{"nmm-solve: NMM time stepping with contacts on a preprocessed mesh"};
  std::string mesh_path, out_dir, config_path, restart_path;
  std::vector<std::string> sets;
  bool quiet = false;
  app.add_option("mesh", mesh_path, "mesh file written by nmm-preprocess")->required();
  app.add_option("-o,--output", out_dir, "output folder")->required();
  app.add_option("--config", config_path, "JSON merge patch applied to the embedded scene");
  app.add_option("--set", sets, "PATH=VALUE: set one scene field (VALUE is JSON), repeatable");
  app.add_option("--restart", restart_path,
                 "continue from a checkpoint (checkpoint.nmmstate) written by an earlier run");
  app.add_flag("-q,--quiet", quiet, "no progress line");
  app.set_version_flag("--version", std::string("nmm-solve ") + NMM_VERSION);
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-solve"); status >= 0)
    return status;
  try {
    const nmm::Mesh mesh = nmm::read_mesh_file(mesh_path);
    const nmm::solve::RunScene run = nmm::solve::make_run_scene(mesh, mesh_path, config_path, sets);
    nmm::solve::TimeStepper stepper(mesh, run.scene, mesh_path + " (embedded scene)");
    if (!restart_path.empty()) stepper.restart_from(restart_path);
    nmm::solve::OutputWriter out(out_dir);
    const bool progress = !quiet && isatty(fileno(stderr));
    const nlohmann::json summary = stepper.run(out, progress);
    if (summary["status"] != "ok") {
      std::cerr << "nmm-solve: stopped after " << summary["steps_completed"].get<long long>()
                << " steps: " << summary["status"].get<std::string>() << "\n";
      return nmm::kExitRunFailed;
    }
  } catch (const nmm::InputError& e) {
    std::cerr << e.what() << "\n";
    return nmm::kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << mesh_path << ": out of memory\n";
    return nmm::kExitRunFailed;
  } catch (const std::exception& e) {
    std::cerr << "nmm-solve: internal error: " << e.what() << "\n";
    return 1;
  }
  return nmm::kExitOk;
}
