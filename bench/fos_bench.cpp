// Factor-of-safety search cost: wall time of nmm-fos with 1 and 2 workers (trials per round),
// and the number of trial runs per decimal digit of the bisection.
//
//   fos_bench [--csv FILE] [--repeats N]
//
// Problem: the block on a 30° plane with φ = 35° (reference/slides.h; F = 1.2128), trials of
// 0.4 s (200 steps). For each worker count k ∈ {1, 2} and tolerance tol ∈ {0.1, 0.01, 0.001} it
// runs nmm-fos (threads engine; every trial is an nmm-solve process) and records the wall time,
// the number of trials and rounds, the error against the closed form, and the trials spent in the
// k-section phase per digit: trials_k / log10(w0 / w), w0 the width of the first bracket and w the
// final one. k-section narrows (k+1)-fold per round of k trials, so the expected count per digit
// is k / log10(k+1): 3.32 for bisection, 4.19 for k = 2 (more trials, but 2.1 rounds per digit
// against 3.3). The machine has 2 cores shared with other work: wall times are what they are on
// the day; the best of --repeats is kept. Nothing fails on a timing. Results:
// bench/results/fos_bench.csv, read in docs/fos-and-sweeps.md.
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "reference/slides.h"
#include "common/stopwatch.h"
#include "solver/discretisation/blas_kernels.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  std::string csv = "fos_bench.csv";
  int repeats = 1;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "fos_bench: usage: fos_bench [--csv FILE] [--repeats N]\n");
      return 2;
    }
  }
  const fs::path work = fs::temp_directory_path() / ("fos_bench_" + std::to_string(getpid()));
  fs::create_directories(work);
  const auto ref = nmm::reference::block_on_plane(30, 35);
  std::ofstream(work / "scene.json") << ref.scene.dump(1);
  const std::string mesh = (work / "scene.nmm").string();
  if (std::system((std::string(NMM_PREPROCESS) + " " + (work / "scene.json").string() + " -o " + mesh +
                   " > /dev/null").c_str()) != 0) {
    std::fprintf(stderr, "fos_bench: nmm-preprocess failed\n");
    return 1;
  }
  std::ofstream out(csv);
  out << "workers,tolerance,wall_seconds,trials,rounds,fos,closed_form,error_percent,"
         "ksection_trials,digits,trials_per_digit,expected_trials_per_digit,trial_wall_seconds\n";
  for (int k : {1, 2})
    for (double tol : {0.1, 0.01, 0.001}) {
      double best = std::numeric_limits<double>::infinity();
      nlohmann::json j;
      for (int r = 0; r < repeats; ++r) {
        const fs::path o = work / ("k" + std::to_string(k) + "_" + std::to_string(r) + "_" + std::to_string(tol));
        const nmm::Stopwatch t0;
        const std::string cmd = std::string(NMM_FOS) + " " + mesh + " -o " + o.string() + " --workers " +
                                std::to_string(k) + " --tol " + std::to_string(tol) + " > /dev/null 2>&1";
        if (std::system(cmd.c_str()) != 0) {
          std::fprintf(stderr, "fos_bench: nmm-fos failed: %s\n", cmd.c_str());
          return 1;
        }
        const double s = t0.seconds();
        if (s < best) {
          best = s;
          std::ifstream in(o / "fos.json");
          j = nlohmann::json::parse(in);
        }
      }
      // The first bracket: after the last round that did not yet have both a stable and a failing
      // trial. Trials after it are the k-section phase.
      double lo = 0, hi = 0, w0 = 0;
      int bracket_round = 0, ksection = 0;
      for (const auto& t : j["trials"]) {
        const double f = t["factor"];
        const int round = t["round"];
        if (w0 > 0 && round > bracket_round) {
          ++ksection;
          continue;
        }
        if (t["verdict"] == "failing") hi = hi == 0 ? f : std::min(hi, f);
        else lo = std::max(lo, f);
        if (lo > 0 && hi > 0 && w0 == 0) {
          bracket_round = round;
        }
        if (lo > 0 && hi > 0) w0 = hi - lo;
      }
      const double w = j["bracket"][1].get<double>() - j["bracket"][0].get<double>();
      const double digits = std::log10(w0 / w);
      const double f = j["fos"];
      char line[512];
      std::snprintf(line, sizeof line, "%d,%g,%.3f,%zu,%d,%.5f,%.5f,%.3f,%d,%.3f,%.3f,%.3f,%.3f\n", k, tol,
                    best, j["trials"].size(), j["rounds"].get<int>(), f, ref.fos, 100 * (f / ref.fos - 1),
                    ksection, digits, digits > 0 ? ksection / digits : 0.0, k / std::log10(k + 1.0),
                    j["trial_wall_seconds"].get<double>());
      out << line;
      std::fputs(line, stdout);
      std::fflush(stdout);
    }
  fs::remove_all(work);
  return 0;
}
