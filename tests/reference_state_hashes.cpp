// Prints the state hash (summary.json's state_hash: SHA-256 of the run state, the contact history
// and the mesh) of every reference problem after a short run of its own, one line each:
//   reference.NAME STEPS HASH
// tests/state_hashes.py compares these lines (with the data/ scenes' hashes) against the table
// tests/state_hashes.txt: a change of layout must leave every one of them bit for bit.
// Each run is short (a few steps, or the problem's one static step): long enough that the
// scene's geometry, materials, joints, loads and supports all reach the state.
#include <cstdio>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "cover_cutter.h"
#include "error.h"
#include "fos_reference.h"
#include "joint_specimen.h"
#include "joint_wave.h"
#include "kirsch_opening.h"
#include "scene.h"
#include "scene_builders.h"
#include "time_stepper.h"

namespace {

using nmm::SceneDef;

// The cantilever of tests/test_solver_physics.cpp and nmm-study: L = 10 m, H = 1 m, clamped by
// fixed points every h/2 along x = 0, P = 1e5 N down at (L, H/2), one static step.
SceneDef cantilever(double h, int order) {
  const double L = 10, H = 1, P = 1e5;
  SceneDef s;
  s.materials.push_back({"rock", 2500, 1e10, 0.25});
  nmm::BodyDef b;
  b.material = 0;
  b.outer = {{0, 0}, {L, 0}, {L, H}, {0, H}};
  s.bodies.push_back(b);
  s.mesh_size = h;
  s.plane = nmm::PlaneKind::stress;
  const int n = static_cast<int>(std::ceil(H / (0.5 * h)));
  for (int i = 0; i <= n; ++i) s.fixed_points.push_back({0, H * i / n});
  s.loads.push_back({{L, H / 2}, {0, -P}});
  s.measure_points.push_back({L, H / 2});
  s.solver.dynamic = false;
  s.solver.static_mode = nmm::StaticMode::equilibrium;
  s.solver.cover_order = order;
  return s;
}

// Runs `steps` steps of the scene's own Δt (one step of 1 s for a static scene) and prints the
// line; a run that stops early prints its status instead of ok.
void run(const std::string& name, const SceneDef& s, int steps) {
  const nmm::Mesh m = nmm::pre::build_mesh(s, name);
  nmm::solve::TimeStepper st(m, s, name);
  std::string status = "ok";
  if (!s.solver.dynamic && s.solver.static_mode == nmm::StaticMode::equilibrium) {
    for (int i = 0; i < steps; ++i) st.step(1.0);
  } else {
    status = st.run_until(steps * s.solver.time_step, [](std::int64_t) {});
  }
  std::printf("reference.%s %d %s%s%s\n", name.c_str(), steps, st.state_hash().c_str(),
              status == "ok" ? "" : " ", status == "ok" ? "" : status.c_str());
  std::fflush(stdout);
}

SceneDef from_json(const nlohmann::json& doc, const std::string& name) {
  return nmm::scene_from_json(doc, name);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: reference_state_hashes DATA_DIR (the repository's data/)\n");
    return 2;
  }
  const std::string data = argv[1];
  try {
    using namespace nmm;
    run("sliding_block_tilted", test::sliding_block_tilted(30, 20), 100);
    run("sliding_block_tilted_n1", test::sliding_block_tilted(30, 20, 0.5, 1), 20);
    run("sliding_block_incline", test::sliding_block_incline(30, 20), 50);
    run("sliding_block_incline_margin_n1", test::sliding_block_incline(30, 20, 0.5, 1, 1.5), 20);
    run("brick_wall_3_dynamic", test::brick_wall(3, true), 20);
    run("brick_wall_3_static", test::brick_wall(3, false), 5);
    run("cantilever", cantilever(0.5, 0), 1);
    run("cantilever_n1", cantilever(0.5, 1), 1);
    {
      solve::KirschSetup k;
      k.h = 0.4;
      k.k0 = 0.5;
      k.b_over_a = 8;
      SceneDef s = solve::kirsch_scene(k);
      run("kirsch", s, 1);
    }
    {
      const std::string path = data + "/single_joint.json";
      SceneDef s = scene_from_json(parse_json_text(read_text_file(path), path), path);
      solve::load_joint_specimen(s, 5e6, 2e6);
      run("joint_specimen", s, 20);
    }
    run("block_on_plane", from_json(studies::block_on_plane(30, 35).scene, "block_on_plane"), 20);
    run("planar_slide",
        from_json(studies::planar_slide(5, 60, 30, 5, 25, 1e4).scene, "planar_slide"), 20);
    run("wave_bar", solve::joint_wave_scene(solve::JointWaveSetup{}), 40);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reference_state_hashes: %s\n", e.what());
    return 2;
  }
  return 0;
}
