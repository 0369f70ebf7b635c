// Runs jobs through run.sh files (see job_runner.h for the layout and why run.sh exits 0).
#include "studies/job_runner.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/vtk_writer.h"

extern char** environ;

namespace nmm::studies {
namespace fs = std::filesystem;

Engine parse_engine(const std::string& word) {
  if (word == "threads") return Engine::threads;
  if (word == "snakemake") return Engine::snakemake;
  throw InputError("", "--engine", "unknown engine '" + word + "' (threads or snakemake)");
}

std::string shell_quote(const std::string& word) {
  std::string out = "'";
  for (char c : word) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

std::string job_dir(const std::string& root, const Job& job) {
  return (fs::path(root) / "runs" / job.id).string();
}

namespace {
fs::path own_folder() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : self.parent_path();
}
}  // namespace

std::string default_snakefile() {
  if (const char* env = std::getenv("NMM_SNAKEFILE"); env != nullptr && *env != '\0') return env;
  // NMM_INSTALLED_WORKFLOW: the install's workflow folder relative to its bin folder
  // (studies/CMakeLists.txt), so an installed tree can be moved or installed under any prefix.
  if (const fs::path bin = own_folder(); !bin.empty()) {
    const fs::path installed = (bin / NMM_INSTALLED_WORKFLOW / "Snakefile").lexically_normal();
    std::error_code ec;
    if (fs::is_regular_file(installed, ec)) return installed.string();
  }
  return std::string(NMM_WORKFLOW_DIR) + "/Snakefile";
}

std::string sibling_tool(const std::string& name) {
  const fs::path bin = own_folder();
  std::error_code ec;
  if (!bin.empty() && fs::exists(bin / name, ec)) return (bin / name).string();
  return name;  // from PATH
}

namespace {

// The job script: each command's output goes to log.txt; the first failure stops the job.
std::string run_script(const Job& job) {
  std::string s =
      "#!/usr/bin/env bash\n"
      "# One job of nmm-fos / nmm-sweep (studies/job_runner.h). Run by the threads engine or by\n"
      "# workflow/Snakefile; it records its outcome in job_status.json and exits 0.\n"
      "export LC_ALL=C\n"
      "# One core per run (Snakemake's threads: 1; N threads-engine workers on N cores): BLAS\n"
      "# threads inside parallel runs only oversubscribe. Set the variables to override.\n"
      "export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}\n"
      "cd \"$(dirname \"$0\")\" || exit 1\n"
      "rm -f job_status.json log.txt\n"
      "t0=$EPOCHREALTIME\n"
      "rc=0\n";
  for (const auto& argv : job.commands) {
    std::string line;
    for (const auto& a : argv) line += (line.empty() ? "" : " ") + shell_quote(a);
    s += "if [ $rc -eq 0 ]; then " + line + " >>log.txt 2>&1; rc=$?; fi\n";
  }
  s +=
      "t1=$EPOCHREALTIME\n"
      "wall=$(awk -v a=\"$t0\" -v b=\"$t1\" 'BEGIN { printf \"%.6f\", b - a }')\n"
      "printf '{\"exit\": %d, \"wall_seconds\": %s}\\n' \"$rc\" \"$wall\" > job_status.json.tmp\n"
      "mv job_status.json.tmp job_status.json\n";
  return s;
}

int spawn_and_wait(const std::vector<std::string>& argv, const std::string& log_path) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!log_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
  }
  pid_t pid = 0;
  const int err = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) return -err - 1000;  // could not start: distinct from any exit status
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

JobResult read_status(const std::string& dir) {
  const std::string path = (fs::path(dir) / "job_status.json").string();
  std::ifstream in(path);
  if (!in) throw RunError("job " + dir + " left no job_status.json (see its log.txt)");
  try {
    nlohmann::json j = nlohmann::json::parse(in);
    JobResult r;
    r.exit_status = j.at("exit").get<int>();
    r.wall_seconds = j.at("wall_seconds").get<double>();
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw RunError(path + ": unreadable job status: " + e.what());
  }
}

}  // namespace

std::vector<JobResult> run_jobs(const std::string& root, const std::vector<Job>& jobs,
                                const EngineOptions& options) {
  for (const Job& job : jobs) {
    const std::string dir = job_dir(root, job);
    fs::create_directories(dir);
    fs::remove(fs::path(dir) / "job_status.json");
    write_file_atomically((fs::path(dir) / "run.sh").string(), run_script(job));
  }
  if (options.engine == Engine::threads) {
    std::atomic<std::size_t> next{0};
    const int n = std::max(1, std::min<int>(options.workers, static_cast<int>(jobs.size())));
    std::vector<std::thread> pool;
    for (int w = 0; w < n; ++w)
      pool.emplace_back([&] {
        for (std::size_t i = next++; i < jobs.size(); i = next++)
          spawn_and_wait({"bash", (fs::path(job_dir(root, jobs[i])) / "run.sh").string()}, "");
      });
    for (auto& t : pool) t.join();
  } else {
    const std::string snakefile =
        options.snakefile.empty() ? default_snakefile() : options.snakefile;
    std::vector<std::string> argv = {options.snakemake, "--snakefile", snakefile,
                                     "--directory", root, "--nolock"};
    if (options.snakemake_profile.empty()) {
      argv.push_back("--cores");
      argv.push_back(std::to_string(std::max(1, options.workers)));
    } else {
      argv.push_back("--profile");
      argv.push_back(options.snakemake_profile);
    }
    const std::string log = (fs::path(root) / "snakemake.log").string();
    const int rc = spawn_and_wait(argv, log);
    if (rc <= -1000)
      throw RunError("cannot start '" + options.snakemake + "' (install Debian's snakemake)");
    if (rc != 0)
      throw RunError("snakemake exited with status " + std::to_string(rc) + " (see " + log + ")");
  }
  std::vector<JobResult> results;
  for (const Job& job : jobs) results.push_back(read_status(job_dir(root, job)));
  return results;
}

}  // namespace nmm::studies
