// Intact rock that breaks, as a change of the run's mesh: see fracture_effect.h.
#include "solver/stepping/fracture_effect.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/mesh_file.h"
#include "common/stopwatch.h"
#include "solver/contact/cohesive_law.h"
#include "solver/discretisation/model.h"
#include "solver/fracture/cohesive_starts.h"
#include "solver/fracture/crack_release.h"
#include "solver/fracture/recut_check.h"
#include "solver/fracture/state_transfer.h"
#include "solver/fracture/tip_growth.h"
#include "solver/stepping/run_view.h"

namespace nmm::solve {

namespace {
/// The run's scene with the crack segments as joints of its crack set (appended in order).
std::unique_ptr<SceneDef> cracked_scene(const SceneDef& scene, const std::vector<CrackSegment>& segments) {
  auto cracked = std::make_unique<SceneDef>(scene);
  for (const CrackSegment& c : segments) cracked->joints.push_back({cracked->fracture.crack_set, {c.a, c.b}});
  return cracked;
}

/// Marks the faces the effects load in the state s of a run on `mesh` (Effect::loaded_faces).
std::vector<std::uint8_t> loaded_faces(const Mesh& mesh, const RunState& s, const std::vector<Effect*>& effects) {
  std::vector<std::uint8_t> loaded(mesh.loop_vertex_count(), 0);
  for (const Effect* e : effects) e->loaded_faces(s, loaded);
  return loaded;
}

/// The fluid pressure the effects put on the faces in the state s (Effect::face_pressures); empty
/// where none does, so that the tips' integral reads a run without fluid as before.
std::vector<double> face_pressures_of(const Mesh& mesh, const RunState& s, const std::vector<Effect*>& effects) {
  std::vector<double> pressure(2 * mesh.loop_vertex_count(), 0.0);
  for (const Effect* e : effects) e->face_pressures(s, pressure);
  if (std::all_of(pressure.begin(), pressure.end(), [](double p) { return p == 0.0; })) pressure.clear();
  return pressure;
}
}  // namespace

FractureEffect::FractureEffect(const Mesh& mesh, const SceneDef& scene)
    : fracture_(scene), elements_(mesh.element_count()) {
  // New faces soften where a rock that can break has a fracture energy (cohesive_law.h), as the
  // contacts judge it (ContactSet::cohesive).
  if (!scene.fracture.present) return;
  for (const BodyDef& b : scene.bodies) {
    const MaterialDef& m = scene.materials[static_cast<std::size_t>(b.material)];
    const double l = characteristic_length(m.young, m.strength);
    if (!(l > 0) || b.outer.empty()) continue;
    if (characteristic_length_ == 0 || l < characteristic_length_) characteristic_length_ = l;
    double x0 = b.outer[0].x, x1 = x0, y0 = b.outer[0].y, y1 = y0;
    for (const Vec2& p : b.outer) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    longest_body_ = std::max({longest_body_, x1 - x0, y1 - y0});
  }
  for (const MaterialDef& m : scene.materials) cohesive_ = cohesive_ || cohesive_law(m.strength).on();
}

Outcome FractureEffect::cascade(double t) const {
  return Outcome::stop(StopCode::fracture_cascade,
                       "cracks were still growing after " + std::to_string(max_per_step()) +
                           " re-cuts of the mesh within one step",
                       t);
}

bool FractureEffect::change(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name,
                            const RunState& solved, const std::vector<std::uint8_t>& removed, int dofs_per_cover,
                            RunState& start, const std::vector<ContactHistory>& history,
                            const std::vector<Effect*>& effects, NewMesh& out, StepTimings& timings) {
  Stopwatch watch;
  // In rock that softens a new crack starts only where cohesive_starts.h allows it.
  const int cracks_before = fracture_.crack_count();
  std::vector<CrackSegment> segments =
      fracture_.find(mesh, scene, solved, removed,
                     cohesive_ ? cohesive_starts(mesh, scene, start, solved, started_in_step_ == start.step,
                                                 scene.joints.size() - fracture_.segments().size(),
                                                 fracture_.growing_segments())
                               : std::vector<std::uint8_t>{});
  if (fracture_.crack_count() > cracks_before) started_in_step_ = start.step;
  if (segments.empty() && any_toughness(scene)) {  // the strength broke nothing: tips that reach their toughness grow
    std::vector<std::uint8_t> skip = removed;
    const std::vector<std::uint8_t>& debris = fracture_.debris();
    if (skip.size() < mesh.element_count()) skip.resize(mesh.element_count(), 0);
    for (std::size_t e = 0; e < debris.size() && e < skip.size(); ++e) skip[e] = skip[e] || debris[e];
    const std::vector<double> pressure = face_pressures(mesh, scene, scene_name, solved);
    // A closed crack's faces carry their contacts' traction (friction on a flaw under compression
    // leaves it the shear its friction does not hold): the same faces as crack_tips.csv counts.
    const std::vector<std::uint8_t> loaded = loaded_faces(mesh, solved, effects);
    segments = grow_by_toughness(mesh, scene, fracture_.segments(), solved, skip, pressure.empty() ? nullptr : &pressure,
                                 &loaded);
  }
  if (segments.empty()) {
    timings.add(kTiming, watch.seconds());
    return false;
  }
  out.scene = cracked_scene(scene, segments);
  const std::size_t first = scene.joints.size();
  out.mesh = std::make_unique<Mesh>(pre::recut(mesh, *out.scene, first, scene_name, out.map));
  // The check mode (docs/fracture.md "Re-cutting"): a re-cut that is not the full cut is a
  // defect of the re-cut, not of the run's physics: it ends the run with the difference.
  if (recut_check_enabled())
    if (const std::string diff = recut_difference(mesh, *out.mesh, *out.scene, scene_name, full_cut_);
        !diff.empty())
      throw RunError("NMM_CHECK_RECUT: at t = " + std::to_string(start.time) + " s the re-cut of " +
                     std::to_string(segments.size()) + " crack segment(s) is not the full cut: " + diff);
  transfer_state(mesh, *out.mesh, out.map, dofs_per_cover, start);
  // New faces soften where a rock that can break has a fracture energy (cohesive_law.h).
  const bool cohesive = std::any_of(scene.materials.begin(), scene.materials.end(),
                                    [](const MaterialDef& m) { return cohesive_law(m.strength).on(); });
  out.history = transfer_history(history, mesh, *out.mesh, out.map, first, cohesive);
  fracture_.cut(segments, *out.mesh, out.map);
  elements_ = out.mesh->element_count();
  timings.add(kTiming, watch.seconds());
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
  elements_ = out.mesh->element_count();
  out.scene = cracked_scene(scene, fracture_.segments());
  return true;
}

void FractureEffect::write_outputs(OutputStep& out) const {
  if (out.step == tips_.last_step) return;
  tips_.last_step = out.step;
  tips_.recorded = true;
  const std::vector<double> pressure = face_pressures_of(out.mesh, out.state, out.effects);
  const std::vector<TipReading> tips =
      read_crack_tips(out.mesh, out.model.scene(), out.space, out.state, fracture_.segments(), fracture_.debris(),
                      loaded_faces(out.mesh, out.state, out.effects), tips_.finder,
                      pressure.empty() ? nullptr : &pressure);
  tips_.now = static_cast<int>(tips.size());
  tips_.any = tips_.any || !tips.empty();
  char row[320];
  for (const TipReading& r : tips) {
    std::snprintf(row, sizeof row, "%lld,%.9g,%d,%.9g,%.9g,%.9g,%.9g,%.6g\n", static_cast<long long>(out.step),
                  out.time, r.tip, r.x, r.y, r.k1, r.k2, r.angle_deg);
    tips_.rows += row;
  }
}

void FractureEffect::write_files(const OutputStep& out, const std::string& dir) const {
  if (tips_.any) write_file_atomically(dir + "/crack_tips.csv", "step,time,tip,x,y,k1,k2,angle_deg\n" + tips_.rows);
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

void FractureEffect::checkpoint_sections(const RunState& /*s*/, const Mesh& mesh, CheckpointSections& sections) const {
  if (fracture_.segments().empty()) return;
  sections.emplace_back("MESH", mesh_to_bytes(mesh));
  sections.emplace_back("FRACTURE", fracture_.save());
}

void FractureEffect::summarise(const RunState& /*s*/, nlohmann::json& summary) const {
  if (active()) {
    // Intact rock that breaks (docs/fracture.md): the cracks so far.
    const std::vector<CrackSegment>& cracks = fracture_.segments();
    double length = 0;
    long tensile = 0;
    for (const CrackSegment& c : cracks) {
      length += std::hypot(c.b.x - c.a.x, c.b.y - c.a.y);
      tensile += c.mode == CrackMode::tensile;
    }
    nlohmann::json f = {{"segments", cracks.size()},
                        {"cracks", fracture_.crack_count()},
                        {"length_m", length},
                        {"tensile_segments", tensile},
                        {"shear_segments", static_cast<long>(cracks.size()) - tensile},
                        {"first_crack_step", cracks.empty() ? nlohmann::json(nullptr) : nlohmann::json(cracks.front().step)},
                        {"elements", elements_},
                        // Splinters the cracks cut off, taken out of the model (fracture.h).
                        {"debris_blocks", fracture_.debris_blocks()},
                        {"debris_area_m2", fracture_.debris_area()},
                        // Steps taken again because their solution broke the rock.
                        {"steps_resolved", fracture_.resolves()}};
    // A bar longer than 2·l_ch snaps back after its peak when pulled (docs/fracture.md).
    if (cohesive_)
      f.update({{"characteristic_length_m", characteristic_length_},
                {"longest_body_m", longest_body_},
                {"snap_back_possible", characteristic_length_ > 0 && longest_body_ > 2 * characteristic_length_}});
    if (!summary.contains("fracture")) summary["fracture"] = nlohmann::json::object();
    summary["fracture"].update(f);
  }
  if (tips_.recorded && (tips_.any || active())) summary["fracture"]["tips"] = tips_.now;
}

void FractureEffect::warnings(const nlohmann::json& summary, std::vector<std::string>& lines) const {
  if (!summary.contains("fracture") || summary["fracture"].value("snap_back_steps", 0L) <= 0) return;
  const nlohmann::json& f = summary["fracture"];
  char line[768];
  std::snprintf(line, sizeof line,
                "the cohesive cracks snapped back in %ld step(s): a face softened through a quarter of w_c in one "
                "step (the longest body, %.4g m, is %s twice Hillerborg's length l_ch = E·G_f/σt² = %.4g m); the run "
                "followed the snap at the step's pace, and its energy balance there is approximate "
                "(docs/fracture.md \"Snap-back\")",
                f["snap_back_steps"].get<long>(), f["longest_body_m"].get<double>(),
                f["snap_back_possible"].get<bool>() ? "longer than" : "shorter than",
                f["characteristic_length_m"].get<double>());
  lines.emplace_back(line);
}

std::vector<TipReading> read_crack_tips(const RunView& run, CrackTipFinder& finder) {
  const Fracture& f = fracture_of(run);
  const std::vector<double> pressure = face_pressures_of(run.mesh, run.state, run.effects);
  return read_crack_tips(run.mesh, run.model.scene(), run.space, run.state, f.segments(), f.debris(),
                         loaded_faces(run.mesh, run.state, run.effects), finder, pressure.empty() ? nullptr : &pressure);
}

void FractureEffect::energy_step(const EnergyStep& e, EnergyTerms& t) const {
  t.fracture += crack_release(e);
}

void FractureEffect::summarise_energy(const EnergyTerms& totals, nlohmann::json& summary) const {
  if (active()) summary["fracture"]["dissipated_j"] = totals.fracture;
}

const Fracture& fracture_of(const RunView& run) {
  for (const MeshChange* c : run.changes)
    if (const auto* f = dynamic_cast<const FractureEffect*>(c)) return f->fracture();
  throw std::logic_error("fracture_of: the run has no fracture effect");
}

}  // namespace nmm::solve
