// The single-joint specimen: scene and loading (joint_specimen.h).
#include "joint_specimen.h"

#include <nlohmann/json.hpp>

#include "error.h"

namespace nmm::reference {

SceneDef scene_with_joint_laws(const std::string& path) {
  nlohmann::json doc = parse_json_text(read_text_file(path), path);
  if (!doc.is_object() || !doc.contains("joint_sets") || !doc["joint_sets"].is_object())
    throw InputError(path, "/joint_sets", "a joint study needs the scene's joint sets (an object)");
  for (auto& [name, js] : doc["joint_sets"].items()) {
    js["normal"]["model"] = "bandis_barton";
    js["shear"]["model"] = "hyperbolic";
  }
  return scene_from_json(doc, path);
}

SceneDef joint_specimen_scene(const std::string& path) {
  SceneDef s = scene_with_joint_laws(path);
  if (s.joint_sets.size() != 1)
    throw InputError(path, "/joint_sets", "the single-joint study needs exactly one joint set");
  if (s.measure_points.size() != 2)
    throw InputError(path, "/measure_points",
                     "the single-joint study needs two points, just above and below the joint");
  return s;
}

void load_joint_specimen(SceneDef& s, double sigma_n, double tau) {
  s.loads.clear();
  const int n = 20;
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 0.5 : 1.0;
    s.loads.push_back({{2.0 * i / n, 2.0}, {0, -sigma_n * 2.0 / n * w}});
  }
  if (tau != 0)
    for (int i = 0; i < 10; ++i) s.loads.push_back({{0.1 + 0.2 * i, 1.02}, {tau * 2.0 / 10, 0}});
}

}  // namespace nmm::reference
