// A run's scene: the scene embedded in the mesh file with the run's variants applied.
//
// Variants: `--config VARIANT.json` is a JSON merge patch (RFC 7386) on the embedded scene, then
// each `--set a.b.c=VALUE` sets one field (VALUE is JSON; a bare word that is not JSON is taken
// as a string, so `--set joint_sets.j.normal.model=constant` works without shell quoting).
// Geometry — bodies, joints, mesh — cannot change without preprocessing again: a variant that
// touches it is refused (InputError, exit status 2).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::solve {

struct RunScene {
  SceneDef scene;            ///< validated scene the solver runs
  nlohmann::json effective;  ///< the scene document after all variants (written to the output)
  /// What errors found later (by the solver) call it: "MESH (embedded scene)", or "scene in
  /// MESH with --config FILE and --set" when variants made it
  std::string name;
};

/// Applies the variants to mesh.scene_text. mesh_path names the embedded scene in errors,
/// config_path ("" for none) the merge patch, and "--set" the command-line settings.
RunScene make_run_scene(const Mesh& mesh, const std::string& mesh_path,
                        const std::string& config_path, const std::vector<std::string>& sets);

/// The same with the merge patch's text in memory (the Python module's config={...}):
/// `config_name` names it in errors as config_path does ("" for none).
RunScene make_run_scene(const Mesh& mesh, const std::string& mesh_path,
                        const std::string& config_text, const std::string& config_name,
                        const std::vector<std::string>& sets);

}  // namespace nmm::solve
