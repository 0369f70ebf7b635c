// What the flow along the joints costs (issue 51; docs/flow.md "Cost", docs/performance.md
// "(h) Flow in the joints") on the preprocessing benchmark's 2,000-joint network.
//
//   flow_bench [--quick] [--joints N] [--steps N] [--csv FILE]
//
// Scene: the target case of bench/preprocess_bench (a 100 m × 100 m body of rock, two random
// sets of N joints in all, dips 30° ± 10° and 120° ± 10°, traces uniform in 2–10 m, seed 42,
// mesh size 0.5 m), with water entering at 1 MPa where joints reach the left side and leaving
// at 0 where they reach the right side (residual aperture 0.1 mm, μ = 1 mPa·s, K_f = 2.2 GPa).
// --quick: 20 m, 80 joints (a check that every part runs, seconds).
//
// Two parts, one CSV row each per case:
// - `flow_solve` (steady and transient): the flow alone, as the effect does it at each step
//   (flow_effect.cpp begin_step): the apertures of the faces, the conductances and volumes, and
//   the volume balance (sparse LDLᵀ: factorise and solve; its first step analyses the ordering
//   too, timed apart). Median of `steps` steps; the network's nodes, segments and unknowns; the
//   steady case's inflow and outflow through the two sides (they must agree: the balance).
// - `run` (none, steady, transient): nmm-solve's run of the scene under gravity (base held,
//   sides on rollers; dynamic steps of 1 ms), without `flow` and with it (flow alone:
//   "coupled": false, so the mechanics are the same in the three runs and the difference is
//   what the flow adds to a step). The first step (CHOLMOD's analysis) apart, then the median
//   of the next `steps`; the runs interleaved step by step so that the machine's load falls on
//   all three alike.
// Times are the calling thread's CPU seconds (OpenBLAS and CHOLMOD on one thread: run with
// OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1), and wall seconds beside them; the load average at
// the start is in every row. Nothing in it fails on a timing.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_common.h"
#include "common/mesh.h"
#include "common/mesh_file.h"
#include "common/scene.h"
#include "common/stopwatch.h"
#include "preprocess/cover_cutter.h"
#include "solver/flow/flow_balance.h"
#include "solver/flow/flow_network.h"
#include "solver/output/solve_run.h"
#include "solver/discretisation/blas_kernels.h"

namespace {

/// The scene's text: preprocess_bench's random network (the same generator and seed) with the
/// flow boundaries, gravity and supports.
std::string scene_text(double side, int joints, double h, bool steady) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> centre(0, side), len(2, 10), scatter(-10, 10);
  const double pi = std::acos(-1.0);
  nlohmann::json list = nlohmann::json::array();
  for (int j = 0; j < joints; ++j) {
    const double dip = ((j % 2) ? 120.0 : 30.0) + scatter(rng);
    const double cx = centre(rng), cy = centre(rng), l = len(rng);
    const double dx = 0.5 * l * std::cos(dip * pi / 180), dy = 0.5 * l * std::sin(dip * pi / 180);
    list.push_back({{"set", "j"}, {"points", {{cx - dx, cy - dy}, {cx + dx, cy + dy}}}});
  }
  nlohmann::json doc = {
      {"name", "flow-bench"},
      {"gravity", {0, -9.81}},
      {"materials", {{"rock", {{"density", 2650}, {"young", 1e10}, {"poisson", 0.25}}}}},
      {"joint_sets",
       {{"j", {{"friction_deg", 30}, {"normal", {{"model", "constant"}, {"kn", 1e11}}},
               {"shear", {{"model", "constant"}, {"ks", 4e10}}}}}}},
      {"bodies", {{{"material", "rock"}, {"outer", {{0, 0}, {side, 0}, {side, side}, {0, side}}}}}},
      {"joints", list},
      {"mesh", {{"size", h}}},
      {"supports",
       {{{"points", {{0, 0}, {side, 0}}}, {"fix", "xy"}},
        {{"points", {{0, 0}, {0, side}}}, {"fix", "x"}},
        {{"points", {{side, 0}, {side, side}}}, {"fix", "x"}}}},
      {"flow",
       {{"aperture", {{"residual", 1e-4}, {"max", 1e-3}, {"coupled", false}}},
        {"boundaries",
         {{{"points", {{0, 0}, {0, side}}}, {"pressure", 1e6}},
          {{"points", {{side, 0}, {side, side}}}, {"pressure", 0}}}},
        {"steady", steady}}},
      {"solver", {{"time_step", 1e-3}, {"steps", 1000}}}};
  return doc.dump();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Timed {
  double cpu = 0, wall = 0;  // s
};
template <class F>
Timed timed(F&& f) {
  const double c0 = nmm::bench::thread_cpu_seconds();
  const nmm::Stopwatch w;
  f();
  return {nmm::bench::thread_cpu_seconds() - c0, w.seconds()};
}

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  bool quick = false;
  int joints = 2000, steps = 5;
  std::string csv_path = "flow_bench.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--joints") && i + 1 < argc) joints = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: flow_bench [--quick] [--joints N] [--steps N] [--csv FILE]\n");
      return 2;
    }
  }
  const double side = quick ? 20 : 100, h = 0.5;
  if (quick) joints = 80;
  const double load = nmm::bench::load_average();

  // The mesh (one cut for every case: the flow block does not change it).
  const std::string text = scene_text(side, joints, h, true);
  const nmm::SceneDef cut_scene = nmm::parse_scene(text, "flow-bench");
  nmm::Mesh mesh;
  const Timed cut = timed([&] { mesh = nmm::pre::build_mesh(cut_scene, "flow-bench"); });
  std::fprintf(stderr, "flow_bench: %d joints, %zu elements, cut in %.1f s\n", joints, mesh.element_count(), cut.wall);

  std::ofstream csv = nmm::bench::start_csv(
      csv_path,
      "part,case,joints,elements,nodes,segments,unknowns,first_cpu_ms,step_cpu_ms,step_wall_ms,"
      "network_cpu_ms,apertures_cpu_ms,balance_cpu_ms,inflow_m3_per_s,outflow_m3_per_s,steps,load_average\n");
  auto row = [&](const std::string& line) {
    csv << line;
    std::fputs(line.c_str(), stdout);
    std::fflush(stdout);
  };
  char line[512];

  // The flow alone, as the effect does it per step.
  for (const bool steady : {true, false}) {
    const nmm::SceneDef scene = nmm::parse_scene(scene_text(side, joints, h, steady), "flow-bench");
    std::unique_ptr<nmm::solve::FlowNetwork> network;
    const Timed built = timed([&] { network = std::make_unique<nmm::solve::FlowNetwork>(mesh, scene, "flow-bench"); });
    nmm::solve::FlowBalance balance(*network, scene, "flow-bench");
    const std::vector<double> loop_u(mesh.loop_xy.size(), 0.0);
    std::vector<double> p(network->nodes(), 0.0);
    std::vector<double> apertures_ms, balance_ms, step_cpu, step_wall;
    double first = 0;
    nmm::solve::FlowStepResult r;
    for (int k = 0; k <= steps; ++k) {
      std::vector<double> ap, c, v;
      const nmm::Stopwatch wall;
      const Timed a = timed([&] {
        ap = network->apertures(loop_u, 1e-4, 1e-3);
        c = network->conductances(ap, 1e-3);
        v = network->volumes(ap);
      });
      const Timed b = timed([&] { r = balance.step(p, c, v, 1e-3, 1e-3 * (k + 1)); });
      p = r.pressure;
      if (k == 0) {
        first = a.cpu + b.cpu;
        continue;
      }
      apertures_ms.push_back(1e3 * a.cpu);
      balance_ms.push_back(1e3 * b.cpu);
      step_cpu.push_back(1e3 * (a.cpu + b.cpu));
      step_wall.push_back(1e3 * wall.seconds());
    }
    std::size_t unknowns = 0;
    for (std::int32_t b : network->node_boundary()) unknowns += b < 0;
    std::snprintf(line, sizeof line, "flow_solve,%s,%d,%zu,%zu,%zu,%zu,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.6g,%.6g,%d,%.2f\n",
                  steady ? "steady" : "transient", joints, mesh.element_count(), network->nodes(),
                  network->segments().size(), unknowns, 1e3 * first, median(step_cpu), median(step_wall),
                  1e3 * built.cpu, median(apertures_ms), median(balance_ms), -r.outflow_rate[0], r.outflow_rate[1],
                  steps, load);
    row(line);
  }

  // nmm-solve's run without flow and with it (flow alone), interleaved step by step.
  mesh.scene_file = "flow-bench";
  mesh.scene_text = text;
  mesh.scene_sha256 = nmm::sha256(text);
  struct Case {
    const char* name;
    std::vector<std::string> sets;
    std::unique_ptr<nmm::solve::SolveRun> run;
    double first_cpu = 0, first_wall = 0;
    std::vector<double> cpu, wall;
  };
  std::vector<Case> cases;
  cases.push_back({"none", {"flow=null"}, nullptr, 0, 0, {}, {}});
  cases.push_back({"steady", {}, nullptr, 0, 0, {}, {}});
  cases.push_back({"transient", {"flow.steady=false"}, nullptr, 0, 0, {}, {}});
  for (Case& c : cases) {
    nmm::solve::SolveOptions o;
    o.sets = c.sets;
    c.run = std::make_unique<nmm::solve::SolveRun>(mesh, "flow-bench", o);
  }
  for (int k = 0; k <= steps; ++k)
    for (Case& c : cases) {
      const Timed t = timed([&] { c.run->advance(c.run->time_after(1), 1); });
      if (k == 0) {
        c.first_cpu = t.cpu;
        c.first_wall = t.wall;
      } else {
        c.cpu.push_back(1e3 * t.cpu);
        c.wall.push_back(1e3 * t.wall);
      }
    }
  for (Case& c : cases) {
    const nlohmann::json s = c.run->summary();
    std::size_t nodes = 0, segments = 0;
    if (s.contains("flow")) {
      nodes = s["flow"].value("nodes", std::size_t{0});
      segments = s["flow"].value("segments", std::size_t{0});
    }
    std::snprintf(line, sizeof line, "run,%s,%d,%zu,%zu,%zu,,%.3f,%.3f,%.3f,,,,,,%d,%.2f\n", c.name, joints,
                  mesh.element_count(), nodes, segments, 1e3 * c.first_cpu, median(c.cpu), median(c.wall), steps,
                  load);
    row(line);
    if (c.run->outcome().failed())
      std::fprintf(stderr, "flow_bench: run %s stopped: %s\n", c.name, c.run->outcome().status().c_str());
  }
  return 0;
}
