// nmm-preprocess SCENE.json -o MESH.nmm
//
// Reads a scene, checks it, cuts the covers (cover_cutter.h) and writes the binary mesh file
// atomically. Bad input of any kind: one line on stderr, exit status 2, no output file.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "preprocess/cover_cutter.h"
#include "preprocess/joint_network.h"
#include "common/json_set.h"
#include "common/vtk_writer.h"
#include "common/command_line.h"
#include "common/error.h"
#include "common/mesh_file.h"
#include "nmm_version.h"
#include "common/scene.h"
#include "common/scene_checks.h"
#include "common/ring_geometry.h"
#include "preprocess/scene_geometry.h"
#include "common/stopwatch.h"
#include "common/whole_file.h"

namespace {

// Sizes past which the preprocessor talks (docs/preprocess.md, "Large meshes"): stages are
// reported from kStagesFrom triangles on (a few seconds of cutting), and a warning is printed
// from kWarnFrom, where a cut takes minutes and the mesh file tens of MB (measured there).
constexpr double kStagesFrom = 2e4;
constexpr double kWarnFrom = 5e5;

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
    const std::string scene_file = scene_path;
    std::string text = nmm::read_text_file(scene_path);
    nlohmann::json base;
    if (!sets.empty()) {
      // --set edits the scene before anything is built (json_set.h); the mesh embeds the result.
      nlohmann::json doc = nmm::parse_json_text(text, scene_path);
      base = doc;
      for (const std::string& set : sets) nmm::apply_set(doc, set);
      text = doc.dump(1) + "\n";
      scene_path += " with --set";
    }
    nmm::SceneDef scene;
    try {
      scene = nmm::parse_scene(text, scene_path);
    } catch (const nmm::InputError& e) {
      // A misspelt joint set or material in a --set: "no joint set 'beding'; joint sets are: ..."
      if (!sets.empty()) nmm::throw_if_misspelt_name(base, nmm::parse_json_text(text, scene_path), e);
      throw;
    }
    // Generated joint sets (docs/joint-networks.md): the mesh embeds the explicit scene, with
    // the generated joints listed and the generate blocks removed, so that nmm-solve and
    // nmm-inspect re-parse exactly the geometry that was cut.
    bool has_generated = false;
    for (const auto& set : scene.joint_sets) has_generated = has_generated || set.generated;
    if (has_generated || !export_path.empty()) {
      const nlohmann::json doc = nmm::parse_json_text(text, scene_path);
      const nlohmann::json expanded = nmm::pre::explicit_scene(doc, scene);
      if (has_generated) {
        text = expanded.dump(1) + "\n";
        scene = nmm::scene_from_json(expanded, scene_path + " (generated joints)");
      }
    }
    nmm::pre::check_scene_geometry(scene, scene_path);
    // The warnings go out once the cut has succeeded, so that a scene the cut refuses gets its
    // one error line alone (bad input: one line on stderr); a large cut, which takes minutes,
    // gives them at its start instead.
    std::vector<std::string> warnings = nmm::check_scene_usability(scene, scene_path, !strict_joints);
    auto flush_warnings = [&warnings] {
      for (const std::string& w : warnings) std::cerr << w << "\n";
      warnings.clear();
    };
    // Triangles of side h covering the bodies' bounding area: the cost driver of the cut.
    double area = 0;
    for (const nmm::BodyDef& b : scene.bodies) area += nmm::ring_area(b.outer);
    const double triangles = area / (0.4330127 * scene.mesh_size * scene.mesh_size);
    if (triangles >= kWarnFrom) {
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "%s: /mesh/size: warning: about %.3g triangles at mesh size %g m: the cut takes "
                    "minutes and the mesh file is large (docs/preprocess.md, Large meshes)",
                    scene_path.c_str(), triangles, scene.mesh_size);
      warnings.emplace_back(buf);
    }
    const bool stages = triangles >= kStagesFrom;
    if (stages) {
      flush_warnings();
      std::fprintf(stderr, "nmm-preprocess: cutting covers (about %.3g triangles)...\n", triangles);
    }
    nmm::pre::CutTimings cut;
    nmm::Mesh mesh = nmm::pre::build_mesh(scene, scene_path, &cut);
    flush_warnings();
    if (stages)
      std::fprintf(stderr,
                   "nmm-preprocess: cut in %.1f s (arrangement %.1f s, covers %.1f s); writing %s...\n",
                   cut.mesh_generation + cut.arrangement + cut.labelling + cut.covers,
                   cut.arrangement, cut.covers, out_path.c_str());
    mesh.scene_file = scene_file;
    mesh.scene_text = text;
    mesh.scene_sha256 = nmm::sha256(text);
    const nmm::Stopwatch t1;
    nmm::write_mesh_file(mesh, out_path);
    if (!export_path.empty()) nmm::write_file_atomically(export_path, text);
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
