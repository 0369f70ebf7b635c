// Contact cost: a staggered brick wall of N × N blocks settling under gravity on a held base.
//
//   contact_bench [--quick] [--csv FILE]
//
// Bricks 1 m × 0.5 m, odd rows shifted by half a brick, all touching their neighbours (one
// interface set, penalty 20·E), mesh size 0.5 m, dynamic, Δt = 1e-3 s. Each wall takes 5
// warm-up steps, then 20 timed steps. The CSV gives time per step and where it goes, and the
// contact detection time against the number of contact-candidate edges (the broad phase should
// grow about linearly). Issue-4 target: time per step growing no faster than about blocks^1.3.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "cover_cutter.h"
#include "scene_builders.h"  // the brick wall, the same scene the static-analysis test uses
#include "time_stepper.h"

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string csv_path = "contact_bench.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: contact_bench [--quick] [--csv FILE]\n");
      return 2;
    }
  }
  const std::vector<int> sizes = quick ? std::vector<int>{5, 10} : std::vector<int>{10, 20, 30};
  std::ofstream csv(csv_path);
  const char* header =
      "wall_n,blocks,elements,unknowns,contact_edges,contacts,step_ms,detection_ms,assembly_ms,"
      "factorisation_ms,solves_ms,update_ms,iterations_per_step,cuts,status\n";
  csv << header;
  std::fputs(header, stdout);
  for (int n : sizes) {
    const nmm::SceneDef s = nmm::test::brick_wall(n, true);
    const nmm::Mesh m = nmm::pre::build_mesh(s, "bench");
    nmm::solve::TimeStepper st(m, s, "bench");
    std::string status = st.run_until(5e-3, [](std::int64_t) {});
    const nmm::solve::StepTimings t0 = st.timings();
    const std::size_t it0 = st.open_close_iterations(), cuts0 = st.time_step_cuts();
    std::int64_t steps = 0;
    const auto w0 = Clock::now();
    if (status == "ok") status = st.run_until(25e-3, [&](std::int64_t) { ++steps; });
    const double wall = since(w0);
    const nmm::solve::StepTimings& t1 = st.timings();
    const double k = 1e3 / std::max<std::int64_t>(steps, 1);
    char line[512];
    std::snprintf(line, sizeof line,
                  "%d,%zu,%zu,%d,%zu,%zu,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.2f,%zu,%s\n", n,
                  m.block_count(), m.element_count(), st.unknowns(), m.contact_edge.size(),
                  st.contacts().contacts().size(), wall * k,
                  (t1.contact_detection - t0.contact_detection) * k, (t1.assembly - t0.assembly) * k,
                  (t1.factorisation - t0.factorisation) * k, (t1.solves - t0.solves) * k,
                  (t1.geometry_update - t0.geometry_update) * k,
                  static_cast<double>(st.open_close_iterations() - it0) / std::max<std::int64_t>(steps, 1),
                  st.time_step_cuts() - cuts0, status == "ok" ? "ok" : "failed");
    csv << line;
    std::fputs(line, stdout);
    std::fflush(stdout);
  }
  return 0;
}
