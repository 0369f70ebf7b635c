// nmm-fos MESH.nmm -o OUT [--restart STATE | --settle STEPS] [--sets a,b] [--config V.json] [--set P=V]... [--watch W]
//         [--tol 0.01] [--workers N] [--engine threads|snakemake] [--profile DIR]
//
// Factor of safety by strength reduction (strength_reduction.h): every trial is one nmm-solve run
// (its contract CLI) with the chosen joint sets' strength divided by the trial factor, continuing
// from STATE when given (else from the mesh's initial state), judged stable or failing by
// trial_verdict.h. --settle STEPS makes that state first: one nmm-solve run of STEPS steps with
// the chosen sets intact (cohesion and tensile strength at the scene limit, 1e11 Pa: UDEC's
// practice of reaching initial equilibrium with strong joints, so that switching gravity on at
// t = 0 breaks no bond), under OUT/settle/; every trial continues from its checkpoint. Writes OUT/fos.json, OUT/mechanism.svg (the failing trial with the smallest
// factor, drawn as every result.svg), OUT/displacement_vs_F.svg (with .png copies of both when
// rsvg-convert is on PATH) and each trial's run under OUT/round-R/runs/.
// Exit status: 0 F found; 2 bad input (one line on stderr); 3 no bracket (stable up to the
// largest factor, or failing at the smallest), after writing fos.json with the reason.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/command_line.h"
#include "common/error.h"
#include "studies/job_runner.h"
#include "studies/mechanism_picture.h"
#include "common/mesh_file.h"
#include "common/number_format.h"
#include "nmm_version.h"
#include "common/png_copy.h"
#include "common/run_config.h"
#include "studies/strength_reduction.h"
#include "common/svg_plot.h"
#include "studies/trial_verdict.h"
#include "common/vtk_writer.h"
#include "solver/discretisation/blas_kernels.h"

namespace fs = std::filesystem;
using namespace nmm::studies;

namespace {

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string factor_id(double f) { return "F" + nmm::format_fixed(f, 6); }

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  CLI::App app{"nmm-fos: factor of safety by strength reduction (trials are nmm-solve runs)"};
  std::string mesh_path, out_dir, restart, config_path, sets_word, engine_word = "threads";
  std::string profile, snakefile, solver, watch_word = "auto";
  std::vector<std::string> sets;
  SearchOptions search;
  VerdictCriterion criterion;
  int workers = 1, settle_steps = 0;
  app.add_option("mesh", mesh_path, "mesh file written by nmm-preprocess")->required();
  app.add_option("-o,--output", out_dir, "output folder")->required();
  app.add_option("--restart", restart, "settled state (OUTDIR/checkpoint.nmmstate) every trial continues from");
  app.add_option("--settle", settle_steps,
                 "settle STEPS steps with the chosen sets intact first; trials restart from it");
  app.add_option("--sets", sets_word, "joint sets whose strength is reduced, comma separated (default: all)");
  app.add_option("--config", config_path, "JSON merge patch for every trial (nmm-solve --config)");
  app.add_option("--set", sets, "PATH=VALUE for every trial (nmm-solve --set), repeatable");
  app.add_option("--tol", search.tolerance, "relative width of the final bracket")->capture_default_str();
  app.add_option("--workers", workers, "trials per round, run in parallel")->capture_default_str();
  app.add_option("--engine", engine_word, "threads or snakemake")->capture_default_str();
  app.add_option("--profile", profile, "Snakemake profile folder (e.g. workflow/profiles/slurm)");
  app.add_option("--snakefile", snakefile, "Snakefile (default: the project's workflow/Snakefile)");
  app.add_option("--solver", solver, "nmm-solve program (default: next to nmm-fos)");
  app.add_option("--start", search.start, "first trial factor")->capture_default_str();
  app.add_option("--max-factor", search.max_factor, "give up when stable up to this factor")->capture_default_str();
  app.add_option("--velocity-floor", criterion.velocity_floor, "m/s: slower counts as stopped")->capture_default_str();
  app.add_option("--watch", watch_word, "what the verdict watches: auto (measure points if any, else blocks), points, blocks, both")->capture_default_str();
  app.add_option("--max-displacement", criterion.max_displacement, "m: beyond it a trial fails (0 = no limit)")->capture_default_str();
  app.set_version_flag("--version", std::string("nmm-fos ") + NMM_VERSION);
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-fos"); status >= 0)
    return status;
  try {
    if (!(search.tolerance > 0 && search.tolerance < 1))
      throw nmm::InputError("", "--tol", "must be in (0, 1), got " + std::to_string(search.tolerance));
    if (workers < 1 || workers > 256)
      throw nmm::InputError("", "--workers", "must be in 1..256");
    if (!(search.start > 0) || !(search.max_factor > search.start))
      throw nmm::InputError("", "--start", "need 0 < start < max-factor");
    if (!(criterion.velocity_floor > 0) || !(criterion.max_displacement >= 0))
      throw nmm::InputError("", "--velocity-floor", "need a positive floor and a non-negative limit");
    criterion.watch = parse_watch(watch_word);
    EngineOptions engine;
    engine.engine = parse_engine(engine_word);
    engine.workers = workers;
    engine.snakemake_profile = profile.empty() ? "" : fs::absolute(profile).string();
    engine.snakefile = snakefile;
    if (settle_steps < 0 || settle_steps > 100000000)
      throw nmm::InputError("", "--settle", "must be a number of steps in 0..1e8");
    if (settle_steps > 0 && !restart.empty())
      throw nmm::InputError("", "--settle", "give --settle or --restart, not both");
    if (!restart.empty() && !fs::is_regular_file(restart))
      throw nmm::InputError(restart, "", "no such checkpoint file (--restart)");

    // The user's variants are checked here (exit 2 before any trial) and give the base strengths.
    const nmm::Mesh mesh = nmm::read_mesh_file(mesh_path);
    const nmm::solve::RunScene run = nmm::solve::make_run_scene(mesh, mesh_path, config_path, sets);
    const std::vector<SetStrength> strengths =
        set_strengths(run.effective, split_commas(sets_word), mesh_path + " (embedded scene)");

    if (fs::exists(out_dir) && !fs::is_directory(out_dir))
      throw nmm::InputError(out_dir, "", "exists and is not a folder (-o)");
    fs::create_directories(out_dir);
    const fs::path out = fs::absolute(out_dir);
    const std::string solve = solver.empty() ? sibling_tool("nmm-solve") : solver;
    search.per_round = workers;

    // The settled state: intact joints, the user's variants, STEPS steps.
    auto with_variants = [&](std::vector<std::string> cmd, const std::vector<std::string>& extra) {
      if (!config_path.empty()) {
        cmd.push_back("--config");
        cmd.push_back(fs::absolute(config_path).string());
      }
      std::vector<std::string> all = sets;
      all.insert(all.end(), extra.begin(), extra.end());
      for (const std::string& s : all) {
        cmd.push_back("--set");
        cmd.push_back(s);
      }
      return cmd;
    };
    nlohmann::json settle_json = nullptr;
    if (settle_steps > 0) {
      const fs::path root = out / "settle";
      Job job;
      job.id = "settle";
      std::vector<std::string> intact = {"solver.steps=" + std::to_string(settle_steps)};
      for (const SetStrength& s : strengths) {
        intact.push_back("joint_sets." + s.name + ".cohesion=1e11");
        intact.push_back("joint_sets." + s.name + ".tensile_strength=1e11");
      }
      job.commands.push_back(with_variants({solve, fs::absolute(mesh_path).string(), "-o",
                                            (root / "runs" / job.id / "out").string(), "--quiet"},
                                           intact));
      std::cerr << "nmm-fos: settling " << settle_steps << " steps with the joints intact\n";
      const JobResult r = run_jobs(root.string(), {job}, engine).at(0);
      const std::string dir = job_dir(root.string(), job);
      restart = dir + "/out/checkpoint.nmmstate";
      if (r.exit_status != 0 || !fs::is_regular_file(restart))
        throw nmm::RunError("the settling run failed (exit " + std::to_string(r.exit_status) + "; see " +
                            dir + "/log.txt)");
      settle_json = {{"steps", settle_steps}, {"wall_seconds", r.wall_seconds}, {"checkpoint", restart},
                     {"intact", "cohesion and tensile_strength 1e11 Pa on the reduced sets"}};
    }

    auto run_round = [&](const std::vector<double>& factors, int round) {
      const fs::path root = out / ("round-" + std::to_string(round));
      std::vector<Job> jobs;
      for (double f : factors) {
        Job job;
        job.id = factor_id(f);
        std::vector<std::string> cmd = {solve, fs::absolute(mesh_path).string(), "-o",
                                        (root / "runs" / job.id / "out").string(), "--quiet",
                                        // frame_reader.h reads the ASCII frames (block watch)
                                        "--text-frames"};
        if (!restart.empty()) {
          cmd.push_back("--restart");
          cmd.push_back(fs::absolute(restart).string());
        }
        job.commands.push_back(with_variants(cmd, reduction_sets(strengths, f)));
        jobs.push_back(job);
      }
      std::cerr << "nmm-fos: round " << round << ":";
      for (double f : factors) std::cerr << " " << f;
      std::cerr << "\n";
      const std::vector<JobResult> results = run_jobs(root.string(), jobs, engine);
      std::vector<TrialRecord> records;
      for (std::size_t i = 0; i < jobs.size(); ++i) {
        const std::string dir = job_dir(root.string(), jobs[i]);
        if (results[i].exit_status != 0 && results[i].exit_status != nmm::kExitRunFailed)
          throw nmm::RunError("trial F = " + std::to_string(factors[i]) + " failed to run (exit " +
                              std::to_string(results[i].exit_status) + "; see " + dir + "/log.txt)");
        const TrialVerdict v = judge_trial(dir + "/out", results[i].exit_status, criterion);
        TrialRecord t;
        t.factor = factors[i];
        t.failing = v.failing;
        t.reason = v.reason;
        t.wall_seconds = results[i].wall_seconds;
        t.max_displacement = v.max_displacement;
        t.end_velocity = v.end_velocity;
        t.dir = dir;
        std::cerr << "nmm-fos:   F = " << t.factor << ": " << (t.failing ? "failing" : "stable")
                  << " (" << t.reason << ")\n";
        records.push_back(t);
      }
      return records;
    };
    const SearchResult result = search_factor_of_safety(search, run_round);

    // fos.json
    nlohmann::json j;
    j["status"] = result.status;
    j["fos"] = result.found ? nlohmann::json(result.fos) : nlohmann::json(nullptr);
    j["bracket"] = {result.lo, result.hi};
    j["tolerance"] = search.tolerance;
    j["rounds"] = result.rounds;
    j["trials_per_round"] = workers;
    j["monotone"] = result.monotone;
    j["engine"] = engine_word;
    j["mesh"] = mesh_path;
    j["restart"] = restart.empty() ? nlohmann::json(nullptr) : nlohmann::json(restart);
    j["settle"] = settle_json;
    j["criterion"] = {{"velocity_floor", criterion.velocity_floor},
                      {"max_displacement", criterion.max_displacement},
                      {"watch", watch_word},
                      {"rule", "failing: run stopped, or a watched measure point or block moved "
                               "beyond max_displacement, or moves faster than velocity_floor over the "
                               "last quarter and faster than decay_ratio times its speed over "
                               "the quarter before"},
                      {"decay_ratio", criterion.decay_ratio}};
    nlohmann::json js = nlohmann::json::array();
    for (const SetStrength& s : strengths)
      js.push_back({{"name", s.name}, {"tan_phi", s.tan_phi}, {"cohesion", s.cohesion},
                    {"tensile_strength", s.tensile_strength}, {"residual_cohesion", s.residual_cohesion},
                    {"shear_model", s.shear_model}});
    j["sets"] = js;
    nlohmann::json jt = nlohmann::json::array();
    double total_wall = 0;
    const TrialRecord* mechanism = nullptr;
    for (const TrialRecord& t : result.trials) {
      total_wall += t.wall_seconds;
      jt.push_back({{"factor", t.factor}, {"verdict", t.failing ? "failing" : "stable"},
                    {"reason", t.reason}, {"round", t.round}, {"wall_seconds", t.wall_seconds},
                    {"max_displacement", t.max_displacement}, {"end_velocity", t.end_velocity},
                    {"dir", fs::relative(t.dir, out).string()}});
      if (t.failing && (mechanism == nullptr || t.factor < mechanism->factor)) mechanism = &t;
    }
    j["trials"] = jt;
    j["trial_wall_seconds"] = total_wall;

    // Pictures.
    nmm::PlotSpec plot;
    plot.title = "Strength reduction: measure-point displacement against F";
    plot.xlabel = "trial factor F";
    plot.ylabel = "largest measure-point displacement (m)";
    plot.log_y = true;
    nmm::PlotSeries stable{"stable", {}, {}, "#1f77b4", false, true};
    nmm::PlotSeries failing{"failing", {}, {}, "#d62728", false, true};
    for (const TrialRecord& t : result.trials) {
      nmm::PlotSeries& s = t.failing ? failing : stable;
      s.x.push_back(t.factor);
      s.y.push_back(std::max(t.max_displacement, 1e-12));
    }
    for (auto* s : {&stable, &failing})
      if (!s->x.empty()) plot.series.push_back(*s);
    if (!plot.series.empty()) {
      nmm::write_svg_plot(plot, (out / "displacement_vs_F.svg").string());
      j["plot_svg"] = "displacement_vs_F.svg";
      if (!nmm::write_png_copy((out / "displacement_vs_F.svg").string()).empty())
        j["plot_png"] = "displacement_vs_F.png";
    }
    if (mechanism != nullptr) {
      char title[128];
      std::snprintf(title, sizeof title, "failing mechanism at F = %.4g,",
                    mechanism->factor);
      // The factor is the study's result; a trial folder that cannot be drawn (its mesh moved
      // on another machine) costs the picture, not the result.
      try {
        write_mechanism_svg(mechanism->dir + "/out", title, (out / "mechanism.svg").string());
        j["mechanism_svg"] = "mechanism.svg";
        if (!nmm::write_png_copy((out / "mechanism.svg").string()).empty())
          j["mechanism_png"] = "mechanism.png";
      } catch (const nmm::RunError& e) {
        std::cerr << "nmm-fos: warning: no mechanism.svg: " << e.what() << "\n";
      }
    }
    nmm::write_file_atomically((out / "fos.json").string(), j.dump(2) + "\n");
    if (!result.found) {
      std::cerr << "nmm-fos: no factor of safety: " << result.status << "\n";
      return nmm::kExitRunFailed;
    }
    std::printf("F = %.4f (bracket %.4f .. %.4f, %zu trials in %d rounds)\n", result.fos, result.lo,
                result.hi, result.trials.size(), result.rounds);
  } catch (...) {
    return nmm::exit_status_of_current_exception("nmm-fos");
  }
  return nmm::kExitOk;
}
