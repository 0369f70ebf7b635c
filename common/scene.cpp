// Scene files: JSON with comments -> SceneDef, validated once.
//
// Every problem is reported as InputError(file, JSON pointer, message) for the first problem
// found, where the pointer (RFC 6901, e.g. /joints/3/points/1) names the value at fault and the
// message says what is wrong and what was expected. The checks run in a fixed order (unknown
// keys of an object first, so that a typo is reported as such rather than as the missing key it
// hides; then the parts in the order below, each after the parts it refers to), so the same bad
// file always gives the same message.
//
// Each part's keys are read in its own file of common/scene/ (scene.h lists them); this file
// reads the top-level keys, calls the parts in order and checks what spans parts (the mesh size
// against the bodies, the expected count of generated joints).
#include "common/scene.h"

#include <nlohmann/json.hpp>

#include "common/lattice.h"
#include "common/number_format.h"
#include "common/ring_geometry.h"
#include "common/scene/json_reader.h"

namespace nmm {

using nlohmann::json;

SceneDef parse_scene(const std::string& text, const std::string& file) {
  return scene_from_json(parse_json_text(text, file), file);
}

SceneDef scene_from_json(const json& doc, const std::string& file) {
  const JsonReader root(doc, file, "");
  root.check_keys({"name", "gravity", "plane", "materials", "joint_sets", "bodies", "joints",
                   "interface_set", "mesh", "fixed_points", "loads", "measure_points", "solver",
                   "supports", "tractions", "insitu_stress", "excavate", "base_acceleration", "water",
                   "fracture", "bolts", "absorbing", "flow"});
  SceneDef scene;

  if (root.has("name")) scene.name = root["name"].as_string();
  if (root.has("gravity")) {
    scene.has_gravity = true;
    scene.gravity = root["gravity"].as_bounded_pair("[gx, gy]", kMaxAcceleration);
  }
  if (root.has("plane"))
    scene.plane = root["plane"].as_choice({"strain", "stress"}, "plane") == 0 ? PlaneKind::strain
                                                                              : PlaneKind::stress;

  const JsonReader materials = root["materials"];
  for (const auto& [name, r] : materials.members())
    scene.materials.push_back(read_material(name, r));
  if (scene.materials.empty()) materials.fail("at least one material is required");

  if (const auto sets = root.optional("joint_sets"))
    for (const auto& [name, r] : sets->members())
      scene.joint_sets.push_back(read_joint_set(name, r));

  const JsonReader bodies = root["bodies"];
  bodies.expect_array();
  if (bodies.size() == 0) bodies.fail("at least one body is required");
  for (std::size_t i = 0; i < bodies.size(); ++i)
    scene.bodies.push_back(read_body(bodies[i], scene.materials));

  if (const auto joints = root.optional("joints")) {
    joints->expect_array();
    for (std::size_t i = 0; i < joints->size(); ++i)
      scene.joints.push_back(read_joint((*joints)[i], scene.joint_sets));
  }

  if (const auto iface = root.optional("interface_set"))
    scene.interface_set = find_by_name(scene.joint_sets, *iface, "joint set", "joint_sets");

  const JsonReader mesh = root["mesh"];
  mesh.check_keys({"size", "split_gap_ends"});
  scene.mesh_size = mesh.number("size", kPositive);
  if (mesh.has("split_gap_ends")) scene.split_gap_ends = mesh["split_gap_ends"].as_bool();
  // Every number derived from the mesh size (triangle and node counts, node coordinates) is
  // checked here, where the message can name /mesh/size (common/lattice.h).
  const std::string lattice = lattice_problem(scene.bodies, scene.mesh_size);
  if (!lattice.empty()) mesh["size"].fail(lattice);

  // Generated joint sets: the expected joint count over the bodies' bounding box stays bounded.
  for (const JointSetDef& set : scene.joint_sets) {
    if (!set.generated) continue;
    const Box box = bodies_box(scene.bodies);
    const JointGenerationDef& g = set.generate;
    const double intensity = g.p21 > 0 ? g.p21 : 1 / g.mean_spacing;
    const double expected = intensity * (box.x1 - box.x0) * (box.y1 - box.y0) / mean_length(g.length);
    if (expected > kMaxGeneratedJoints)
      root["joint_sets"][set.name]["generate"].fail(
          "about " + format_number(expected) + " joints expected over the bodies' box, more than " +
          format_number(kMaxGeneratedJoints) + "; lower p21 or raise the trace length");
  }

  if (const auto fixed = root.optional("fixed_points")) scene.fixed_points = read_points(*fixed);
  if (const auto loads = root.optional("loads")) read_loads(*loads, scene.loads, scene.load_tables);
  if (const auto measure = root.optional("measure_points"))
    scene.measure_points = read_points(*measure);

  if (const auto solver = root.optional("solver")) scene.solver = read_solver(*solver);

  if (const auto r = root.optional("supports")) scene.supports = read_supports(*r);
  if (const auto r = root.optional("tractions")) scene.tractions = read_tractions(*r);
  if (const auto r = root.optional("insitu_stress")) scene.insitu_stress = read_insitu(*r, scene);
  if (const auto r = root.optional("excavate")) scene.excavate = read_excavate(*r, scene.bodies.size());
  if (const auto r = root.optional("base_acceleration"))
    read_base_acceleration(*r, scene.base_acceleration_x, scene.base_acceleration_y);
  if (const auto r = root.optional("water")) scene.water = read_water(*r, scene);
  if (const auto r = root.optional("fracture")) scene.fracture = read_fracture(*r, scene);
  if (const auto r = root.optional("bolts")) scene.bolts = read_bolts(*r);
  if (const auto r = root.optional("absorbing")) scene.absorbing = read_absorbing(*r);
  if (const auto r = root.optional("flow")) scene.flow = read_flow(*r, scene);
  return scene;
}

}  // namespace nmm
