// Redrawing result.svg from a run folder: see result_redraw.h.
//
// Checks, each an InputError naming the file at fault:
// - summary.json must be readable; without "inputs.mesh" (runs of older versions) a mesh must be
//   given (nmm-report --mesh).
// - The frame must be of this mesh: as many points as loop vertices and as many cells as
//   manifold elements (a frame of another mesh would colour the wrong elements silently).
// - A chosen step must have a frame; the error lists the first and last steps that do.
#include "report/result_redraw.h"

#include "report/failure_cause.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/mesh_file.h"
#include "common/run_config.h"
#include "solver/output/output_writer.h"
#include "report/run_report.h"
#include "common/whole_file.h"
#include "common/vtk_writer.h"
#include "common/vtu_reader.h"

namespace nmm::report {
namespace fs = std::filesystem;

namespace {

const GridArray* find_array(const std::vector<GridArray>& arrays, const std::string& name) {
  for (const GridArray& a : arrays)
    if (a.name == name && a.type == GridArray::Type::Float64) return &a;
  return nullptr;
}

}  // namespace

std::vector<std::pair<double, std::int64_t>> list_run_frames(const std::string& dir) {
  const std::string path = (fs::path(dir) / "frames.pvd").string();
  const std::string pvd = read_text_file(path);
  std::vector<std::pair<double, std::int64_t>> out;
  for (std::size_t at = pvd.find("<DataSet"); at != std::string::npos;
       at = pvd.find("<DataSet", at + 1)) {
    // One DataSet element; the effects' parts of a frame (frames/flow_*.vtu) are not frames.
    const std::string element = pvd.substr(at, pvd.find('>', at) - at);
    if (element.find("file=\"frames/frame_") == std::string::npos && element.find("file=\"frames/") != std::string::npos)
      continue;
    const std::size_t t = pvd.find("timestep=\"", at), f = pvd.find("file=\"frames/frame_", at);
    if (t == std::string::npos || f == std::string::npos)
      throw InputError(path, "byte " + std::to_string(at), "a DataSet without timestep or frame file");
    char* end = nullptr;
    const double time = std::strtod(pvd.c_str() + t + 10, &end);
    const long long step = std::strtoll(pvd.c_str() + f + 19, &end, 10);
    out.emplace_back(time, static_cast<std::int64_t>(step));
  }
  if (out.empty()) throw InputError(path, "", "lists no frame");
  std::sort(out.begin(), out.end(),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  return out;
}

nlohmann::json read_run_summary(const std::string& dir) {
  const std::string summary_path = (fs::path(dir) / "summary.json").string();
  try {
    return nlohmann::json::parse(read_text_file(summary_path));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(summary_path, "", std::string("not JSON: ") + e.what());
  }
}

namespace {
// RUN/cracks.csv (step,time,x0,y0,x1,y1,mode): each row's segment appended to `scene`'s joints
// (of its crack set) and its mode to `joint_crack` (1 tensile, 2 shear), in the run's order.
void read_crack_rows(const std::string& dir, SceneDef& scene, std::vector<std::uint8_t>& joint_crack) {
  const std::string path = (fs::path(dir) / "cracks.csv").string();
  std::istringstream in(read_text_file(path));
  std::string line;
  std::getline(in, line);
  if (line != "step,time,x0,y0,x1,y1,mode") throw InputError(path, "line 1", "is not the header of cracks.csv");
  for (int row = 2; std::getline(in, line); ++row) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    double v[4];
    bool ok = f.size() == 7 && (f[6] == "tensile" || f[6] == "shear");
    for (int k = 0; ok && k < 4; ++k) {
      char* end = nullptr;
      v[k] = std::strtod(f[static_cast<std::size_t>(2 + k)].c_str(), &end);
      ok = end != f[static_cast<std::size_t>(2 + k)].c_str() && *end == 0 && std::isfinite(v[k]);
    }
    if (!ok) throw InputError(path, "line " + std::to_string(row), "is not step,time,x0,y0,x1,y1,tensile|shear");
    scene.joints.push_back({scene.fracture.crack_set, {{v[0], v[1]}, {v[2], v[3]}}});
    joint_crack.push_back(f[6] == "tensile" ? 1 : 2);
  }
}
}  // namespace

RunInputs load_run_inputs(const std::string& dir, const std::string& mesh_path_given) {
  const std::string summary_path = (fs::path(dir) / "summary.json").string();
  RunInputs r;
  r.summary = read_run_summary(dir);
  const nlohmann::json inputs = r.summary.value("inputs", nlohmann::json::object());
  // The mesh and the run's scene (its variants change fixed points and the scene's name).
  r.mesh_path = mesh_path_given;
  if (r.mesh_path.empty()) {
    if (!inputs.contains("mesh") || !inputs["mesh"].is_string())
      throw InputError(summary_path, "/inputs/mesh",
                       "does not name the mesh file; give it with --mesh MESH.nmm");
    r.mesh_path = inputs["mesh"].get<std::string>();
  }
  r.mesh = read_mesh_file(r.mesh_path);
  std::string config_path;
  std::vector<std::string> sets;
  if (inputs.contains("config") && inputs["config"].is_string())
    config_path = inputs["config"].get<std::string>();
  if (inputs.contains("set") && inputs["set"].is_array())
    for (const auto& s : inputs["set"])
      if (s.is_string()) sets.push_back(s.get<std::string>());
  // A merge patch given in memory (the Python module's config={...}) is kept in the summary.
  if (inputs.contains("config_patch") && inputs["config_patch"].is_object())
    r.scene = solve::make_run_scene(r.mesh, r.mesh_path, inputs["config_patch"].dump(),
                                    summary_path + " /inputs/config_patch", sets).scene;
  else
    r.scene = solve::make_run_scene(r.mesh, r.mesh_path, config_path, sets).scene;
  return r;
}

std::string redraw_result_svg(const std::string& dir, const RedrawOptions& options,
                              RedrawInfo* info) {
  const RunInputs run_inputs = load_run_inputs(dir, options.mesh_path);
  const nlohmann::json& summary = run_inputs.summary;
  const nlohmann::json inputs = summary.value("inputs", nlohmann::json::object());
  const std::string& mesh_path = run_inputs.mesh_path;

  std::string field_name = options.field;
  if (field_name.empty()) field_name = inputs.value("picture_field", std::string("displacement"));
  PictureField field;
  if (!parse_picture_field(field_name, field))
    throw InputError("--picture-field", "", "'" + field_name + "' is not one of displacement, sxx, syy, sxy, pressure");

  // The frame.
  const auto frames = list_run_frames(dir);
  std::size_t pick = frames.size() - 1;
  if (options.frame_step >= 0) {
    pick = frames.size();
    for (std::size_t i = 0; i < frames.size(); ++i)
      if (frames[i].second == options.frame_step) pick = i;
    if (pick == frames.size())
      throw InputError((fs::path(dir) / "frames.pvd").string(), "",
                       "no frame of step " + std::to_string(options.frame_step) + " (" +
                           std::to_string(frames.size()) + " frames, steps " +
                           std::to_string(frames.front().second) + " to " +
                           std::to_string(frames.back().second) + ")");
  }
  const auto [time, step] = frames[pick];
  const std::string frame_path = (fs::path(dir) / solve::frame_file_name(step)).string();
  const PolygonGrid grid = read_vtu(frame_path);
  const auto fits = [&](const Mesh& m) {
    return grid.point_count() == m.loop_vertex_count() && grid.cell_count() == m.element_count();
  };
  // A cracked run (docs/fracture.md): its frames after the last re-cut are of the mesh the cracks
  // cut (RUN/cracked_mesh.nmm), whose joints after the scene's are the cracks of cracks.csv.
  const fs::path cracked_path = fs::path(dir) / "cracked_mesh.nmm";
  const bool cracked = !fits(run_inputs.mesh) && fs::exists(cracked_path);
  const Mesh cracked_mesh = cracked ? read_mesh_file(cracked_path.string()) : Mesh{};
  const Mesh& mesh = cracked ? cracked_mesh : run_inputs.mesh;
  SceneDef cracked_scene;
  std::vector<std::uint8_t> joint_crack;
  if (cracked) {
    cracked_scene = run_inputs.scene;
    joint_crack.assign(cracked_scene.joints.size(), 0);
    read_crack_rows(dir, cracked_scene, joint_crack);
  }
  const SceneDef& scene = cracked ? cracked_scene : run_inputs.scene;
  if (!fits(mesh))
    throw InputError(frame_path, "",
                     "is not a frame of " + (cracked ? cracked_path.string() : mesh_path) + " (" +
                         std::to_string(grid.point_count()) + " points, " + std::to_string(grid.cell_count()) +
                         " cells; the mesh has " + std::to_string(mesh.loop_vertex_count()) + " loop vertices, " +
                         std::to_string(mesh.element_count()) + " elements)" +
                         (cracked ? "; a cracked run's frames before its last crack have meshes not kept" : ""));
  const GridArray* stress_array = find_array(grid.cell_data, "stress");
  if (stress_array == nullptr || stress_array->components != 3)
    throw InputError(frame_path, "", "has no 3-component cell array 'stress'");
  std::vector<double> loop_xy(2 * grid.point_count());
  for (std::size_t v = 0; v < grid.point_count(); ++v) {
    loop_xy[2 * v] = grid.points[3 * v];
    loop_xy[2 * v + 1] = grid.points[3 * v + 1];
  }
  const std::vector<double>& stress = stress_array->f64;

  PictureState state;
  state.time = time;
  const bool last = pick + 1 == frames.size();
  state.status = last ? summary.value("status", std::string("unknown")) : "step " + std::to_string(step);
  if (last) state.stop = run_outcome(summary).code;  // an earlier frame is no stop
  state.loop_xy = &loop_xy;
  state.stress = &stress;
  state.joint_crack = std::move(joint_crack);
  // The flow network of that step (frames/flow_<step>.vtu: the frame's part "flow").
  if (field == PictureField::pressure) {
    const fs::path flow_path = fs::path(dir) / solve::frame_part_file_name(step, "flow");
    if (!fs::exists(flow_path))
      throw InputError(flow_path.string(), "", "missing: --picture-field pressure needs a run with flow (a \"flow\" block in its scene)");
    try {
      state.flow = flow_segments_of(read_vtu(flow_path.string()));
    } catch (const std::invalid_argument& e) {
      throw InputError(flow_path.string(), "", e.what());
    }
  }
  // Bodies excavated by this frame's step (summary.json "excavated_bodies", cumulative across
  // restarts): left out of the picture as nmm-solve --pictures leaves them out.
  if (summary.contains("excavated_bodies") && summary["excavated_bodies"].is_array())
    for (const auto& x : summary["excavated_bodies"]) {
      if (!x.is_object() || !x.contains("body") || !x["body"].is_number_integer()) continue;
      const std::int64_t body = x["body"].get<std::int64_t>();
      const std::int64_t at = x.value("step", std::int64_t{0});
      if (body < 0 || static_cast<std::size_t>(body) >= scene.bodies.size() || at > step) continue;
      state.excavated_body.resize(scene.bodies.size(), 0);
      state.excavated_body[static_cast<std::size_t>(body)] = 1;
    }

  // Contacts of that step (contacts.csv, or contacts.csv.gz). A run without it had no contacts; a contacts.csv
  // without rows of this step was sampled (--contacts-every), unless the step is the last.
  std::string contacts_path = (fs::path(dir) / "contacts.csv").string();
  if (!fs::exists(contacts_path) && fs::exists(contacts_path + ".gz")) contacts_path += ".gz";
  if (fs::exists(contacts_path)) {
    const NumberTable c = read_number_csv(contacts_path);
    const int cs = c.column("step"), cx = c.column("x"), cy = c.column("y"),
              cst = c.column("state"), cv = c.column("vertex"), ce = c.column("edge");
    if (cs < 0 || cx < 0 || cy < 0 || cst < 0)
      throw InputError(contacts_path, "line 1", "header lacks step, x, y or state");
    for (const auto& r : c.rows) {
      if (r.size() < c.names.size() || static_cast<std::int64_t>(r[cs]) != step) continue;
      PictureContact pc{r[cx], r[cy], static_cast<int>(r[cst])};
      if (cv >= 0 && ce >= 0) {
        pc.vertex = static_cast<int>(r[cv]);
        pc.edge = static_cast<int>(r[ce]);
      }
      state.contacts.push_back(pc);
    }
    // contacts.csv holds only closed contacts: a step with none closed has no rows. Sampling
    // (--contacts-every N) keeps output steps 0, N, 2N, ... and the last of the run: every
    // output step writes a frame, so the frame's index among them says whether it was kept.
    const int every = std::max(1, inputs.value("contacts_every", 1));
    state.contacts_known = pick % static_cast<std::size_t>(every) == 0 || pick + 1 == frames.size();
  }

  // Bolts of that step (bolts.csv), each a run of rows of one bolt, and whether it had broken
  // (summary.json "bolts": known for the run's last state).
  const std::string bolts_path = (fs::path(dir) / "bolts.csv").string();
  if (fs::exists(bolts_path)) {
    const NumberTable b = read_number_csv(bolts_path);
    const int bs = b.column("step"), bb = b.column("bolt"), bx = b.column("x"), by = b.column("y"),
              bf = b.column("axial_force"), bux = b.column("ux"), buy = b.column("uy");
    if (bs < 0 || bb < 0 || bx < 0 || by < 0 || bf < 0 || bux < 0 || buy < 0)
      throw InputError(bolts_path, "line 1", "header lacks step, bolt, axial_force, x, y, ux or uy");
    for (const auto& r : b.rows) {
      if (r.size() < b.names.size() || static_cast<std::int64_t>(r[bs]) != step) continue;
      const std::size_t i = static_cast<std::size_t>(r[bb]);
      if (i >= scene.bolts.size()) continue;
      if (state.bolts.size() <= i) state.bolts.resize(i + 1);
      PictureBolt& pb = state.bolts[i];
      pb.points.push_back({r[bx], r[by]});
      pb.start.push_back({r[bx] - r[bux], r[by] - r[buy]});
      pb.axial.push_back(r[bf]);
    }
    if (last && summary.contains("bolts") && summary["bolts"].is_array())
      for (const auto& x : summary["bolts"]) {
        if (!x.is_object() || !x.contains("bolt") || !x["bolt"].is_number_unsigned()) continue;
        const std::size_t i = x["bolt"].get<std::size_t>();
        if (i < state.bolts.size()) state.bolts[i].broken = x.value("broken", false);
      }
  }

  // Measure points of that step, and where they started (x − ux: the exaggerated drawing).
  const NumberTable h = read_number_csv((fs::path(dir) / "history.csv").string());
  const int hs = h.column("step"), hx = h.column("x"), hy = h.column("y");
  const int hux = h.column("ux"), huy = h.column("uy");
  if (hs >= 0 && hx >= 0 && hy >= 0)
    for (const auto& r : h.rows)
      if (r.size() >= h.names.size() && static_cast<std::int64_t>(r[hs]) == step) {
        state.measure_points.push_back({r[hx], r[hy]});
        if (hux >= 0 && huy >= 0) state.measure_start.push_back({r[hx] - r[hux], r[hy] - r[huy]});
      }
  if (state.measure_start.size() != state.measure_points.size()) state.measure_start.clear();

  state.exaggeration = options.exaggerate;
  if (!(state.exaggeration > 0) && inputs.contains("exaggerate") && inputs["exaggerate"].is_number())
    state.exaggeration = inputs["exaggerate"].get<double>();
  state.title = options.title;
  if (info != nullptr)
    *info = {step, time, mesh.element_count(), state.contacts.size(), state.contacts_known};
  return result_svg(mesh, scene, state, field);
}

RedrawInfo redraw_result(const std::string& dir, const RedrawOptions& options) {
  RedrawInfo info;
  const std::string svg = redraw_result_svg(dir, options, &info);
  write_file_atomically((fs::path(dir) / "result.svg").string(), svg);
  return info;
}

}  // namespace nmm::report
