// nmm-sweep SWEEP.json -o OUT [--engine threads|snakemake] [--workers N] [--profile DIR] [--set P=V]...
//
// Expands a sweep file (sweep.h) into independent runs, runs them with the chosen engine and
// writes OUT/sweep.csv (one row per run), OUT/sweep.json (the expanded runs) and OUT/sweep.svg
// (each varied parameter against each measured output, sweep_picture.h; sweep.png too when
// rsvg-convert is on PATH). A scene without
// per-run preprocessing is preprocessed once into OUT/base.nmm. Exit status: 0 every run ran
// (a run that stopped with status 3 is a row, not an error); 2 bad input (one line on stderr);
// 3 the engine failed or some run had bad input (its row says so; sweep.csv is still written).
#include <CLI/CLI.hpp>

#include <sys/wait.h>

#include <filesystem>
#include <iostream>

#include "common/atomic_file.h"
#include "common/command_line.h"
#include "common/error.h"
#include "studies/job_runner.h"
#include "nmm_version.h"
#include "common/png_copy.h"
#include "studies/sweep.h"
#include "studies/sweep_picture.h"
#include "common/vtk_writer.h"
#include "solver/discretisation/blas_kernels.h"

namespace fs = std::filesystem;
using namespace nmm::studies;

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  CLI::App app{"nmm-sweep: independent nmm-solve runs over a list or product of variants"};
  std::string sweep_path, out_dir, engine_word = "threads", profile, snakefile;
  int workers = 1;
  std::vector<std::string> extra_sets;
  app.add_option("sweep", sweep_path, "sweep file (JSON)")->required();
  app.add_option("-o,--output", out_dir, "output folder")->required();
  app.add_option("--engine", engine_word, "threads or snakemake")->capture_default_str();
  app.add_option("--workers", workers, "runs at a time (threads, or Snakemake --cores)")->capture_default_str();
  app.add_option("--profile", profile, "Snakemake profile folder (e.g. workflow/profiles/slurm)");
  app.add_option("--snakefile", snakefile, "Snakefile (default: the project's workflow/Snakefile)");
  app.add_option("--set", extra_sets, "PATH=VALUE added to every run's nmm-solve (e.g. solver.steps=20)");
  app.set_version_flag("--version", std::string("nmm-sweep ") + NMM_VERSION);
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-sweep"); status >= 0)
    return status;
  try {
    if (workers < 1 || workers > 256) throw nmm::InputError("", "--workers", "must be in 1..256");
    EngineOptions engine;
    engine.engine = parse_engine(engine_word);
    engine.workers = workers;
    engine.snakemake_profile = profile.empty() ? "" : fs::absolute(profile).string();
    engine.snakefile = snakefile;
    Sweep sweep = read_sweep(sweep_path);
    for (SweepRun& r : sweep.runs)
      for (const std::string& s : extra_sets) {
        if (s.find('=') == std::string::npos) throw nmm::InputError("", "--set", "'" + s + "' is not PATH=VALUE");
        r.sets.push_back(s);
      }
    if (fs::exists(out_dir) && !fs::is_directory(out_dir))
      throw nmm::InputError(out_dir, "", "exists and is not a folder (-o)");
    fs::create_directories(out_dir);
    const fs::path out = fs::absolute(out_dir);
    const std::string solve = sibling_tool("nmm-solve"), preprocess = sibling_tool("nmm-preprocess");

    std::string base_mesh = sweep.mesh;
    bool need_base = false;
    for (const SweepRun& r : sweep.runs) need_base |= r.preprocess_sets.empty();
    if (base_mesh.empty() && need_base) {
      base_mesh = (out / "base.nmm").string();
      const std::string cmd = preprocess + " " + shell_quote(sweep.scene) + " -o " + shell_quote(base_mesh) +
                              " > " + shell_quote((out / "preprocess.log").string()) + " 2>&1";
      const int st = std::system(cmd.c_str());
      if (!WIFEXITED(st) || WEXITSTATUS(st) != 0)
        throw nmm::InputError(sweep.scene, "", "nmm-preprocess failed (see " + (out / "preprocess.log").string() + ")");
    }
    nlohmann::json plan = nlohmann::json::array();
    for (const SweepRun& r : sweep.runs)
      plan.push_back({{"run", r.id}, {"variant", r.name}, {"set", r.sets}, {"preprocess_set", r.preprocess_sets}});
    nmm::write_file_atomically((out / "sweep.json").string(), plan.dump(2) + "\n");

    const std::vector<Job> jobs = sweep_jobs(sweep, out.string(), base_mesh, solve, preprocess);
    std::cerr << "nmm-sweep: " << jobs.size() << " runs, engine " << engine_word << "\n";
    const std::vector<JobResult> results = run_jobs(out.string(), jobs, engine);
    const std::string csv = sweep_csv(sweep, out.string(), results);
    nmm::write_file_atomically((out / "sweep.csv").string(), csv);
    // The picture of the table: each varied parameter against each measured output.
    std::string picture_note;
    if (const std::string svg = sweep_svg(sweep, csv); !svg.empty()) {
      nmm::write_file_atomically((out / "sweep.svg").string(), svg);
      picture_note = nmm::write_png_copy((out / "sweep.svg").string()).empty()
                         ? ", sweep.svg"
                         : ", sweep.svg (and .png)";
    }
    int bad = 0, stopped = 0;
    for (const JobResult& r : results) {
      bad += r.exit_status != 0 && r.exit_status != nmm::kExitRunFailed;
      stopped += r.exit_status == nmm::kExitRunFailed;
    }
    std::cerr << "nmm-sweep: " << results.size() - bad - stopped << " ran to the end, " << stopped
              << " stopped (exit 3), " << bad << " failed; " << (out / "sweep.csv").string()
              << picture_note << "\n";
    if (bad > 0) return nmm::kExitRunFailed;
  } catch (...) {
    return nmm::exit_status_of_current_exception("nmm-sweep");
  }
  return nmm::kExitOk;
}
