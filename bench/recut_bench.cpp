// What inserting a crack costs against the size of the model (docs/fracture.md "Cost").
//
//   recut_bench [--csv FILE]
//
// A square body of side L at mesh size h = 1 m (L = 22 m: about 10³ elements; 70 m: 10⁴;
// 220 m: 10⁵), and a crack of 5 segments, 2.5 m in all, cut into it near its centre as a run
// cuts one (preprocess/recut.h): finding the triangles it touches (a scan), the exact cut of
// those and their nodes' stars (cut_region), the splice into the mesh; then the run's state
// carried over (state_transfer.h) and what the stepper derives from a mesh built again (a
// TimeStepper on the cut mesh: model, contact set, sparse pattern). The whole cut of the body
// (build_mesh) is timed beside them. Each figure is the median of 5 repetitions, s.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "common/mesh.h"
#include "common/scene.h"
#include "common/stopwatch.h"
#include "preprocess/cover_cutter.h"
#include "preprocess/recut.h"
#include "solver/fracture/state_transfer.h"
#include "solver/stepping/time_stepper.h"
#include "solver/discretisation/blas_kernels.h"

namespace {

nmm::SceneDef square(double side) {
  nmm::SceneDef s = nmm::bench::square_rock(side, 1);  // its joint set: the cracks'
  s.materials[0].strength = {true, 5e6, 12e6, 35, 0};
  s.fracture.present = true;
  s.fracture.crack_set = 0;
  nmm::SupportDef base;
  base.points = {{0, 0}, {side, 0}};
  base.fix_x = base.fix_y = true;
  s.supports.push_back(base);
  s.solver.dynamic = false;
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  std::string csv_path;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csv_path = argv[++i];
  std::string csv = "side_m,elements,segments,region_triangles,find_s,cut_s,splice_s,recut_s,transfer_s,"
                    "rederive_s,build_mesh_s\n";
  std::printf("%8s %9s %6s %10s %10s %10s %10s %10s %10s %12s\n", "side m", "elements", "region", "find s",
              "cut s", "splice s", "recut s", "transfer s", "rederive s", "build_mesh s");
  for (const double side : {22.0, 70.0, 220.0}) {
    const nmm::SceneDef scene = square(side);
    std::vector<double> build, find, cut, splice, recut, transfer, rederive;
    nmm::Mesh old, now;
    nmm::pre::RecutMap map;
    for (int rep = 0; rep < 5; ++rep) {
      nmm::Stopwatch w;
      old = nmm::pre::build_mesh(scene, "bench");
      build.push_back(w.seconds());
      nmm::SceneDef cracked = scene;
      const std::size_t first = cracked.joints.size();
      const double c = side / 2 + 0.13;
      for (int k = 0; k < 5; ++k)  // a crack across a few elements, as one step grows it
        cracked.joints.push_back({0, {{c + 0.5 * k, c + 0.21 * k}, {c + 0.5 * (k + 1), c + 0.21 * (k + 1)}}});
      w.restart();
      now = nmm::pre::recut(old, cracked, first, "bench", map);
      recut.push_back(w.seconds());
      find.push_back(map.seconds_find);
      cut.push_back(map.seconds_cut);
      splice.push_back(map.seconds_splice);
      nmm::solve::TimeStepper before(old, scene, "bench");
      nmm::solve::RunState s = before.view().state;
      w.restart();
      nmm::solve::transfer_state(old, now, map, 2, s);
      transfer.push_back(w.seconds());
      w.restart();
      nmm::solve::TimeStepper after(now, cracked, "bench");
      rederive.push_back(w.seconds());
    }
    std::printf("%8.0f %9zu %6zu %10.4f %10.4f %10.4f %10.4f %10.4f %10.4f %12.4f\n", side, old.element_count(),
                map.region_triangles, median(find), median(cut), median(splice), median(recut), median(transfer),
                median(rederive), median(build));
    char row[400];
    std::snprintf(row, sizeof row, "%.0f,%zu,5,%zu,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", side, old.element_count(),
                  map.region_triangles, median(find), median(cut), median(splice), median(recut), median(transfer),
                  median(rederive), median(build));
    csv += row;
  }
  if (!csv_path.empty()) std::ofstream(csv_path) << csv;
  return 0;
}
