// What one solver output frame costs, and where it goes (docs/performance.md, "Output").
//
//   output_bench [--scene FILE.json] [--frames N] [--csv FILE]
//
// Scene: data/block_on_incline.json (default; its mesh as nmm-preprocess cuts it), stepped 50
// steps so that the frame holds a real state (displacements, stresses). Then N frames (default
// 100) are written into a temporary folder, each variant in turn:
//   level6_fsync_rebuild  zlib level 6 (Z_DEFAULT_COMPRESSION), fsync of every file and of its
//                         folder, the grid rebuilt from the mesh for every frame: how frames were
//                         written before
//   level1_fsync_rebuild  zlib level 1, the rest as before
//   level1_nofsync_rebuild  level 1, no fsync (the rename alone)
//   level0_nofsync_cached   no compression (zlib level 0, stored blocks), no fsync, grid cached
//   level1_nofsync_cached   level 1, no fsync, the grid built once (what OutputWriter does now)
//   level6_nofsync_cached   level 6, no fsync, grid cached
// and `writer` is OutputWriter::write_frame itself (frame + frames.pvd), as nmm-solve calls it.
// Columns: ms per frame (wall), bytes per frame; the load average is recorded, since the machine
// is shared. Nothing fails on a timing.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "atomic_file.h"
#include "bench_common.h"
#include "cover_cutter.h"
#include "output_writer.h"
#include "time_stepper.h"
#include "vtk_writer.h"
#include "vtu_compressed.h"

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
namespace fs = std::filesystem;
}  // namespace

int main(int argc, char** argv) {
  std::string scene_path = std::string(NMM_SOURCE_DIR) + "/data/block_on_incline.json";
  std::string csv_path = "output_bench.csv";
  int frames = 100;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--scene") && i + 1 < argc) scene_path = argv[++i];
    else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) frames = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: output_bench [--scene FILE.json] [--frames N] [--csv FILE]\n");
      return 2;
    }
  }
  std::ifstream in(scene_path);
  std::stringstream text;
  text << in.rdbuf();
  const nmm::SceneDef scene = nmm::parse_scene(text.str(), scene_path);
  const nmm::Mesh mesh = nmm::pre::build_mesh(scene, scene_path);
  nmm::solve::TimeStepper st(mesh, scene, scene_path);
  for (int i = 0; i < 50; ++i) st.step(scene.solver.time_step);
  const std::vector<double> stress = st.mean_stress();

  const fs::path dir = fs::temp_directory_path() / ("nmm_output_bench_" + std::to_string(::getpid()));
  fs::create_directories(dir / "frames");
  std::ofstream csv = nmm::bench::start_csv(
      csv_path, "variant,unknowns,elements,loop_vertices,frames,ms_per_frame,bytes_per_frame,load\n");

  // One frame by hand, as write_frame does it, with the variant's choices.
  auto frame_grid = [&](nmm::PolygonGrid grid) {
    const std::size_t nv = mesh.loop_vertex_count();
    std::vector<double> u(3 * nv, 0.0);
    for (std::size_t v = 0; v < nv; ++v) {
      grid.points[3 * v] = st.loop_xy()[2 * v];
      grid.points[3 * v + 1] = st.loop_xy()[2 * v + 1];
      u[3 * v] = st.state().loop_u[2 * v];
      u[3 * v + 1] = st.state().loop_u[2 * v + 1];
    }
    grid.point_data.clear();
    grid.add_point_array("displacement", 3, std::move(u));
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
  auto row = [&](const char* name, double seconds, double bytes) {
    char line[256];
    std::snprintf(line, sizeof line, "%s,%d,%zu,%zu,%d,%.3f,%.0f,%.2f\n", name, st.unknowns(),
                  mesh.element_count(), mesh.loop_vertex_count(), frames, 1e3 * seconds / frames,
                  bytes / frames, nmm::bench::load_average());
    csv << line;
    std::fputs(line, stdout);
  };
  for (const Variant& v : variants) {
    double bytes = 0;
    std::string pvd;
    const auto t0 = Clock::now();
    for (int f = 0; f < frames; ++f) {
      const nmm::PolygonGrid grid = frame_grid(v.cached ? cached : nmm::mesh_to_grid(mesh));
      const std::string data = nmm::vtu_compressed(grid, v.level);
      bytes += static_cast<double>(data.size());
      const auto sync = v.fsync ? nmm::Durability::synced : nmm::Durability::renamed;
      nmm::write_file_atomically((dir / ("frames/frame_" + std::to_string(f) + ".vtu")).string(), data, sync);
      pvd += "    <DataSet timestep=\"" + std::to_string(f) + "\" file=\"frames/frame_" + std::to_string(f) + ".vtu\"/>\n";
      nmm::write_file_atomically((dir / "frames.pvd").string(), "<VTKFile>\n" + pvd + "</VTKFile>\n", sync);
    }
    row(v.name, since(t0), bytes);
  }
  {
    nmm::solve::OutputWriter out(dir.string());
    nmm::solve::FrameFields fields{&st.loop_xy(), &st.state().loop_u, &stress};
    const auto t0 = Clock::now();
    for (int f = 0; f < frames; ++f) out.write_frame(f, f * 1e-3, mesh, fields);
    const double s = since(t0);
    double bytes = 0;
    for (const auto& e : fs::directory_iterator(dir / "frames"))
      if (e.path().filename().string().rfind("frame_0", 0) == 0) bytes += static_cast<double>(fs::file_size(e.path()));
    row("writer", s, bytes);
  }
  fs::remove_all(dir);
  return 0;
}
