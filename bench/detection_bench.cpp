// Contact detection alone (issue 11: "contact detection must cost a small fraction of a step"):
// the broad and narrow phase of solver/contact/contact_detection.cpp on the staggered brick walls of
// contact_bench after 3 static steps, repeated on the same configuration: each call building
// its Verlet list, and each reusing the list one call built (what most steps pay), with whether
// the two find the same contacts.
//
//   detection_bench [--sizes 10,20,30,50] [--reps 20] [--csv FILE] [--peer] [--mesh H] [--steps K] [--shi]
//
// --peer: the DDA code's walls of contact_bench --peer (reference/brick_wall.h peer_wall), mesh
// size H (default 2 m), after K static steps (default 3): what the 10,000- and 100,000-block
// walls of docs/performance.md (h) detect in a step (their search distance 2.5·g2·w0 grows with
// the wall's width: w0 is half the model's size). Open contacts are looked for as far as the
// run looks (the stepper's reach, min(d0, 0.05·h): step_control.h); --shi: d0 far, as before
// 2026-12-02.
//
// Times are the thread's CPU time (CLOCK_THREAD_CPUTIME_ID), fastest and median of `reps`
// calls: on a machine shared with other jobs the wall-clock time of a call includes the time
// the thread waits for a core, its CPU time does not. The counts (candidate edges and vertices,
// vertex–edge pairs reaching the narrow phase, contacts, element pairs near) do not depend on
// the machine. The step time to compare with is contact_bench's (bench/results/contact_bench.csv).

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "solver/contact/contact_detection.h"
#include "bench/bench_common.h"
#include "preprocess/cover_cutter.h"
#include "reference/brick_wall.h"
#include "solver/stepping/step_control.h"
#include "solver/stepping/time_stepper.h"

int main(int argc, char** argv) {
  std::vector<int> sizes{10, 20, 30, 50};
  int reps = 20;
  std::string csv_path = "detection_bench.csv";
  bool peer = false;
  double mesh_size = 2;
  int steps = 3;
  bool shi = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) sizes = nmm::bench::parse_sizes(argv[++i]);
    else if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) reps = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else if (!std::strcmp(argv[i], "--peer")) peer = true;
    else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc) mesh_size = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--shi")) shi = true;
    else {
      std::fprintf(stderr, "usage: detection_bench [--sizes 10,20,30,50] [--reps 20] [--csv FILE] [--peer] [--mesh H] [--steps K] [--shi]\n");
      return 2;
    }
  }
  const char* header =
      "wall_n,blocks,elements,candidate_edges,candidate_vertices,search_distance_m,pairs_tested,"
      "contacts,near_pairs,fastest_ms,median_ms,us_per_edge,reused_pairs_tested,reused_fastest_ms,"
      "reused_median_ms,reused_same_contacts,load_average,list_reach_m,list_edges,build_fastest_ms,open_gap_m\n";
  std::ofstream csv = nmm::bench::start_csv(csv_path, header);
  for (int n : sizes) {
    const nmm::SceneDef s = peer ? nmm::reference::peer_wall(n, n, false, mesh_size) : nmm::reference::brick_wall(n, false);
    const nmm::Mesh m = nmm::pre::build_mesh(s, "wall");
    nmm::solve::TimeStepper st(m, s, "wall");
    st.set_threads(1);
    st.run_until(steps * s.solver.time_step, [](std::int64_t) {});
    const nmm::solve::ContactTopology topo = nmm::solve::build_contact_topology(m);
    // The closed contacts of the last step, as the solver passes them.
    const nmm::solve::ClosedContacts closed = st.view().contacts.closed_contacts();
    // As time_stepper.cpp: search distance 2.5·g2·w0, new contacts at most 1e-3·h deep.
    const double d0 = 2.5 * s.solver.max_displacement_ratio * st.view().model.w0();
    // The run's reach for open contacts (step_control.h contact_reach), or d0 (--shi).
    const double open = shi ? d0 : std::min(d0, nmm::solve::StepControl::kReach * s.mesh_size);
    std::vector<double> times;
    std::size_t contacts = 0, near = 0;
    nmm::solve::DetectionStats stats;
    for (int r = 0; r < reps; ++r) {
      nmm::solve::DetectionStats one;
      nmm::solve::ElementPairs pairs;
      const double t0 = nmm::bench::thread_cpu_seconds();
      const auto found = nmm::solve::detect_contacts(topo, st.view().state.loop_xy, d0, 1e-3 * s.mesh_size, closed, &one, &pairs, nullptr, open);
      times.push_back(nmm::bench::thread_cpu_seconds() - t0);
      contacts = found.size();
      near = pairs.size();
      stats = one;
    }
    std::sort(times.begin(), times.end());
    // The same call reusing the Verlet list the first call built, as the steps after a build do:
    // the list's candidates only, the same contacts.
    const auto& xy = st.view().state.loop_xy;
    nmm::solve::CandidateList list;
    const auto fresh = nmm::solve::detect_contacts(topo, xy, d0, 1e-3 * s.mesh_size, closed, nullptr, nullptr, &list, open);
    std::vector<double> reused;
    nmm::solve::DetectionStats reused_stats;
    bool same = true;
    for (int r = 0; r < reps; ++r) {
      nmm::solve::DetectionStats one;
      const double t0 = nmm::bench::thread_cpu_seconds();
      const auto found = nmm::solve::detect_contacts(topo, xy, d0, 1e-3 * s.mesh_size, closed, &one, nullptr, &list, open);
      reused.push_back(nmm::bench::thread_cpu_seconds() - t0);
      same &= found.size() == fresh.size();
      for (std::size_t c = 0; same && c < found.size(); ++c)
        same = found[c].vertex == fresh[c].vertex && found[c].edge == fresh[c].edge && found[c].gap == fresh[c].gap;
      reused_stats = one;
    }
    std::sort(reused.begin(), reused.end());
    // The list's build alone: a list whose reach is too short for the search is built anew by
    // each call, whose other work is the reused call's.
    std::vector<double> built;
    for (int r = 0; r < reps; ++r) {
      nmm::solve::CandidateList fresh_list = list;
      fresh_list.reach = 0;
      const double t0 = nmm::bench::thread_cpu_seconds();
      nmm::solve::detect_contacts(topo, xy, d0, 1e-3 * s.mesh_size, closed, nullptr, nullptr, &fresh_list, open);
      built.push_back(nmm::bench::thread_cpu_seconds() - t0);
    }
    std::sort(built.begin(), built.end());
    char line[600];
    std::snprintf(line, sizeof line, "%d,%zu,%zu,%zu,%zu,%.4f,%zu,%zu,%zu,%.3f,%.3f,%.3f,%zu,%.3f,%.3f,%d,%.2f,%.4f,%zu,%.3f,%.4f\n", n,
                  m.block_count(), m.element_count(), topo.edges.size(), topo.vertices.size(), d0,
                  stats.pairs_tested, contacts, near, 1e3 * times.front(), 1e3 * times[times.size() / 2],
                  1e6 * times.front() / static_cast<double>(topo.edges.size()), reused_stats.pairs_tested,
                  1e3 * reused.front(), 1e3 * reused[reused.size() / 2], same ? 1 : 0, nmm::bench::load_average(),
                  list.reach, list.edges.size(), 1e3 * (built.front() - reused.front()), open);
    csv << line;
    std::fputs(line, stdout);
    std::fflush(stdout);
  }
  return 0;
}
