// The single-joint specimen: scene and loading (joint_specimen.h).
#include "reference/joint_specimen.h"

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/whole_file.h"

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

JointSetDef seed_shear_joint() {
  JointSetDef js;
  js.name = "joint";
  js.friction_deg = 30;
  js.normal.model = NormalModel::bandis_barton;
  js.normal.kni = 15.35e9;
  js.normal.vm = 0.227e-3;
  js.shear.model = ShearModel::hyperbolic;
  js.shear.ksi = 1e10;
  js.shear.rf = 0.9;
  return js;
}

SceneDef joint_specimen_scene(const JointSetDef& joint, double young, double h) {
  SceneDef s;
  s.materials.push_back({"rock", 2650, young, 0.25, {}});
  s.joint_sets.push_back(joint);
  s.interface_set = 0;
  s.mesh_size = h;
  s.plane = PlaneKind::stress;
  BodyDef base, top;
  base.material = top.material = 0;
  base.outer = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  top.outer = {{0, 1}, {2, 1}, {2, 2}, {0, 2}};
  s.bodies = {base, top};
  for (double x = 0.05; x < 2; x += 0.1) s.fixed_points.push_back({x, 0.02});
  s.measure_points = {{1.0, 1.0001}, {1.0, 0.9999}};
  s.solver.time_step = 1e-3;
  s.solver.dynamic_factor = 0;  // quasi-static: settles to equilibrium
  s.solver.max_displacement_ratio = 0.01;
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
