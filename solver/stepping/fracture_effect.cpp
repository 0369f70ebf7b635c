// Intact rock that breaks, as a change of the run's mesh: see fracture_effect.h.
#include "solver/stepping/fracture_effect.h"

#include <algorithm>
#include <cstdio>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/mesh_file.h"
#include "common/stopwatch.h"
#include "solver/contact/cohesive_law.h"
#include "solver/fracture/recut_check.h"
#include "solver/fracture/state_transfer.h"
#include "solver/fracture/tip_growth.h"

namespace nmm::solve {

namespace {
/// The run's scene with the crack segments as joints of its crack set (appended in order).
std::unique_ptr<SceneDef> cracked_scene(const SceneDef& scene, const std::vector<CrackSegment>& segments) {
  auto cracked = std::make_unique<SceneDef>(scene);
  for (const CrackSegment& c : segments) cracked->joints.push_back({cracked->fracture.crack_set, {c.a, c.b}});
  return cracked;
}
}  // namespace

Outcome FractureEffect::cascade(double t) const {
  return Outcome::stop(StopCode::fracture_cascade,
                       "cracks were still growing after " + std::to_string(max_per_step()) +
                           " re-cuts of the mesh within one step",
                       t);
}

bool FractureEffect::change(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name,
                            const RunState& solved, const std::vector<std::uint8_t>& removed, int dofs_per_cover,
                            RunState& start, const std::vector<ContactHistory>& history, NewMesh& out,
                            StepTimings& timings) {
  Stopwatch watch;
  std::vector<CrackSegment> segments = fracture_.find(mesh, scene, solved, removed);
  if (segments.empty() && any_toughness(scene)) {  // the strength broke nothing: tips that reach their toughness grow
    std::vector<std::uint8_t> skip = removed;
    const std::vector<std::uint8_t>& debris = fracture_.debris();
    if (skip.size() < mesh.element_count()) skip.resize(mesh.element_count(), 0);
    for (std::size_t e = 0; e < debris.size() && e < skip.size(); ++e) skip[e] = skip[e] || debris[e];
    const std::vector<double> pressure = face_pressures(mesh, scene, scene_name, solved);
    segments = grow_by_toughness(mesh, scene, fracture_.segments(), solved, skip, pressure.empty() ? nullptr : &pressure);
  }
  if (segments.empty()) {
    timings.fracture += watch.seconds();
    return false;
  }
  out.scene = cracked_scene(scene, segments);
  const std::size_t first = scene.joints.size();
  out.mesh = std::make_unique<Mesh>(pre::recut(mesh, *out.scene, first, scene_name, out.map));
  // The check mode (docs/fracture.md "Re-cutting"): a re-cut that is not the full cut is a
  // defect of the re-cut, not of the run's physics: it ends the run with the difference.
  if (recut_check_enabled())
    if (const std::string diff = recut_difference(mesh, *out.mesh, *out.scene, scene_name); !diff.empty())
      throw RunError("NMM_CHECK_RECUT: at t = " + std::to_string(start.time) + " s the re-cut of " +
                     std::to_string(segments.size()) + " crack segment(s) is not the full cut: " + diff);
  transfer_state(mesh, *out.mesh, out.map, dofs_per_cover, start);
  // New faces soften where a rock that can break has a fracture energy (cohesive_law.h).
  const bool cohesive = std::any_of(scene.materials.begin(), scene.materials.end(),
                                    [](const MaterialDef& m) { return cohesive_law(m.strength).on(); });
  out.history = transfer_history(history, mesh, *out.mesh, out.map, first, cohesive);
  fracture_.cut(segments, *out.mesh, out.map);
  timings.fracture += watch.seconds();
  return true;
}

std::vector<double> FractureEffect::face_pressures(const Mesh& mesh, const SceneDef& scene,
                                                  const std::string& scene_name, const RunState& s) {
  if (!scene.flow.present || !scene.flow.coupled || s.flow_pressure.empty()) return {};
  if (flow_mesh_ != &mesh || flow_mesh_vertices_ != mesh.loop_vertex_count() || !flow_network_) {
    flow_network_ = std::make_unique<FlowNetwork>(mesh, scene, scene_name);
    flow_mesh_ = &mesh;
    flow_mesh_vertices_ = mesh.loop_vertex_count();
  }
  return flow_network_->face_pressures(s.flow_pressure, mesh.loop_vertex_count());
}

bool FractureEffect::restart(const CheckpointSections& sections, const Mesh& mesh, const SceneDef& scene,
                             const std::string& path, NewMesh& out) {
  // A cracked run's checkpoint: its mesh and cracks come with the state.
  const auto section = [&](const char* tag) {
    const auto it = std::find_if(sections.begin(), sections.end(), [&](const auto& s) { return s.first == tag; });
    return it == sections.end() ? nullptr : &it->second;
  };
  const std::string* mesh_bytes = section("MESH");
  if (!mesh_bytes) return false;
  if (!scene.fracture.present || !section("FRACTURE"))
    throw InputError(path, "section MESH", "a cracked run's checkpoint: the scene needs its fracture block");
  out.mesh = std::make_unique<Mesh>(mesh_from_bytes(*mesh_bytes, path + " section MESH"));
  if (out.mesh->scene_sha256 != mesh.scene_sha256)
    throw InputError(path, "section MESH", "the cracked mesh of another scene");
  fracture_.load(*section("FRACTURE"), *out.mesh, path);
  out.scene = cracked_scene(scene, fracture_.segments());
  return true;
}

void FractureEffect::write_files(const OutputStep& out, const std::string& dir) const {
  if (!active()) return;
  std::string csv = "step,time,x0,y0,x1,y1,mode\n";
  char row[256];
  for (const CrackSegment& c : fracture_.segments()) {
    std::snprintf(row, sizeof row, "%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%s\n", static_cast<long long>(c.step), c.time,
                  c.a_now.x, c.a_now.y, c.b_now.x, c.b_now.y, c.mode == CrackMode::tensile ? "tensile" : "shear");
    csv += row;
  }
  write_file_atomically(dir + "/cracks.csv", csv);
  if (!fracture_.segments().empty()) {
    Mesh cracked = out.mesh;
    cracked.tool = "nmm-solve";  // the cracks were cut by the run, not by nmm-preprocess
    write_mesh_file(cracked, dir + "/cracked_mesh.nmm");
  }
}

void FractureEffect::checkpoint_sections(const Mesh& mesh, CheckpointSections& sections) const {
  if (fracture_.segments().empty()) return;
  sections.emplace_back("MESH", mesh_to_bytes(mesh));
  sections.emplace_back("FRACTURE", fracture_.save());
}

}  // namespace nmm::solve
