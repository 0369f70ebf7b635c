// Prints the state hash (summary.json's state_hash: SHA-256 of the run state, the contact history
// and the mesh) of every reference problem after a short run of its own, and its physical figures
// (the measure points' displacements and the largest of an element vertex, m), after a first
// line naming the platform:
//   platform LIBRARY | KERNELS | COMPILER       (the BLAS, its kernel set, the compiler)
//   reference.NAME STEPS HASH
//   figures reference.NAME UX0 UY0 UX1 UY1 ...
// tests/state_hashes.py compares these lines (with the data/ scenes' hashes) against the table
// tests/state_hashes.txt: on a platform the table has, a change of layout must leave every hash
// bit for bit; elsewhere the figures must match within round-off.
// Each run is short (a few steps, or the problem's one static step): long enough that the
// scene's geometry, materials, joints, loads and supports all reach the state.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reference/brick_wall.h"
#include "reference/cantilever.h"
#include "preprocess/cover_cutter.h"
#include "common/error.h"
#include "reference/joint_specimen.h"
#include "reference/kirsch.h"
#include "common/scene.h"
#include "reference/slides.h"
#include "reference/sliding_block.h"
#include "solver/stepping/time_stepper.h"
#include "reference/wave_bar.h"
#include "solver/discretisation/blas_info.h"
#include "nmm_version.h"
#include "common/whole_file.h"
#include "solver/discretisation/blas_kernels.h"

namespace {

using nmm::SceneDef;

// Runs `steps` steps of the scene's own Δt (one step of 1 s for a static scene) and prints the
// line; a run that stops early prints its status instead of ok.
void run(const std::string& name, const SceneDef& s, int steps) {
  const nmm::Mesh m = nmm::pre::build_mesh(s, name);
  nmm::solve::TimeStepper st(m, s, name);
  nmm::Outcome status;
  if (!s.solver.dynamic && s.solver.static_mode == nmm::StaticMode::equilibrium) {
    for (int i = 0; i < steps; ++i) st.step(1.0);
  } else {
    status = st.run_until(steps * s.solver.time_step, [](std::int64_t) {});
  }
  std::printf("reference.%s %d %s%s%s\n", name.c_str(), steps, state_hash(st.view()).c_str(),
              status.ok() ? "" : " ", status.ok() ? "" : status.status().c_str());
  // Figures: the measure points' displacements, then the largest displacement of an element
  // vertex (m; every problem has one, measure points or not).
  std::printf("figures reference.%s", name.c_str());
  for (const nmm::solve::TrackedPoint& p : st.view().state.measure) {
    const auto u = p.displacement();
    std::printf(" %.17g %.17g", u[0], u[1]);
  }
  double largest = 0;
  const std::vector<double>& xy = st.view().state.loop_xy;
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2)
    largest = std::max(largest, std::hypot(xy[i] - m.loop_xy[i], xy[i + 1] - m.loop_xy[i + 1]));
  std::printf(" %.17g\n", largest);
  std::fflush(stdout);
}

SceneDef from_json(const nlohmann::json& doc, const std::string& name) {
  return nmm::scene_from_json(doc, name);
}

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  if (argc != 2) {
    std::fprintf(stderr, "usage: reference_state_hashes DATA_DIR (the repository's data/)\n");
    return 2;
  }
  const std::string data = argv[1];
  const nmm::solve::BlasInfo blas = nmm::solve::blas_info();
  std::printf("platform %s | %s | %s\n", blas.library.c_str(), blas.core.empty() ? "-" : blas.core.c_str(),
              NMM_COMPILER);
  try {
    using namespace nmm::reference;
    run("sliding_block_tilted", sliding_block_tilted(30, 20), 100);
    run("sliding_block_tilted_dt2e-3_kn5E", sliding_block_tilted(30, 20, 0.5, 0, 2e-3, 5), 50);
    run("sliding_block_tilted_n1", sliding_block_tilted(30, 20, 0.5, 1), 20);
    run("sliding_block_incline", sliding_block_incline(30, 20), 50);
    run("sliding_block_incline_margin_n1", sliding_block_incline(30, 20, 0.5, 1, 1.5), 20);
    run("brick_wall_3_dynamic", brick_wall(3, true), 20);
    run("brick_wall_3_static", brick_wall(3, false), 5);
    run("cantilever", cantilever(0.5, 0), 1);
    run("cantilever_n1", cantilever(0.5, 1), 1);
    {
      KirschSetup k;
      k.h = 0.4;
      k.k0 = 0.5;
      k.b_over_a = 8;
      SceneDef s = kirsch_scene(k);
      run("kirsch", s, 1);
    }
    {
      const std::string path = data + "/single_joint.json";
      SceneDef s = nmm::scene_from_json(nmm::parse_json_text(nmm::read_text_file(path), path), path);
      load_joint_specimen(s, 5e6, 2e6);
      run("joint_specimen", s, 20);
      SceneDef laws = joint_specimen_scene(path);
      load_joint_specimen(laws, 5e6, 2e6);
      run("joint_specimen_laws", laws, 20);
    }
    run("block_on_plane", from_json(block_on_plane(30, 35).scene, "block_on_plane"), 20);
    run("planar_slide",
        from_json(planar_slide(5, 60, 30, 5, 25, 1e4).scene, "planar_slide"), 20);
    run("wave_bar", joint_wave_scene(JointWaveSetup{}), 40);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reference_state_hashes: %s\n", e.what());
    return 2;
  }
  return 0;
}
