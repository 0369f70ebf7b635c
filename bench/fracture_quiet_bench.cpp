// What a run that can crack costs per quiet step (nothing cracks) against the same run intact
// (issue 49 item 3; docs/performance.md "Fracturing's quiet steps").
//
//   OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 fracture_quiet_bench [--elements N] [--mode static|dynamic]
//       [--rounds R] [--steps S] [--csv FILE]
//
// Scene: the tension bar of the fracturing matrix (reference/rock_tests.h: 4 m × 1 m of the
// laboratory rock in plane strain, one end on rollers, the other pulled on rollers at the rate
// that reaches σt after 150 steps), its mesh size set for about N elements (default 10⁵), with
// static (DDA) steps, then with dynamic ones (or only the --mode given). "intact": the same document without its `fracture` block (the
// material keeps its `strength`, which alone breaks nothing, fracture.h); "can crack": as it is.
// Both steppers stay alive and take their batches of S steps in turn, each round starting with
// the other one, so a drift in the machine's speed hits both alike (the 2-core machine is
// shared). Per step: wall time and the thread's CPU time (OpenBLAS and CHOLMOD on one thread:
// the CPU time excludes what other jobs take), the fastest batch and the median over rounds of
// the paired ratio (can crack / intact). The rows break the can-crack step down: the stepper's
// `fracture` timing of the fastest batch (what fracturing adds to a quiet step: keeping the
// step's start to re-solve from and the strength check, StepTimings::fracture), those two parts
// timed apart after the batches (keep_ms: step_start.h; find_ms: Fracture::find), and, for
// scale, one full copy of the run state into fresh memory (what each step did before
// step_start.h). Every step stays below σt (the bench checks that nothing cracked).
// Nothing here fails on a timing. Results: bench/results/fracture_quiet_bench*.csv.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "common/scene.h"
#include "common/stopwatch.h"
#include "preprocess/cover_cutter.h"
#include "reference/rock_tests.h"
#include "solver/fracture/step_start.h"
#include "solver/stepping/time_stepper.h"
#include "solver/discretisation/blas_kernels.h"

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// One run being timed: its scene, mesh and stepper stay alive between batches.
struct Run {
  Run(nmm::SceneDef s, const std::string& name)
      : scene(std::move(s)), mesh(nmm::pre::build_mesh(scene, name)), st(mesh, scene, name) {}
  nmm::SceneDef scene;
  nmm::Mesh mesh;
  nmm::solve::TimeStepper st;
  double best_wall = std::numeric_limits<double>::infinity();  // s/step, the fastest batch
  double best_cpu = std::numeric_limits<double>::infinity();   // s/step, CPU of the fastest batch (by CPU)
  double fracture = 0;                                         // s/step, StepTimings::fracture of the fastest batch
  std::vector<double> wall, cpu;                               // s/step, per round
  // Times a batch of n steps of dt.
  void batch(int n, double dt) {
    const double f0 = st.view().timings.effect("fracture");
    const double c0 = nmm::bench::thread_cpu_seconds();
    const nmm::Stopwatch w0;
    for (int i = 0; i < n; ++i) st.step(dt);
    const double w = w0.seconds() / n, c = (nmm::bench::thread_cpu_seconds() - c0) / n;
    wall.push_back(w);
    cpu.push_back(c);
    if (w < best_wall) best_wall = w;
    if (c < best_cpu) best_cpu = c, fracture = (st.view().timings.effect("fracture") - f0) / n;
  }
};

// Times the pair (intact, can crack) in one mode and writes their rows.
int measure(double elements, bool dynamic, int rounds, int steps, std::ofstream& csv) {
  nmm::reference::RockTestCase c;
  c.test = nmm::reference::RockTest::tension_bar;
  c.dynamic = dynamic;
  nmm::reference::RockTestSpecimen sp = nmm::reference::rock_test(c);
  // Equilateral triangles of side h over the bar's 4 m²: about 4 / (√3/4·h²) elements.
  const double h = std::sqrt(4.0 / (elements * std::sqrt(3.0) / 4));
  sp.scene["mesh"]["size"] = h;
  nlohmann::json intact_doc = sp.scene;
  intact_doc.erase("fracture");
  const nmm::SceneDef crack_scene = nmm::scene_from_json(sp.scene, "tension bar (can crack)");
  const nmm::SceneDef intact_scene = nmm::scene_from_json(intact_doc, "tension bar (intact)");
  const double dt = crack_scene.solver.time_step;

  std::vector<std::unique_ptr<Run>> runs;
  runs.push_back(std::make_unique<Run>(intact_scene, "intact"));
  runs.push_back(std::make_unique<Run>(crack_scene, "can crack"));
  if (fracture_of(runs[0]->st.view()).active() || !fracture_of(runs[1]->st.view()).active()) {
    std::fprintf(stderr, "fracture_quiet_bench: the intact run must not crack and the other must be able to\n");
    return 1;
  }
  for (auto& r : runs) r->st.step(dt), r->st.step(dt);  // warm-up: the symbolic analysis
  std::vector<double> ratio_wall, ratio_cpu;
  for (int r = 0; r < rounds; ++r) {
    for (int i = 0; i < 2; ++i) runs[static_cast<std::size_t>((i + r) % 2)]->batch(steps, dt);
    ratio_wall.push_back(runs[1]->wall.back() / runs[0]->wall.back());
    ratio_cpu.push_back(runs[1]->cpu.back() / runs[0]->cpu.back());
  }
  const nmm::solve::RunState& state = runs[1]->st.view().state;
  if (!fracture_of(runs[1]->st.view()).segments().empty()) {
    std::fprintf(stderr, "fracture_quiet_bench: the bar cracked: not a quiet step\n");
    return 1;
  }
  // For scale: what one copy of the run state into fresh memory costs (median of 5).
  std::vector<double> copies;
  for (int i = 0; i < 5; ++i) {
    const nmm::Stopwatch w;
    const nmm::solve::RunState copy = state;
    copies.push_back(w.seconds());
    if (copy.step != state.step) return 1;
  }
  // The two parts of the can-crack step's `fracture` time, apart (median of 5): keeping the
  // step's start (step_start.h; buffers warm, as from the second step on) and the strength check
  // after the step (Fracture::find on a copy, so the run's own record is untouched).
  std::vector<double> keeps, finds;
  {
    nmm::solve::StepStart start;
    start.keep(state, runs[1]->st.view().contacts.history());
    for (int i = 0; i < 5; ++i) {
      const nmm::Stopwatch w;
      start.keep(state, runs[1]->st.view().contacts.history());
      keeps.push_back(w.seconds());
    }
    for (int i = 0; i < 5; ++i) {
      nmm::solve::Fracture f = fracture_of(runs[1]->st.view());
      const nmm::Stopwatch w;
      const std::vector<nmm::solve::CrackSegment> found = f.find(runs[1]->mesh, runs[1]->scene, state, {});
      finds.push_back(w.seconds());
      if (!found.empty()) return 1;
    }
  }
  const double state_mb = 8e-6 * static_cast<double>(state.cover_xy.size() + state.cover_u.size() +
                                                      state.velocity.size() + state.accel.size() +
                                                      state.stress.size() + state.loop_xy.size() + state.loop_u.size());
  const double ms = 1e3;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const Run& r = *runs[i];
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%zu,%d,%d,%.2f,%.2f,%.3f,%.3f,%.3f,%.4f,%.4f,%.3f,%.1f,%.1f\n",
                  i ? "can crack" : "intact", dynamic ? "dynamic" : "static", r.mesh.element_count(),
                  r.st.view().space.unknowns(), rounds * steps, r.best_wall * ms, r.best_cpu * ms, r.fracture * ms,
                  i ? median(keeps) * ms : 0.0, i ? median(finds) * ms : 0.0, i ? median(ratio_wall) : 1.0,
                  i ? median(ratio_cpu) : 1.0, i ? median(copies) * ms : 0.0, i ? state_mb : 0.0,
                  nmm::bench::load_average());
    csv << line;
    std::fputs(line, stdout);
  }
  std::printf("%s: quiet-step overhead of fracturing: fastest batches %+.1f %% (CPU %+.1f %%), paired median "
              "%+.1f %% (CPU %+.1f %%)\n",
              dynamic ? "dynamic" : "static", 100 * (runs[1]->best_wall / runs[0]->best_wall - 1),
              100 * (runs[1]->best_cpu / runs[0]->best_cpu - 1), 100 * (median(ratio_wall) - 1),
              100 * (median(ratio_cpu) - 1));
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  double elements = 1e5;
  std::vector<bool> modes{false, true};  // static, dynamic
  int rounds = 6, steps = 4;
  std::string csv_path = "fracture_quiet_bench.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--elements") && i + 1 < argc) elements = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--mode") && i + 1 < argc && !std::strcmp(argv[i + 1], "static")) modes = {false}, ++i;
    else if (!std::strcmp(argv[i], "--mode") && i + 1 < argc && !std::strcmp(argv[i + 1], "dynamic")) modes = {true}, ++i;
    else if (!std::strcmp(argv[i], "--rounds") && i + 1 < argc) rounds = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: fracture_quiet_bench [--elements N] [--mode static|dynamic] [--rounds R] "
                           "[--steps S] [--csv FILE]\n");
      return 2;
    }
  }
  // 2 + rounds·steps steps must stay below the 150 that reach σt.
  if (elements < 100 || rounds < 1 || steps < 1 || 2 + rounds * steps > 120) {
    std::fprintf(stderr, "fracture_quiet_bench: --elements ≥ 100, and 2 + rounds·steps ≤ 120 (quiet steps)\n");
    return 2;
  }
  std::ofstream csv = nmm::bench::start_csv(
      csv_path,
      "run,mode,elements,unknowns,steps,step_wall_ms,step_cpu_ms,fracture_ms,keep_ms,find_ms,paired_wall_ratio,"
      "paired_cpu_ratio,"
      "state_copy_ms,state_mb,load_average\n");
  for (const bool dynamic : modes)
    if (const int failed = measure(elements, dynamic, rounds, steps, csv)) return failed;
  return 0;
}
