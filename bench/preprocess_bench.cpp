// Preprocessing time against elements and joints.
//
//   preprocess_bench [--quick] [--csv FILE]
//
// Scenes: a square body of side L with a random joint network of two sets (dips 30° ± 10° and
// 120° ± 10°, trace lengths uniform in [2, 10] m, centres uniform over the body; fixed seed),
// cut at several mesh sizes and joint counts. Writes one CSV row per run with the time of each
// phase of the cover cutter (s). The issue-2 target is the 100 m body, 2,000 joints, h = 0.5.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>

#include "bench/bench_common.h"
#include "preprocess/cover_cutter.h"
#include "common/mesh.h"
#include "common/scene.h"
#include "common/stopwatch.h"

namespace {

nmm::SceneDef make_scene(double side, int joints, double h, unsigned seed) {
  nmm::SceneDef s = nmm::bench::square_rock(side, h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> centre(0, side), len(2, 10), scatter(-10, 10);
  const double pi = std::acos(-1.0);
  for (int j = 0; j < joints; ++j) {
    const double dip = ((j % 2) ? 120.0 : 30.0) + scatter(rng);
    const double cx = centre(rng), cy = centre(rng), l = len(rng);
    const double dx = 0.5 * l * std::cos(dip * pi / 180), dy = 0.5 * l * std::sin(dip * pi / 180);
    s.joints.push_back({0, {{cx - dx, cy - dy}, {cx + dx, cy + dy}}});
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string csv_path = "preprocess_bench.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: preprocess_bench [--quick] [--csv FILE]\n");
      return 2;
    }
  }
  struct Case { double side; int joints; double h; };
  std::vector<Case> cases;
  if (quick) {
    cases = {{20, 80, 0.5}, {40, 320, 0.5}};
  } else {
    // Elements grow at fixed joints, then joints grow at fixed mesh size; last: the target.
    for (double h : {2.0, 1.0, 0.7, 0.5}) cases.push_back({100, 500, h});
    for (int j : {0, 250, 1000, 4000}) cases.push_back({100, j, 0.5});
    cases.push_back({100, 2000, 0.5});
  }
  std::ofstream csv(csv_path);
  csv << "side_m,joints,mesh_size_m,triangles,elements,physical_covers,blocks,contact_edges,"
         "mesh_s,arrangement_s,labelling_s,covers_s,total_s\n";
  for (const Case& c : cases) {
    const nmm::SceneDef s = make_scene(c.side, c.joints, c.h, 42);
    nmm::pre::CutTimings t;
    const nmm::Stopwatch t0;
    const nmm::Mesh m = nmm::pre::build_mesh(s, "bench", &t);
    const double total = t0.seconds();
    char line[512];
    std::snprintf(line, sizeof line, "%g,%d,%g,%zu,%zu,%zu,%zu,%zu,%.3f,%.3f,%.3f,%.3f,%.3f\n",
                  c.side, c.joints, c.h, m.triangle_count(), m.element_count(), m.cover_count(),
                  m.block_count(), m.contact_edge.size(), t.mesh_generation, t.arrangement,
                  t.labelling, t.covers, total);
    csv << line;
    std::fputs(line, stdout);
    std::fflush(stdout);
  }
  return 0;
}
