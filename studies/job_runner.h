// Independent solver runs ("jobs") executed by an existing engine: in-process threads, or the
// Snakemake workflow in workflow/ (locally with --cores N, or on a Slurm cluster through a
// Snakemake profile). There is no scheduler of our own: the threads engine is a plain pool of N
// workers pulling the next job, Snakemake does everything else.
//
// A job is a short list of commands (argv lists) run one after the other in its directory,
// stopping at the first that fails. Both engines run the same file, JOBDIR/run.sh, which records
// the outcome in JOBDIR/job_status.json: {"exit": status of the first failing command or 0,
// "wall_seconds": s}. run.sh itself exits 0 after recording, because a solver run that stops with
// status 3 (diverged) is an outcome to report (a failing FoS trial), not an engine failure.
// Engine layout (what workflow/Snakefile expects): ROOT/runs/ID/run.sh → ROOT/runs/ID/job_status.json.
#pragma once

#include <string>
#include <vector>

namespace nmm::studies {

struct Job {
  std::string id;                                  ///< directory name under ROOT/runs, [A-Za-z0-9_.-]
  std::vector<std::vector<std::string>> commands;  ///< argv lists, run in order
};

struct JobResult {
  int exit_status = -1;     ///< first non-zero status of the job's commands, 0 if all succeeded
  double wall_seconds = 0;  ///< s, the whole job
};

enum class Engine { threads, snakemake };

struct EngineOptions {
  Engine engine = Engine::threads;
  int workers = 1;                ///< threads, or Snakemake's --cores (local) / --jobs (profile)
  std::string snakefile;          ///< workflow/Snakefile; "" = the one found next to the sources
  std::string snakemake_profile;  ///< Snakemake profile directory (e.g. workflow/profiles/slurm)
  std::string snakemake = "snakemake";  ///< the snakemake program
};

/// Parses "threads" / "snakemake" (InputError naming --engine otherwise).
Engine parse_engine(const std::string& word);

/// ROOT/runs/ID for a job.
std::string job_dir(const std::string& root, const Job& job);

/// Writes run.sh for every job under ROOT/runs, runs them with the chosen engine and returns
/// their results in the jobs' order. Throws RunError when the engine itself fails (Snakemake
/// missing or exiting non-zero, a job that left no job_status.json).
std::vector<JobResult> run_jobs(const std::string& root, const std::vector<Job>& jobs,
                                const EngineOptions& options);

/// Quotes a word for POSIX sh (single quotes).
std::string shell_quote(const std::string& word);

/// The Snakefile shipped in workflow/: $NMM_SNAKEFILE when set; else the installed copy next to
/// the running program (PREFIX/bin/nmm-sweep → PREFIX/share/nmm/workflow/Snakefile, written by
/// `cmake --install`); else the source tree's (NMM_WORKFLOW_DIR, for programs run from build/bin).
std::string default_snakefile();

/// The program NAME (nmm-solve, nmm-preprocess) in the running program's own folder — build/bin
/// or the install's bin — when it is there, so the tools drive their own build; else NAME, found
/// on PATH.
std::string sibling_tool(const std::string& name);

}  // namespace nmm::studies
