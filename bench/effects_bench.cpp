// Only the effects a scene calls for: what each effect costs per step, and where a step's time
// goes.
//
//   effects_bench [--quick] [--csv FILE]
//
// (a) contact off: one body, no joints (the continuum path: no contact detection, effects
//     without "contact") against the identical body with contact switched on by a joint that
//     lies outside it, and by a second tiny body far away. The jointless step should be fully
//     accounted for by the continuum parts (assembly, factorisation, solves, geometry update).
// (b) each effect switched off removes its cost: gravity, inertia (static), point loads, fixed
//     points — assembly and step time with and without.
// (c) where a step's time goes: a continuum scene of about 50,000 unknowns (as solver_bench) and
//     the brick wall N = 10 of contact_bench.
//
// Timing: each scene runs two warm-up steps (the first, timed on its own, includes CHOLMOD's
// symbolic analysis), then rounds of timed batches. The scenes compared in (a) and in (b) are
// all alive at once and take their batches in turn, each round starting with the next scene,
// so a drift in the machine's speed hits them alike. The batch with the smallest mean step is
// reported with its own breakdown (the least disturbed batch is the best estimate on a shared
// machine); comparisons also give the median over rounds of the ratio between the batches of
// one round. Nothing here fails on a timing. Results: bench/results/effects_bench.csv, read in
// docs/performance.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench_common.h"
#include "common/number_format.h"
#include "preprocess/cover_cutter.h"
#include "reference/brick_wall.h"
#include "reference/scene_pieces.h"
#include "solver/stepping/time_stepper.h"
#include "common/stopwatch.h"
#include "solver/discretisation/blas_kernels.h"

namespace {

// A square body of about `unknowns` unknowns (h = 1 m, as solver_bench), under gravity,
// dynamic, held by fixed points along its bottom.
struct SquareOptions {
  double unknowns = 2e4;
  bool gravity = true;
  bool dynamic = true;
  int fixed_points = 2;  // along the bottom (at least 2 for a static run)
  int loads = 0;         // point loads spread over the top
  bool joint_outside = false;  // a joint beside the body, outside it: contact on, nothing cut
  bool far_body = false;       // a second small body far away: contact on
};

nmm::SceneDef square(const SquareOptions& o, double* side_out = nullptr) {
  const double h = 1.0, side = std::round(std::sqrt(o.unknowns * h * h * std::sqrt(3.0) / 4));
  nmm::SceneDef s;
  s.materials.push_back({"rock", 2650, 1e10, 0.25, {}});
  nmm::JointSetDef js;
  js.name = "joint";
  js.friction_deg = 30;
  js.normal.kn = 2e11;  // Pa/m (constant joint stiffness, 20·E/h at h = 1 m)
  js.shear.ks = 8e10;   // Pa/m
  s.joint_sets.push_back(js);
  s.bodies.push_back(nmm::reference::box(0, 0, side, side));
  s.mesh_size = h;
  s.has_gravity = o.gravity;
  s.gravity = {0, o.gravity ? -9.81 : 0.0};
  s.solver.dynamic = o.dynamic;
  s.solver.static_mode = nmm::StaticMode::equilibrium;  // "inertia off": no mass term at all
  s.solver.time_step = 1e-3;
  for (int i = 0; i < o.fixed_points; ++i)
    s.fixed_points.push_back({0.1 + (side - 0.2) * i / std::max(o.fixed_points - 1, 1), 0.1});
  for (int i = 0; i < o.loads; ++i)
    s.loads.push_back({{0.1 + (side - 0.2) * i / std::max(o.loads - 1, 1), side - 0.1}, {1e3, -1e4}});
  if (o.joint_outside) s.joints.push_back({0, {{-5, 0}, {-5, side}}});
  if (o.far_body) s.bodies.push_back(nmm::reference::box(side + 50, 0, side + 51, 1));
  if (side_out) *side_out = side;
  return s;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : "+") + x;
  return s;
}

struct Measured {
  std::string section, scene, effects, status = "ok";
  int unknowns = 0;
  std::size_t elements = 0;
  int steps = 0;  // per batch
  double step = std::numeric_limits<double>::infinity(), detection = 0, assembly = 0, factorisation = 0, solves = 0, update = 0;  // s/step
  std::size_t analyses = 0;
  double iterations = 0, cuts = 0;  // per step
  double first_step = 0;            // s, the first step, with the symbolic analysis
  double paired_ratio = 0;          // median over rounds of step / the first scene's step
  std::string note;
};

// One scene being timed: its scene, mesh and stepper stay alive so that batches of several
// scenes can be interleaved (a drift in the machine's speed then hits all of them alike).
class Timed {
 public:
  Timed(nmm::SceneDef scene, const std::string& section, const std::string& name, int steps)
      : scene_(std::move(scene)), mesh_(nmm::pre::build_mesh(scene_, name)), st_(mesh_, scene_, name) {
    r_.section = section;
    r_.scene = name;
    r_.effects = join(run_effects(st_.view()));
    r_.unknowns = st_.view().space.unknowns();
    r_.elements = mesh_.element_count();
    r_.steps = steps;
  }
  // Steps that are not timed in the batches; the first, which includes CHOLMOD's symbolic
  // analysis, is timed on its own (first_step()).
  void warm_up(int n) {
    const nmm::Stopwatch w0;
    if (n > 0 && advance(1)) first_step_ = w0.seconds();
    advance(n - 1);
  }
  double first_step() const { return first_step_; }
  // One batch of timed steps; the fastest batch is kept, with its own breakdown. Returns the
  // batch's mean step, s (0 if the run has stopped).
  double batch() {
    if (r_.status != "ok") return 0;
    const nmm::solve::StepTimings t0 = st_.view().timings;
    const std::size_t it0 = st_.view().state.iterations, cut0 = st_.view().state.cuts;
    const nmm::Stopwatch w0;
    if (!advance(r_.steps)) return 0;
    const double n = r_.steps, wall = w0.seconds() / n;
    const nmm::solve::StepTimings& t1 = st_.view().timings;
    if (wall < r_.step) {
      r_.step = wall;
      r_.detection = (t1.contact_detection - t0.contact_detection) / n;
      r_.assembly = (t1.assembly - t0.assembly) / n;
      r_.factorisation = (t1.factorisation - t0.factorisation) / n;
      r_.solves = (t1.solves - t0.solves) / n;
      r_.update = (t1.geometry_update - t0.geometry_update) / n;
      r_.iterations = static_cast<double>(st_.view().state.iterations - it0) / n;
      r_.cuts = static_cast<double>(st_.view().state.cuts - cut0) / n;
    }
    r_.analyses = st_.view().system.analyses();
    return wall;
  }
  Measured& result() { return r_; }

 private:
  // Contact scenes go through run_until (step control); the others take plain steps.
  bool advance(int n) {
    if (r_.status != "ok") return false;
    const double dt = scene_.solver.time_step;
    if (!st_.view().contacts.active()) {
      for (int i = 0; i < n; ++i) st_.step(dt);
      return true;
    }
    const nmm::Outcome ran = st_.run_until(st_.view().state.time + n * dt, [](std::int64_t) {});
    if (!ran.ok()) r_.status = "stopped: " + ran.reason.substr(0, 60);
    return ran.ok();
  }
  nmm::SceneDef scene_;
  nmm::Mesh mesh_;
  nmm::solve::TimeStepper st_;
  Measured r_;
  double first_step_ = 0;
};

// Times several scenes side by side: warm-up, then `rounds` rounds of one batch each.
std::vector<Measured> measure_together(const std::vector<std::pair<nmm::SceneDef, std::string>>& scenes,
                                       const std::string& section, int warmup, int steps, int rounds) {
  std::vector<std::unique_ptr<Timed>> runs;
  for (const auto& [scene, name] : scenes) {
    runs.push_back(std::make_unique<Timed>(scene, section, name, steps));
    runs.back()->warm_up(warmup);
  }
  // ratios[i][r]: scene i's batch against scene 0's batch of the same round (paired, so that a
  // slow round weighs on both).
  std::vector<std::vector<double>> ratios(runs.size());
  for (int r = 0; r < rounds; ++r) {  // each round starts with the next scene
    std::vector<double> wall(runs.size(), 0);
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const std::size_t k = (i + r) % runs.size();
      wall[k] = runs[k]->batch();
    }
    for (std::size_t i = 0; i < runs.size(); ++i)
      if (wall[0] > 0 && wall[i] > 0) ratios[i].push_back(wall[i] / wall[0]);
  }
  std::vector<Measured> out;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    out.push_back(runs[i]->result());
    out.back().first_step = runs[i]->first_step();
    std::vector<double>& q = ratios[i];
    if (!q.empty()) {
      std::sort(q.begin(), q.end());
      out.back().paired_ratio = q.size() % 2 ? q[q.size() / 2] : 0.5 * (q[q.size() / 2 - 1] + q[q.size() / 2]);
    }
  }
  return out;
}

void write(std::ofstream& csv, const Measured& r) {
  const double ms = 1e3;
  const double other = r.step - r.detection - r.assembly - r.factorisation - r.solves - r.update;
  char line[1024];
  std::snprintf(line, sizeof line,
                "%s,%s,%s,%d,%zu,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%zu,%.2f,%.2f,%.3f,%s,%s\n",
                r.section.c_str(), r.scene.c_str(), r.effects.c_str(), r.unknowns, r.elements,
                r.steps, r.step * ms, r.detection * ms, r.assembly * ms, r.factorisation * ms,
                r.solves * ms, r.update * ms, other * ms, r.analyses, r.iterations, r.cuts,
                r.first_step * ms, r.status.c_str(), r.note.c_str());
  csv << line;
  std::fputs(line, stdout);
  std::fflush(stdout);
}

std::string percent(const char* what, double x) {
  return std::string(what) + " " + nmm::format_signed(100 * x, 1) + " %";
}

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  bool quick = false;
  std::string csv_path = "effects_bench.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: effects_bench [--quick] [--csv FILE]\n");
      return 2;
    }
  }
  const double big = quick ? 1e4 : 5e4, mid = quick ? 5e3 : 2e4;
  const int steps = quick ? 5 : 10, many = quick ? 200 : 1000, rounds = quick ? 3 : 5;
  const char* header =
      "section,scene,effects,unknowns,elements,steps_per_batch,step_ms,contact_detection_ms,"
      "assembly_ms,factorisation_ms,solves_ms,geometry_update_ms,other_ms,symbolic_analyses,"
      "iterations_per_step,cuts_per_step,first_step_ms,status,note\n";
  std::ofstream csv = nmm::bench::start_csv(csv_path, header);

  // (a) Contact off for a jointless single body; the same body with contact switched on.
  SquareOptions a;
  a.unknowns = big;
  SquareOptions a2o = a, a3o = a;
  a2o.joint_outside = true;
  a3o.far_body = true;
  std::vector<Measured> ra = measure_together({{square(a), "one body no joints"},
                                               {square(a2o), "same body + joint outside it (contact on)"},
                                               {square(a3o), "same body + 1 m block 50 m away (contact on)"}},
                                              "a", 2, steps, 2 * rounds);
  Measured a1 = ra[0];
  {
    const double parts = a1.detection + a1.assembly + a1.factorisation + a1.solves + a1.update;
    ra[0].note = percent("step beyond its continuum parts:", a1.step / parts - 1);
    for (std::size_t i = 1; i < ra.size(); ++i) {
      char note[200];
      std::snprintf(note, sizeof note,
                    "step vs no joints: fastest batches %+.1f %%; median of paired batches %+.1f %%",
                    100 * (ra[i].step / a1.step - 1), 100 * (ra[i].paired_ratio - 1));
      ra[i].note = note;
    }
  }
  for (const Measured& r : ra) write(csv, r);

  // (b) Each effect off removes its cost.
  SquareOptions all;
  all.unknowns = mid;
  all.fixed_points = many;
  all.loads = many;
  std::vector<std::pair<std::string, SquareOptions>> variants;
  variants.emplace_back("all effects", all);
  SquareOptions v = all;
  v.gravity = false;
  variants.emplace_back("gravity off", v);
  v = all;
  v.dynamic = false;
  variants.emplace_back("static (inertia off)", v);
  v = all;
  v.loads = 0;
  variants.emplace_back("point loads off", v);
  v = all;
  v.fixed_points = 0;
  variants.emplace_back("fixed points off", v);
  v = all;
  v.gravity = false;
  v.loads = 0;
  v.fixed_points = 0;
  variants.emplace_back("elasticity + inertia only", v);
  v = all;
  v.gravity = false;
  v.dynamic = false;
  v.loads = 0;
  v.fixed_points = 2;
  variants.emplace_back("static elasticity + 2 fixed points", v);
  std::vector<std::pair<nmm::SceneDef, std::string>> bs;
  for (const auto& [label, o] : variants) {
    char name[128];
    std::snprintf(name, sizeof name, "%s (%d loads / %d fixed points)", label.c_str(), o.loads,
                  o.fixed_points);
    bs.emplace_back(square(o), name);
  }
  std::vector<Measured> rb = measure_together(bs, "b", 2, steps, rounds);
  for (std::size_t i = 1; i < rb.size(); ++i) {
    char note[160];
    std::snprintf(note, sizeof note,
                  "assembly %+.3f ms and step %+.3f ms vs all effects (paired batches: step %+.1f %%)",
                  1e3 * (rb[i].assembly - rb[0].assembly), 1e3 * (rb[i].step - rb[0].step),
                  100 * (rb[i].paired_ratio - 1));
    rb[i].note = note;
  }
  for (const Measured& r : rb) write(csv, r);

  // (c) Where a step's time goes: the continuum scene of (a) is a1; the brick wall N = 10.
  Measured c1 = a1;
  c1.section = "c";
  c1.note = "continuum";
  write(csv, c1);
  {
    const int n = quick ? 5 : 10;
    const nmm::SceneDef s = nmm::reference::brick_wall(n, true);  // the wall of contact_bench
    char name[64];
    std::snprintf(name, sizeof name, "brick wall N = %d", n);
    Timed wall(s, "c", name, quick ? 10 : 20);
    wall.warm_up(5);
    wall.batch();
    Measured c2 = wall.result();
    c2.first_step = wall.first_step();
    c2.note = "contact (as contact_bench; one batch after 5 warm-up steps)";
    write(csv, c2);
  }
  return 0;
}
