// Contact cost: staggered brick walls of N × N blocks settling under gravity on a held base,
// in DDA static mode and dynamic, the reference problem of reference/brick_wall.h.
//
//   contact_bench [--quick] [--sizes 10,20,30,50] [--csv FILE]
//   contact_bench --trace N --sizes 10 [--dynamic] [--peer] [--mesh H] [--threads N] [--memory]
//       per-step counts, times and resident memory of N steps (one solver thread unless told);
//       --memory adds a line at each phase of the system matrix's pattern, analysis and
//       factorisation (common/memory_marks.h): resident memory, its peak within the phase, the
//       heap's bytes in use and free, CHOLMOD's bytes, the factor, the matrix's copies, the scatter
//   contact_bench --peer [--sizes 10,20,30] [--steps 100] [--csv FILE]
//       [--mesh H] [--contact-tolerance T] [--threads N]
//       the DDA code's walls (reference/brick_wall.h peer_wall), static and dynamic, the first
//       STEPS steps timed whole: what bench/ntdda_compare.sh sets beside the DDA code's time.
//       T overrides solver.contact_tolerance; N solver threads (default 1, 0: nmm-solve's
//       default); the CSV gives this thread's CPU time and the wall-clock time per step.
//   --mesh-dir DIR (with --peer, or --trace --peer): each wall's cut mesh is read from
//       DIR/peer_N_hH.nmm when it is there, else cut and written there. What it is for: running
//       the steps under valgrind (callgrind's instruction counts, a measure the machine's load
//       does not move), where the cut itself cannot run — CGAL's interval arithmetic sets the
//       FPU's rounding mode, which valgrind does not follow. Cut once outside valgrind, then:
//         valgrind --tool=callgrind build/bin/contact_bench --peer --sizes 10 --mesh 2 --mesh-dir DIR
//
// Bricks 1 m × 0.5 m, odd rows shifted by half a brick, all touching their neighbours (one
// interface set, penalty 2e11 N/m, φ = 35°), mesh size 0.5 m, Δt = 1e-3 s. Each wall takes 5
// warm-up steps, then 20 timed steps (10 for walls above 30 × 30). The CSV gives per step: wall
// time and where it goes, open–close iterations, factorisations and triangular solve pairs,
// time-step cuts. Targets (issue 11, one core): < 1.5 factorisations per step in settling
// systems, the 30 × 30 static wall < 40 ms per step, the 20 × 20 dynamic wall < 25 ms per step,
// cost growing no faster than blocks^1.2. Run it with OMP_NUM_THREADS=1 for one core.
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/CholmodSupport>

#include "bench/bench_common.h"
#include "common/memory_marks.h"
#include "common/mesh_file.h"
#include "reference/brick_wall.h"
#include "preprocess/cover_cutter.h"
#include "common/stopwatch.h"
#include "solver/stepping/time_stepper.h"
#include "solver/discretisation/blas_kernels.h"

namespace {

// The wall's cut mesh: from `dir` when a run before cut it there (see the header), else cut now
// (and written there when `dir` is given). Static and dynamic walls share the cut.
nmm::Mesh wall_mesh(const nmm::SceneDef& s, int n, double h, const std::string& dir) {
  if (dir.empty()) return nmm::pre::build_mesh(s, "bench");
  char name[96];
  std::snprintf(name, sizeof name, "/peer_%d_h%g.nmm", n, h);
  const std::string path = dir + name;
  if (std::ifstream(path).good()) return nmm::read_mesh_file(path);
  nmm::Mesh m = nmm::pre::build_mesh(s, "bench");
  m.scene_sha256 = nmm::sha256(m.scene_text);  // the file's reader checks it (the cut in memory leaves it unset)
  nmm::write_mesh_file(m, path);
  return m;
}

// A long run of one wall, one line per step: where a settling wall's work goes as it settles.
// The probe of --memory: one line per mark, the peak of resident memory since the last mark
// (the phase's own, Linux's VmHWM reset at each mark) and what was live: the heap's bytes in use
// (main arena and mmapped blocks, mallinfo2) and held free, and the system matrix's parts.
struct MemoryTrace {
  const nmm::solve::TimeStepper* stepper = nullptr;
  int step = 0;            // the step being taken
  double run_peak_mb = 0;  // the largest peak of the phases so far, MB
  double cpu_s = nmm::bench::thread_cpu_seconds();  // at the last mark, s
  void mark(const char* phase) {
    const double cpu = nmm::bench::thread_cpu_seconds();
    const nmm::bench::Resident r = nmm::bench::resident();
    run_peak_mb = std::max(run_peak_mb, r.peak_mb);
    const struct mallinfo2 mi = mallinfo2();
    const nmm::solve::SystemMatrix& sys = stepper->view().system;
    constexpr double mb = 1e-6;
    std::printf("# memory step %d %-21s cpu %6.2f s, resident %6.0f MB, peak in phase %6.0f MB; heap in use %6.0f MB (mmapped %6.0f), "
                "free held %5.0f MB; CHOLMOD %6.0f MB (peak in factorize %6.0f); factor %5.0f, matrix copies %4.0f, scatter %4.0f MB\n",
                step, phase, cpu - cpu_s, r.now_mb, r.peak_mb, mb * static_cast<double>(mi.uordblks + mi.hblkhd),
                mb * static_cast<double>(mi.hblkhd), mb * static_cast<double>(mi.fordblks),
                mb * static_cast<double>(sys.cholmod_bytes()), mb * static_cast<double>(sys.cholmod_peak_bytes()),
                mb * static_cast<double>(sys.factor_bytes()), mb * static_cast<double>(sys.matrix_bytes()),
                mb * static_cast<double>(sys.scatter_bytes()));
    std::fflush(stdout);
    nmm::bench::reset_peak_resident();
    cpu_s = nmm::bench::thread_cpu_seconds();  // the probe's own time left out
  }
};

int trace_run(int n, bool dynamic, bool peer, int steps, double mesh_size, int threads, bool memory,
              const std::string& mesh_dir) {
  const nmm::SceneDef s =
      peer ? nmm::reference::peer_wall(n, n, dynamic, mesh_size) : nmm::reference::brick_wall(n, dynamic);
  const nmm::Mesh m = peer ? wall_mesh(s, n, mesh_size, mesh_dir) : nmm::pre::build_mesh(s, "bench");
  // The cut's working memory, freed but still held by malloc, goes back to the system: what is
  // resident from here on is what nmm-solve holds, which reads the cut mesh from its file.
  const nmm::bench::Resident cut = nmm::bench::resident();
  malloc_trim(0);
  nmm::bench::reset_peak_resident();  // peak_rss_mb below: the run's own peak, from here on
  const nmm::bench::Resident meshed = nmm::bench::resident();
  // The stepper lives until the last step's matrix is copied out for the closing comparison:
  // that comparison's own factor must not count in the run's peak (/usr/bin/time's).
  auto held = std::make_unique<nmm::solve::TimeStepper>(m, s, "bench");
  nmm::solve::TimeStepper& st = *held;
  st.set_threads(threads);
  MemoryTrace trace;
  trace.stepper = &st;
  if (memory) nmm::set_memory_probe([&trace](const char* phase) { trace.mark(phase); });
  const nmm::bench::Resident set_up = nmm::bench::resident();
  std::printf("# resident after the cut %.0f MB (peak %.0f MB), the mesh alone %.0f MB, with the stepper %.0f MB\n",
              cut.now_mb, cut.peak_mb, meshed.now_mb, set_up.now_mb);
  std::printf("step,newton,friction_updates,cg,factorisations,cg_over_budget,unsettled,cuts,ms,"
              "factorisation_ms,cg_ms,detection_ms,cpu_ms,analyses,rss_mb,peak_rss_mb,orderings,kept_analyses,placed_analyses,"
              "factor_mnz,factor_gflop,detection_cpu_ms,list_builds,pairs_tested,reach_redos,contacts\n");
  nmm::solve::ContactSolveStats a = st.view().contact_solve;
  nmm::solve::DetectionStats da = st.view().contacts.detection_stats();
  nmm::solve::StepTimings ta = st.view().timings;
  std::size_t cuts = st.view().state.cuts, analyses = st.view().system.analyses(),
              orderings = st.view().system.orderings(), kept = st.view().system.kept_analyses(),
              placed = st.view().system.placed_analyses();
  for (int k = 1; k <= steps; ++k) {
    trace.step = k;
    const nmm::Stopwatch w0;
    const double c0 = nmm::bench::thread_cpu_seconds();
    const nmm::Outcome ran = st.run_until(k * s.solver.time_step, [](std::int64_t) {});
    const double ms = 1e3 * w0.seconds(), cpu_ms = 1e3 * (nmm::bench::thread_cpu_seconds() - c0);
    const nmm::solve::ContactSolveStats& b = st.view().contact_solve;
    const nmm::solve::StepTimings& tb = st.view().timings;
    const nmm::solve::DetectionStats& db = st.view().contacts.detection_stats();
    if (memory) trace.mark("end of step");
    nmm::bench::Resident mem = nmm::bench::resident();
    if (memory) mem.peak_mb = std::max(mem.peak_mb, trace.run_peak_mb);
    std::printf("%d,%ld,%ld,%ld,%ld,%ld,%ld,%zu,%.2f,%.2f,%.2f,%.2f,%.2f,%zu,%.0f,%.0f,%zu,%zu,%zu,%.3f,%.3f,%.2f,%zu,%zu,%ld,%zu\n", k, b.newton - a.newton,
                b.strength_updates - a.strength_updates, b.cg_iterations - a.cg_iterations,
                b.factorisations - a.factorisations, b.cg_aborted - a.cg_aborted, b.unsettled - a.unsettled,
                st.view().state.cuts - cuts, ms, 1e3 * (b.factorisation_seconds - a.factorisation_seconds),
                1e3 * (b.cg_seconds - a.cg_seconds), 1e3 * (tb.contact_detection - ta.contact_detection), cpu_ms,
                st.view().system.analyses() - analyses, mem.now_mb, mem.peak_mb,
                st.view().system.orderings() - orderings, st.view().system.kept_analyses() - kept,
                st.view().system.placed_analyses() - placed, 1e-6 * st.view().system.factor_nonzeros(),
                1e-9 * st.view().system.factor_flops(), 1e3 * (db.cpu_seconds - da.cpu_seconds),
                db.list_builds - da.list_builds, db.pairs_tested - da.pairs_tested,
                tb.reach_redos - ta.reach_redos, st.view().contacts.contacts().size());
    std::fflush(stdout);
    if (!ran.ok()) {
      std::printf("# stopped: %s\n", ran.reason.c_str());
      return 1;
    }
    if (k == 1 || k == steps)
      std::printf("# unknowns %d, matrix nonzeros %zu, factor nonzeros %.0f, factorisation Mflop %.1f, ordering %s, analyses %zu, "
                  "orderings %zu, scatter %.0f MB, factor %.0f MB%s, matrix copies %.0f MB, single-precision refinements %zu\n",
                  st.view().space.unknowns(), st.view().system.nonzeros(), st.view().system.factor_nonzeros(), 1e-6 * st.view().system.factor_flops(),
                  st.view().system.ordering().c_str(), st.view().system.analyses(), st.view().system.orderings(),
                  1e-6 * static_cast<double>(st.view().system.scatter_bytes()),
                  1e-6 * static_cast<double>(st.view().system.factor_bytes()),
                  st.view().system.single_precision() ? " (single precision)" : "",
                  1e-6 * static_cast<double>(st.view().system.matrix_bytes()), st.view().system.single_refinements());
    a = b;
    ta = tb;
    da = db;
    cuts = st.view().state.cuts;
    analyses = st.view().system.analyses();
    orderings = st.view().system.orderings();
    kept = st.view().system.kept_analyses();
    placed = st.view().system.placed_analyses();
  }
  // One factorisation against one CG iteration's work (a factor solve pair and a product with
  // the matrix) on the last step's matrix, thread CPU time: what one factorisation is worth.
  nmm::set_memory_probe({});
  std::printf("# run's peak resident %.0f MB\n", std::max(nmm::bench::resident().peak_mb, trace.run_peak_mb));
  const nmm::solve::SystemMatrix::Sparse km = st.view().system.matrix();
  held.reset();
  Eigen::CholmodSupernodalLLT<nmm::solve::SystemMatrix::Sparse, Eigen::Upper> llt;
  llt.analyzePattern(km);
  double f_best = 1e9, s_best = 1e9;
  Eigen::VectorXd x = Eigen::VectorXd::Ones(km.rows()), y(km.rows());
  for (int rep = 0; rep < 3; ++rep) {
    double c0 = nmm::bench::thread_cpu_seconds();
    llt.factorize(km);
    f_best = std::min(f_best, nmm::bench::thread_cpu_seconds() - c0);
    c0 = nmm::bench::thread_cpu_seconds();
    for (int i = 0; i < 20; ++i) {
      y = llt.solve(x);
      x.noalias() = km.selfadjointView<Eigen::Upper>() * y;
      x /= x.norm();
    }
    s_best = std::min(s_best, (nmm::bench::thread_cpu_seconds() - c0) / 20);
  }
  std::printf("# factorisation %.3f ms, CG iteration (solve pair + product) %.3f ms, ratio %.1f (thread CPU)\n",
              1e3 * f_best, 1e3 * s_best, f_best / s_best);
  return 0;
}
// The peer's walls: the first `steps` steps timed whole (thread CPU), as the DDA code's
// ms_per_step covers its whole analysis.
int peer_run(const std::vector<int>& sizes, int steps, double h, double tau, int threads, const std::string& csv_path,
             const std::string& mesh_dir) {
  const char* header =
      "mode,wall_n,mesh_size,blocks,unknowns,contacts,steps,cpu_ms_per_step,solves_per_step,"
      "factorisations_per_step,cg_per_step,friction_updates_per_step,detection_ms_per_step,"
      "factorisation_ms_per_step,cg_ms_per_step,cuts,status,load_average,threads,wall_ms_per_step,"
      "line_search_ms_per_step,assembly_ms_per_step,update_ms_per_step,analyses\n";
  std::ofstream csv = nmm::bench::start_csv(csv_path, header);
  for (const bool dynamic : {false, true}) {
    for (int n : sizes) {
      nmm::SceneDef s = nmm::reference::peer_wall(n, n, dynamic, h);
      if (tau > 0) s.solver.contact_tolerance = tau;
      const nmm::Mesh m = wall_mesh(s, n, h, mesh_dir);
      nmm::solve::TimeStepper st(m, s, "bench");
      st.set_threads(threads);
      std::int64_t done = 0;
      // CPU time of this thread (what one-thread runs compare on a shared machine) and wall-clock
      // time (what more threads save: their work is not this thread's CPU time).
      const double c0 = nmm::bench::thread_cpu_seconds();
      const auto w0 = std::chrono::steady_clock::now();
      const nmm::Outcome ran = st.run_until(steps * s.solver.time_step, [&](std::int64_t) { ++done; });
      const double cpu = nmm::bench::thread_cpu_seconds() - c0;
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
      const nmm::solve::ContactSolveStats& cs = st.view().contact_solve;
      const double per = 1.0 / static_cast<double>(std::max<std::int64_t>(done, 1));
      const nmm::solve::StepTimings& tm = st.view().timings;
      char line[700];
      std::snprintf(line, sizeof line, "%s,%d,%g,%zu,%d,%zu,%lld,%.3f,%.2f,%.3f,%.2f,%.2f,%.3f,%.3f,%.3f,%zu,%s,%.2f,%d,%.3f,%.3f,%.3f,%.3f,%zu\n",
                    dynamic ? "dynamic" : "static", n, h, m.block_count(), st.view().space.unknowns(),
                    st.view().contacts.contacts().size(), static_cast<long long>(done), 1e3 * cpu * per,
                    static_cast<double>(cs.newton) * per, static_cast<double>(cs.factorisations) * per,
                    static_cast<double>(cs.cg_iterations) * per, static_cast<double>(cs.strength_updates) * per,
                    1e3 * st.view().timings.contact_detection * per, 1e3 * cs.factorisation_seconds * per,
                    1e3 * cs.cg_seconds * per, st.view().state.cuts, ran.status().c_str(),
                    nmm::bench::load_average(),
                    st.view().threads, 1e3 * wall * per, 1e3 * cs.line_search_seconds * per,
                    1e3 * tm.assembly * per, 1e3 * tm.geometry_update * per, st.view().system.analyses());
      csv << line;
      std::fputs(line, stdout);
      std::fflush(stdout);
    }
  }
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  std::vector<int> sizes{10, 20, 30, 50};
  std::string csv_path = "contact_bench.csv", mesh_dir;
  int trace_steps = 0;
  bool trace_dynamic = false, peer = false, trace_memory = false;
  int peer_steps = 100;
  double peer_mesh = 0.5, peer_tau = 0;
  int peer_threads = 1;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) sizes = {5, 10};
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) sizes = nmm::bench::parse_sizes(argv[++i]);
    else if (!std::strcmp(argv[i], "--trace") && i + 1 < argc) trace_steps = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--dynamic")) trace_dynamic = true;
    else if (!std::strcmp(argv[i], "--memory")) trace_memory = true;
    else if (!std::strcmp(argv[i], "--peer")) peer = true;
    else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) peer_steps = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc) peer_mesh = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--contact-tolerance") && i + 1 < argc) peer_tau = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) peer_threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else if (!std::strcmp(argv[i], "--mesh-dir") && i + 1 < argc) mesh_dir = argv[++i];
    else {
      std::fprintf(stderr, "usage: contact_bench [--quick] [--sizes 10,20,30,50] [--csv FILE] | --trace STEPS --sizes N [--dynamic] [--peer [--mesh H]] [--memory] | --peer [--sizes 10,20,30] [--steps 100] [--mesh H] [--contact-tolerance T] [--threads N] [--csv FILE] [--mesh-dir DIR]\n");
      return 2;
    }
  }
  if (trace_steps > 0)
    return trace_run(sizes.front(), trace_dynamic, peer, trace_steps, peer_mesh, peer_threads, trace_memory, mesh_dir);
  if (peer) return peer_run(sizes, peer_steps, peer_mesh, peer_tau, peer_threads, csv_path, mesh_dir);
  const char* header =
      "mode,wall_n,blocks,elements,unknowns,contacts,step_ms,detection_ms,assembly_ms,"
      "factorisation_ms,solves_ms,update_ms,iterations_per_step,factorisations_per_step,"
      "solves_per_step,cuts,status,step_cpu_ms,load_average\n";
  std::ofstream csv = nmm::bench::start_csv(csv_path, header);
  for (const bool dynamic : {false, true}) {
    for (int n : sizes) {
      const nmm::SceneDef s = nmm::reference::brick_wall(n, dynamic);
      const nmm::Mesh m = nmm::pre::build_mesh(s, "bench");
      nmm::solve::TimeStepper st(m, s, "bench");
      nmm::Outcome ran = st.run_until(5e-3, [](std::int64_t) {});
      const nmm::solve::StepTimings t0 = st.view().timings;
      const std::size_t it0 = st.view().state.iterations, cuts0 = st.view().state.cuts;
      std::int64_t steps = 0;
      const double timed = n > 30 ? 10e-3 : 20e-3;
      const nmm::Stopwatch w0;
      const double c0 = nmm::bench::thread_cpu_seconds();
      if (ran.ok()) ran = st.run_until(5e-3 + timed, [&](std::int64_t) { ++steps; });
      const double wall = w0.seconds(), cpu = nmm::bench::thread_cpu_seconds() - c0;
      const nmm::solve::StepTimings& t1 = st.view().timings;
      const double per = 1.0 / static_cast<double>(std::max<std::int64_t>(steps, 1));
      const double k = 1e3 * per;
      char line[600];
      std::snprintf(line, sizeof line,
                    "%s,%d,%zu,%zu,%d,%zu,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.2f,%.2f,%.2f,%zu,%s,%.3f,%.2f\n",
                    dynamic ? "dynamic" : "static", n, m.block_count(), m.element_count(),
                    st.view().space.unknowns(), st.view().contacts.contacts().size(), wall * k,
                    (t1.contact_detection - t0.contact_detection) * k, (t1.assembly - t0.assembly) * k,
                    (t1.factorisation - t0.factorisation) * k, (t1.solves - t0.solves) * k,
                    (t1.geometry_update - t0.geometry_update) * k,
                    static_cast<double>(st.view().state.iterations - it0) * per,
                    static_cast<double>(t1.factorisations - t0.factorisations) * per,
                    static_cast<double>(t1.solves_count - t0.solves_count) * per,
                    st.view().state.cuts - cuts0, ran.status().c_str(), cpu * k,
                    nmm::bench::load_average());
      csv << line;
      std::fputs(line, stdout);
      std::fflush(stdout);
    }
  }
  return 0;
}
