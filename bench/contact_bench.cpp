// Contact cost: staggered brick walls of N × N blocks settling under gravity on a held base,
// in DDA static mode and dynamic, the reference problem of tests/scene_builders.h.
//
//   contact_bench [--quick] [--sizes 10,20,30,50] [--csv FILE]
//
// Bricks 1 m × 0.5 m, odd rows shifted by half a brick, all touching their neighbours (one
// interface set, penalty 2e11 N/m, φ = 35°), mesh size 0.5 m, Δt = 1e-3 s. Each wall takes 5
// warm-up steps, then 20 timed steps (10 for walls above 30 × 30). The CSV gives per step: wall
// time and where it goes, open–close iterations, factorisations and triangular solve pairs,
// time-step cuts. Targets (issue 11, one core): < 1.5 factorisations per step in settling
// systems, the 30 × 30 static wall < 40 ms per step, the 20 × 20 dynamic wall < 25 ms per step,
// cost growing no faster than blocks^1.2. Run it with OMP_NUM_THREADS=1 for one core.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "cover_cutter.h"
#include "scene_builders.h"  // the brick wall, the same scene the static-analysis test uses
#include "time_stepper.h"

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{10, 20, 30, 50};
  std::string csv_path = "contact_bench.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) sizes = {5, 10};
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) sizes = nmm::bench::parse_sizes(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: contact_bench [--quick] [--sizes 10,20,30,50] [--csv FILE]\n");
      return 2;
    }
  }
  std::ofstream csv(csv_path);
  const char* header =
      "mode,wall_n,blocks,elements,unknowns,contacts,step_ms,detection_ms,assembly_ms,"
      "factorisation_ms,solves_ms,update_ms,iterations_per_step,factorisations_per_step,"
      "solves_per_step,cuts,status\n";
  csv << header;
  std::fputs(header, stdout);
  for (const bool dynamic : {false, true}) {
    for (int n : sizes) {
      const nmm::SceneDef s = nmm::test::brick_wall(n, dynamic);
      const nmm::Mesh m = nmm::pre::build_mesh(s, "bench");
      nmm::solve::TimeStepper st(m, s, "bench");
      std::string status = st.run_until(5e-3, [](std::int64_t) {});
      const nmm::solve::StepTimings t0 = st.timings();
      const std::size_t it0 = st.open_close_iterations(), cuts0 = st.time_step_cuts();
      std::int64_t steps = 0;
      const double timed = n > 30 ? 10e-3 : 20e-3;
      const auto w0 = Clock::now();
      if (status == "ok") status = st.run_until(5e-3 + timed, [&](std::int64_t) { ++steps; });
      const double wall = since(w0);
      const nmm::solve::StepTimings& t1 = st.timings();
      const double per = 1.0 / static_cast<double>(std::max<std::int64_t>(steps, 1));
      const double k = 1e3 * per;
      char line[600];
      std::snprintf(line, sizeof line,
                    "%s,%d,%zu,%zu,%d,%zu,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.2f,%.2f,%.2f,%zu,%s\n",
                    dynamic ? "dynamic" : "static", n, m.block_count(), m.element_count(),
                    st.unknowns(), st.contacts().contacts().size(), wall * k,
                    (t1.contact_detection - t0.contact_detection) * k, (t1.assembly - t0.assembly) * k,
                    (t1.factorisation - t0.factorisation) * k, (t1.solves - t0.solves) * k,
                    (t1.geometry_update - t0.geometry_update) * k,
                    static_cast<double>(st.open_close_iterations() - it0) * per,
                    static_cast<double>(t1.factorisations - t0.factorisations) * per,
                    static_cast<double>(t1.solves_count - t0.solves_count) * per,
                    st.time_step_cuts() - cuts0, status == "ok" ? "ok" : status.c_str());
      csv << line;
      std::fputs(line, stdout);
      std::fflush(stdout);
    }
  }
  return 0;
}
