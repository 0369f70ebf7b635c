// nmm-preprocess SCENE.json -o MESH.nmm
//
// Reads a scene, checks it and cuts the covers (preprocess_scene.h, as the Python module does),
// and writes the binary mesh file atomically. Bad input of any kind: one line on stderr, exit status 2, no output file.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/command_line.h"
#include "common/error.h"
#include "common/mesh_file.h"
#include "common/scene.h"
#include "common/stopwatch.h"
#include "common/whole_file.h"
#include "nmm_version.h"
#include "preprocess/preprocess_scene.h"

namespace {

// Stages are reported from kStagesFrom triangles on, a few seconds of cutting (docs/preprocess.md,
// "Large meshes"; the warning of a cut that takes minutes comes from scene_warnings()).
constexpr double kStagesFrom = 2e4;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nmm-preprocess: cut the covers of a scene and write the binary mesh file"};
  std::string scene_path, out_path;
  std::string export_path;
  std::vector<std::string> sets;
  bool quiet = false, timings = false, strict_joints = false;
  app.add_option("scene", scene_path, "scene file (JSON, comments allowed)")->required();
  app.add_option("-o,--output", out_path, "mesh file to write (.nmm)")->required();
  app.add_option("--export-scene", export_path,
                 "also write the explicit scene (generated joints listed) to this file");
  app.add_option("--set", sets,
                 "PATH=VALUE on the scene before preprocessing, e.g. "
                 "joint_sets.NAME.generate.seed=7 (another realisation; geometry is rebuilt)");
  app.add_flag("-q,--quiet", quiet, "print nothing on success");
  app.add_flag("--timings", timings, "print where the time went, on stderr");
  app.add_flag("--strict-joints", strict_joints,
               "a joint touching no body is an error (by default a warning names it)");
  app.set_version_flag("--version", std::string("nmm-preprocess ") + NMM_VERSION);
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-preprocess"); status >= 0)
    return status;

  try {
    const nmm::Stopwatch t0;
    // The scene as cut (preprocess_scene.h): --set applied, generated joints listed, checked.
    const nmm::pre::PreparedScene scene =
        nmm::pre::prepare_scene(nmm::read_text_file(scene_path), scene_path, sets);
    // The warnings go out once the cut has succeeded, so that a scene the cut refuses gets its
    // one error line alone (bad input: one line on stderr); a large cut, which takes minutes,
    // gives them at its start instead.
    std::vector<std::string> warnings = nmm::pre::scene_warnings(scene, strict_joints);
    auto flush_warnings = [&warnings] {
      for (const std::string& w : warnings) std::cerr << w << "\n";
      warnings.clear();
    };
    const double triangles = nmm::pre::estimated_triangles(scene.scene);
    const bool stages = triangles >= kStagesFrom;
    if (stages) {
      flush_warnings();
      std::fprintf(stderr, "nmm-preprocess: cutting covers (about %.3g triangles)...\n", triangles);
    }
    nmm::pre::CutTimings cut;
    const nmm::Mesh mesh = nmm::pre::cut_scene(scene, &cut);
    flush_warnings();
    if (stages)
      std::fprintf(stderr,
                   "nmm-preprocess: cut in %.1f s (arrangement %.1f s, covers %.1f s); writing %s...\n",
                   cut.mesh_generation + cut.arrangement + cut.labelling + cut.covers,
                   cut.arrangement, cut.covers, out_path.c_str());
    const nmm::Stopwatch t1;
    nmm::write_mesh_file(mesh, out_path);
    if (!export_path.empty()) nmm::write_file_atomically(export_path, scene.text);
    const double write_s = t1.seconds();
    const double total_s = t0.seconds();
    if (!quiet)
      std::printf("%s: %zu nodes, %zu triangles, %zu physical covers, %zu manifold elements, "
                  "%zu blocks, area %.9g m²\n",
                  out_path.c_str(), mesh.node_count(), mesh.triangle_count(), mesh.cover_count(),
                  mesh.element_count(), mesh.block_count(), nmm::total_area(mesh));
    if (timings)
      std::fprintf(stderr,
                   "timings (s): mesh %.3f, arrangement %.3f, labelling %.3f, covers %.3f, "
                   "write %.3f, total %.3f\n",
                   cut.mesh_generation, cut.arrangement, cut.labelling, cut.covers, write_s,
                   total_s);
  } catch (const std::bad_alloc&) {
    std::cerr << scene_path << ": out of memory while cutting covers (use a larger mesh.size)\n";
    return nmm::kExitBadInput;
  } catch (...) {
    return nmm::exit_status_of_current_exception("nmm-preprocess");
  }
  return nmm::kExitOk;
}
