// A scene as nmm-preprocess cuts it: see preprocess_scene.h.
#include "preprocess/preprocess_scene.h"

#include <cstdio>
#include <utility>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/json_set.h"
#include "common/mesh_file.h"
#include "common/ring_geometry.h"
#include "common/scene_checks.h"
#include "preprocess/joint_network.h"
#include "preprocess/scene_geometry.h"

namespace nmm::pre {

PreparedScene prepare_scene(std::string text, const std::string& file,
                            const std::vector<std::string>& sets) {
  PreparedScene out;
  out.file = file;
  out.name = file;
  nlohmann::json base;
  if (!sets.empty()) {
    // --set edits the scene before anything is built (json_set.h); the mesh embeds the result.
    nlohmann::json doc = parse_json_text(text, file);
    base = doc;
    for (const std::string& set : sets) apply_set(doc, set);
    text = doc.dump(1) + "\n";
    out.name += " with --set";
  }
  try {
    out.scene = parse_scene(text, out.name);
  } catch (const InputError& e) {
    // A misspelt joint set or material in a --set: "no joint set 'beding'; joint sets are: ..."
    if (!sets.empty()) throw_if_misspelt_name(base, parse_json_text(text, out.name), e);
    throw;
  }
  // Generated joint sets (docs/joint-networks.md): the mesh embeds the explicit scene, with the
  // generated joints listed and the generate blocks removed, so that nmm-solve and nmm-inspect
  // re-parse exactly the geometry that was cut.
  bool has_generated = false;
  for (const auto& set : out.scene.joint_sets) has_generated = has_generated || set.generated;
  if (has_generated) {
    const nlohmann::json expanded = explicit_scene(parse_json_text(text, out.name), out.scene);
    text = expanded.dump(1) + "\n";
    out.scene = scene_from_json(expanded, out.name + " (generated joints)");
  }
  check_scene_geometry(out.scene, out.name);
  out.text = std::move(text);
  return out;
}

double estimated_triangles(const SceneDef& scene) {
  double area = 0;
  for (const BodyDef& b : scene.bodies) area += ring_area(b.outer);
  return area / (0.4330127 * scene.mesh_size * scene.mesh_size);
}

std::vector<std::string> scene_warnings(const PreparedScene& scene, bool strict_joints) {
  std::vector<std::string> warnings = check_scene_usability(scene.scene, scene.name, !strict_joints);
  const double triangles = estimated_triangles(scene.scene);
  if (triangles >= kLargeMeshTriangles) {
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "%s: /mesh/size: warning: about %.3g triangles at mesh size %g m: the cut takes "
                  "minutes and the mesh file is large (docs/preprocess.md, Large meshes)",
                  scene.name.c_str(), triangles, scene.scene.mesh_size);
    warnings.emplace_back(buf);
  }
  return warnings;
}

Mesh cut_scene(const PreparedScene& scene, CutTimings* timings) {
  Mesh mesh = build_mesh(scene.scene, scene.name, timings);
  mesh.scene_file = scene.file;
  mesh.scene_text = scene.text;
  mesh.scene_sha256 = sha256(scene.text);
  return mesh;
}

}  // namespace nmm::pre
