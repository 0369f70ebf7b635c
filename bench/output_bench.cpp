// What one solver output frame costs, and where it goes (docs/performance.md, "Output").
//
//   output_bench [--scene FILE.json] [--mesh-size H] [--frames N] [--steps S] [--csv FILE]
//
// Scene: data/block_on_incline.json (default) cut at mesh size H (default 0.33 m: 2,854
// unknowns, the size of the run a user reported), stepped 50 steps so that a frame holds a real
// state (displacements, stresses). Then N frames (default 100) are written into a temporary
// folder by each variant (interleaved in 5 rounds):
//   level6_fsync_rebuild    zlib level 6 (Z_DEFAULT_COMPRESSION), fsync of every file and of its
//                           folder, the grid rebuilt from the mesh for every frame: how frames
//                           were written before
//   level1_fsync_rebuild    zlib level 1, the rest as before
//   level1_nofsync_rebuild  level 1, no fsync (the rename alone)
//   level0_nofsync_cached   no compression (zlib level 0, stored blocks), no fsync, grid cached
//   level1_nofsync_cached   level 1, no fsync, the grid built once (what OutputWriter does now)
//   level6_nofsync_cached   level 6, no fsync, grid cached
//   writer                  OutputWriter::write_frame itself (frame + frames.pvd), as nmm-solve
//                           calls it
// and then whole runs of S steps (default 1,400) through TimeStepper::run, as nmm-solve makes
// them, with a history.csv row at every step: frames at every step (output_every 1, the only way
// to a per-step history before solver.history_every), and history_every 1 with frames every 10
// and every 100 steps. Columns: ms per frame (wall) and bytes per frame; for the runs also the
// run's output seconds (summary.json timings.output) and wall seconds. The load average is
// recorded, since the machine is shared. Nothing fails on a timing.
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "bench/bench_common.h"
#include "preprocess/cover_cutter.h"
#include "solver/output/output_writer.h"
#include "solver/output/run_driver.h"
#include "common/stopwatch.h"
#include "solver/stepping/time_stepper.h"
#include "common/vtk_writer.h"
#include "common/vtu_compressed.h"
#include "solver/discretisation/blas_kernels.h"

namespace {
namespace fs = std::filesystem;
}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  std::string scene_path = std::string(NMM_SOURCE_DIR) + "/data/block_on_incline.json";
  std::string csv_path = "output_bench.csv";
  int frames = 100;
  double mesh_size = 0.33;
  long steps = 1400;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--scene") && i + 1 < argc) scene_path = argv[++i];
    else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) frames = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--mesh-size") && i + 1 < argc) mesh_size = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::stol(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: output_bench [--scene FILE.json] [--mesh-size H] [--frames N] "
                           "[--steps S] [--csv FILE]\n");
      return 2;
    }
  }
  std::ifstream in(scene_path);
  std::stringstream text;
  text << in.rdbuf();
  nmm::SceneDef scene = nmm::parse_scene(text.str(), scene_path);
  scene.mesh_size = mesh_size;
  const nmm::Mesh mesh = nmm::pre::build_mesh(scene, scene_path);
  nmm::solve::TimeStepper st(mesh, scene, scene_path);
  for (int i = 0; i < 50; ++i) st.step(scene.solver.time_step);
  const std::vector<double> stress = mean_stress(st.view());

  const fs::path dir = fs::temp_directory_path() / ("nmm_output_bench_" + std::to_string(::getpid()));
  fs::create_directories(dir / "frames");
  std::ofstream csv = nmm::bench::start_csv(
      csv_path, "variant,unknowns,elements,loop_vertices,frames,ms_per_frame,bytes_per_frame,run_steps,"
                "output_seconds,wall_seconds,load\n");

  // One frame by hand, as write_frame does it, with the variant's choices.
  auto frame_grid = [&](nmm::PolygonGrid grid) {
    const std::size_t nv = mesh.loop_vertex_count();
    std::vector<double> u(3 * nv, 0.0);
    for (std::size_t v = 0; v < nv; ++v) {
      grid.points[3 * v] = st.view().state.loop_xy[2 * v];
      grid.points[3 * v + 1] = st.view().state.loop_xy[2 * v + 1];
      u[3 * v] = st.view().state.loop_u[2 * v];
      u[3 * v + 1] = st.view().state.loop_u[2 * v + 1];
    }
    grid.point_data.clear();
    grid.add_point_array("displacement", 3, std::move(u));
    // The writer's cell arrays: the identifiers and the stress (output_writer.cpp).
    std::vector<nmm::GridArray> kept;
    for (nmm::GridArray& a : grid.cell_data)
      if (a.name == "element" || a.name == "block" || a.name == "body") kept.push_back(std::move(a));
    grid.cell_data = std::move(kept);
    grid.add_cell_array("stress", 3, stress);
    return grid;
  };
  struct Variant {
    const char* name;
    int level;
    bool fsync;
    bool cached;
  };
  const Variant variants[] = {{"level6_fsync_rebuild", 6, true, false},
                              {"level1_fsync_rebuild", 1, true, false},
                              {"level1_nofsync_rebuild", 1, false, false},
                              {"level0_nofsync_cached", 0, false, true},
                              {"level1_nofsync_cached", 1, false, true},
                              {"level6_nofsync_cached", 6, false, true}};
  const nmm::PolygonGrid cached = nmm::mesh_to_grid(mesh);
  auto row = [&](const std::string& name, int n, double seconds, double bytes, const std::string& run) {
    char line[320];
    std::snprintf(line, sizeof line, "%s,%d,%zu,%zu,%d,%.3f,%.0f,%s,%.2f\n", name.c_str(), st.view().space.unknowns(),
                  mesh.element_count(), mesh.loop_vertex_count(), n, 1e3 * seconds / n, bytes / n,
                  run.c_str(), nmm::bench::load_average());
    csv << line;
    std::fputs(line, stdout);
  };
  // Interleaved: 5 rounds, each variant writing a fifth of its frames in turn, so that the
  // shared machine's load falls on all of them alike.
  constexpr int kRounds = 5;
  constexpr std::size_t kVariants = sizeof variants / sizeof variants[0];
  double seconds[kVariants] = {}, written[kVariants] = {};
  std::string pvd[kVariants];
  nmm::solve::OutputWriter out((dir / "writer").string());
  const nmm::solve::FrameFields fields{&st.view().state.loop_xy, &st.view().state.loop_u, &stress};
  double writer_seconds = 0;
  for (int round = 0; round < kRounds; ++round) {
    const nmm::Stopwatch w0;
    for (int f = round * frames / kRounds; f < (round + 1) * frames / kRounds; ++f)
      out.write_frame(f, f * 1e-3, mesh, fields);
    writer_seconds += w0.seconds();
    for (std::size_t i = 0; i < kVariants; ++i) {
      const Variant& v = variants[i];
      const nmm::Stopwatch t0;
      for (int f = round * frames / kRounds; f < (round + 1) * frames / kRounds; ++f) {
        const nmm::PolygonGrid grid = frame_grid(v.cached ? cached : nmm::mesh_to_grid(mesh));
        const std::string data = nmm::vtu_compressed(grid, v.level);
        written[i] += static_cast<double>(data.size());
        const auto sync = v.fsync ? nmm::Durability::synced : nmm::Durability::renamed;
        nmm::write_file_atomically((dir / ("frames/frame_" + std::to_string(f) + ".vtu")).string(), data, sync);
        pvd[i] += "    <DataSet timestep=\"" + std::to_string(f) + "\" file=\"frames/frame_" + std::to_string(f) + ".vtu\"/>\n";
        nmm::write_file_atomically((dir / "frames.pvd").string(), "<VTKFile>\n" + pvd[i] + "</VTKFile>\n", sync);
      }
      seconds[i] += t0.seconds();
    }
  }
  for (std::size_t i = 0; i < kVariants; ++i) row(variants[i].name, frames, seconds[i], written[i], ",,");
  {
    double bytes = 0;
    for (const auto& e : fs::directory_iterator(dir / "writer" / "frames"))
      bytes += static_cast<double>(fs::file_size(e.path()));
    row("writer", frames, writer_seconds, bytes, ",,");
  }
  // Whole runs, history at every step.
  for (const long every : {1L, 10L, 100L}) {
    nmm::SceneDef run_scene = scene;
    run_scene.solver.steps = steps;
    run_scene.solver.output_every = every;
    run_scene.solver.history_every = 1;
    nmm::solve::TimeStepper runner(mesh, run_scene, scene_path);
    const fs::path run_dir = dir / ("run_" + std::to_string(every));
    nmm::solve::OutputWriter run_out(run_dir.string());
    const nlohmann::json summary = nmm::solve::run_to_end(runner, run_out);
    double bytes = 0;
    int n = 0;
    for (const auto& e : fs::directory_iterator(run_dir / "frames")) {
      bytes += static_cast<double>(fs::file_size(e.path()));
      ++n;
    }
    const double output = summary["timings"]["output"].get<double>();
    row("run_output_every_" + std::to_string(every), n, output, bytes,
        std::to_string(steps) + "," + std::to_string(output) + "," +
            std::to_string(summary["wall_seconds"].get<double>()));
  }
  fs::remove_all(dir);
  return 0;
}
