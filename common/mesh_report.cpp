#include "common/mesh_report.h"

#include <algorithm>
#include <limits>
#include <string>

#include "common/error.h"
#include "common/mesh_file.h"
#include "common/number_format.h"

namespace nmm {

namespace {

// Joints the mesh's edges name beyond the scene's own: the crack segments of a cracked mesh.
std::size_t crack_segments(const Mesh& mesh, const SceneDef& scene) {
  std::int32_t last = -1;
  for (const std::int32_t j : mesh.loop_edge_joint) last = std::max(last, j);
  const auto n = static_cast<std::size_t>(last + 1);
  return n > scene.joints.size() ? n - scene.joints.size() : 0;
}

// %g for people: also drops printf's padded exponent (1e-06 -> 1e-6).
std::string fmt_g(double v, int digits = 6) {
  std::string s = format_rough(v, digits);
  const std::size_t e = s.find('e');
  if (e != std::string::npos && e + 2 < s.size() && s[e + 2] == '0' && e + 3 < s.size())
    s.erase(e + 2, 1);
  return s;
}

// Label and value in two columns, so the summary reads like a table.
void row(std::string& out, const std::string& label, const std::string& value) {
  out += label;
  out += std::string(label.size() < 26 ? 26 - label.size() : 1, ' ');
  out += value;
  out += '\n';
}

void check_cover(const Mesh& mesh, long long cover) {
  if (cover < 0 || static_cast<unsigned long long>(cover) >= mesh.cover_count())
    throw InputError("", "--cover",
                     "physical cover " + std::to_string(cover) + " does not exist (the mesh has " +
                         std::to_string(mesh.cover_count()) + " physical covers, 0 to " +
                         std::to_string(static_cast<long long>(mesh.cover_count()) - 1) + ")");
}

void check_body_index(std::int32_t body, std::size_t bodies, const std::string& file,
                      const std::string& what) {
  if (body < 0 || static_cast<std::size_t>(body) >= bodies)
    throw InputError(file, "/bodies",
                     what + " refers to body " + std::to_string(body) + " but the scene has " +
                         std::to_string(bodies) + " bodies");
}

}  // namespace

SceneDef embedded_scene(const Mesh& mesh, const std::string& mesh_name) {
  const std::string label = mesh_name + " (embedded scene)";
  SceneDef scene = parse_scene(mesh.scene_text, label);
  // The mesh and its scene are written together, but a mesh file assembled by other means could
  // pair them wrongly; every later lookup of scene.bodies[...] relies on this check.
  const std::size_t nb = scene.bodies.size();
  for (std::size_t e = 0; e < mesh.element_body.size(); ++e)
    check_body_index(mesh.element_body[e], nb, label, "element " + std::to_string(e));
  for (std::size_t c = 0; c < mesh.cover_body.size(); ++c)
    check_body_index(mesh.cover_body[c], nb, label, "physical cover " + std::to_string(c));
  for (std::size_t b = 0; b < mesh.block_body.size(); ++b)
    check_body_index(mesh.block_body[b], nb, label, "block " + std::to_string(b));
  return scene;
}

MeshStats mesh_stats(const Mesh& mesh, const SceneDef* scene) {
  MeshStats s;
  const double sliver = kSliverAreaFactor * mesh.mesh_size * mesh.mesh_size;
  s.min_element_area = std::numeric_limits<double>::infinity();
  s.max_element_area = -std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const double a = element_area(mesh, e);
    s.min_element_area = std::min(s.min_element_area, a);
    s.max_element_area = std::max(s.max_element_area, a);
    if (a < sliver) ++s.sliver_elements;
  }
  if (mesh.element_count() == 0) s.min_element_area = s.max_element_area = 0;
  s.area = total_area(mesh);
  if (scene)
    for (const BodyDef& b : scene->bodies) s.scene_area += body_area(b);
  for (std::int32_t o : mesh.contact_edge_opposite) s.contact_edges_paired += o >= 0 ? 1 : 0;
  return s;
}

std::string mesh_summary_text(const Mesh& mesh, const SceneDef* scene) {
  const MeshStats s = mesh_stats(mesh, scene);
  const double h = mesh.mesh_size;
  std::string out;
  if (scene) {
    std::string name = scene->name.empty() ? "(unnamed)" : scene->name;
    if (!mesh.scene_file.empty()) name += "  (from " + mesh.scene_file + ")";
    row(out, "scene", name);
  } else if (!mesh.scene_file.empty()) {
    row(out, "scene file", mesh.scene_file);
  }
  row(out, "mesh size", fmt_g(h) + " m");
  row(out, "nodes", std::to_string(mesh.node_count()));
  row(out, "triangles", std::to_string(mesh.triangle_count()));
  row(out, "mathematical covers", std::to_string(mesh.mathematical_cover_count()));
  row(out, "physical covers",
      std::to_string(mesh.cover_count()) + "  (" + std::to_string(mesh.dofs_per_cover) +
          " unknowns each)");
  row(out, "manifold elements", std::to_string(mesh.element_count()));
  row(out, "blocks", std::to_string(mesh.block_count()));
  if (scene) {
    row(out, "bodies", std::to_string(scene->bodies.size()));
    row(out, "joints", std::to_string(scene->joints.size()));
    // A mesh the run's cracks re-cut (nmm-solve's cracked_mesh.nmm, docs/fracture.md): its edges
    // name the crack segments as joints after the scene's.
    if (const std::size_t cracks = crack_segments(mesh, *scene); cracks > 0)
      row(out, "crack segments", std::to_string(cracks) + "  (cut by the run: joints after the scene's)");
  }
  std::string area = fmt_g(s.area, 10) + " m²";
  if (scene) area += "  (scene bodies: " + fmt_g(s.scene_area, 10) + " m²)";
  row(out, "area", area);
  if (mesh.element_count() > 0) {
    row(out, "element area min / max",
        fmt_g(s.min_element_area) + " / " + fmt_g(s.max_element_area) + " m²");
  }
  row(out, "sliver elements",
      std::to_string(s.sliver_elements) + "  (area < " + fmt_g(kSliverAreaFactor) +
          "·h² = " + fmt_g(kSliverAreaFactor * h * h) + " m²)");
  row(out, "contact-candidate edges",
      std::to_string(mesh.contact_edge.size()) + "  (" + std::to_string(s.contact_edges_paired) +
          " with an element across)");
  std::string version = std::to_string(kMeshFormatVersion);
  if (!mesh.tool_version.empty())
    version += "  (written by " + (mesh.tool.empty() ? std::string("nmm-preprocess") : mesh.tool) + " " + mesh.tool_version + ")";
  row(out, "file format version", version);
  row(out, "scene SHA-256", to_hex(mesh.scene_sha256));
  return out;
}

std::string mesh_summary_text(const Mesh& mesh) {
  const SceneDef scene = embedded_scene(mesh, mesh.scene_file);
  return mesh_summary_text(mesh, &scene);
}

nlohmann::json mesh_report_json(const Mesh& mesh, const SceneDef* scene, bool full) {
  using nlohmann::json;
  const MeshStats s = mesh_stats(mesh, scene);
  json j = json::object();
  // The contract's keys (docs/interface.md).
  j["nodes"] = mesh.node_count();
  j["triangles"] = mesh.triangle_count();
  j["mathematical_covers"] = mesh.mathematical_cover_count();
  j["physical_covers"] = mesh.cover_count();
  j["manifold_elements"] = mesh.element_count();
  j["blocks"] = mesh.block_count();
  j["area"] = s.area;
  // Extras.
  j["scene_name"] = scene ? json(scene->name) : json(nullptr);
  j["scene_file"] = mesh.scene_file;
  j["scene_sha256"] = to_hex(mesh.scene_sha256);
  j["format_version"] = kMeshFormatVersion;
  j["tool_version"] = mesh.tool_version;
  j["mesh_size"] = mesh.mesh_size;
  j["dofs_per_cover"] = mesh.dofs_per_cover;
  j["bodies"] = scene ? json(scene->bodies.size()) : json(nullptr);
  j["joints"] = scene ? json(scene->joints.size()) : json(nullptr);
  if (const std::size_t cracks = scene ? crack_segments(mesh, *scene) : 0; cracks > 0) j["crack_segments"] = cracks;
  j["scene_area"] = scene ? json(s.scene_area) : json(nullptr);
  j["loop_vertices"] = mesh.loop_vertex_count();
  j["contact_edges"] = mesh.contact_edge.size();
  j["contact_edges_paired"] = s.contact_edges_paired;
  // null rather than 0 without elements: a 0 would look like a degenerate element.
  j["min_element_area"] = mesh.element_count() ? json(s.min_element_area) : json(nullptr);
  j["max_element_area"] = mesh.element_count() ? json(s.max_element_area) : json(nullptr);
  j["sliver_elements"] = s.sliver_elements;
  j["sliver_area_threshold"] = kSliverAreaFactor * mesh.mesh_size * mesh.mesh_size;
  if (!full) return j;

  json node_xy = json::array();
  for (std::size_t i = 0; i < mesh.node_count(); ++i)
    node_xy.push_back({mesh.node_xy[2 * i], mesh.node_xy[2 * i + 1]});
  json tri = json::array();
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    tri.push_back({mesh.triangle_nodes[3 * t], mesh.triangle_nodes[3 * t + 1],
                   mesh.triangle_nodes[3 * t + 2]});
  j["node_xy"] = std::move(node_xy);
  j["triangle_nodes"] = std::move(tri);
  j["physical_cover_node"] = mesh.cover_node;
  j["physical_cover_body"] = mesh.cover_body;
  j["block_body"] = mesh.block_body;

  json elements = json::array();
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    json poly = json::array();
    const auto b = static_cast<std::size_t>(mesh.element_loop_offset[e]);
    const auto end = static_cast<std::size_t>(mesh.element_loop_offset[e + 1]);
    for (std::size_t v = b; v < end; ++v)
      poly.push_back({mesh.loop_xy[2 * v], mesh.loop_xy[2 * v + 1]});
    json el = json::object();
    el["triangle"] = mesh.element_triangle[e];
    el["polygon"] = std::move(poly);
    el["covers"] = {mesh.element_covers[3 * e], mesh.element_covers[3 * e + 1],
                    mesh.element_covers[3 * e + 2]};
    el["block"] = mesh.element_block[e];
    el["body"] = mesh.element_body[e];
    el["area"] = element_area(mesh, e);
    json material = nullptr;
    const std::int32_t body = mesh.element_body[e];
    if (scene && body >= 0 && static_cast<std::size_t>(body) < scene->bodies.size()) {
      const int m = scene->bodies[static_cast<std::size_t>(body)].material;
      if (m >= 0 && static_cast<std::size_t>(m) < scene->materials.size())
        material = scene->materials[static_cast<std::size_t>(m)].name;
    }
    el["material"] = std::move(material);
    elements.push_back(std::move(el));
  }
  j["elements"] = std::move(elements);
  return j;
}

nlohmann::json mesh_report_json(const Mesh& mesh, bool full) {
  const SceneDef scene = embedded_scene(mesh, mesh.scene_file);
  return mesh_report_json(mesh, &scene, full);
}

nlohmann::json cover_report_json(const Mesh& mesh, long long cover) {
  check_cover(mesh, cover);
  const auto c = static_cast<std::size_t>(cover);
  const auto n = static_cast<std::size_t>(mesh.cover_node[c]);
  nlohmann::json j = nlohmann::json::object();
  j["index"] = cover;
  j["node"] = mesh.cover_node[c];
  j["node_xy"] = {mesh.node_xy[2 * n], mesh.node_xy[2 * n + 1]};
  j["body"] = mesh.cover_body[c];
  nlohmann::json elements = nlohmann::json::array();
  double area = 0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k)
      if (mesh.element_covers[3 * e + static_cast<std::size_t>(k)] ==
          static_cast<std::int32_t>(c)) {
        elements.push_back(e);
        area += element_area(mesh, e);
        break;
      }
  j["elements"] = std::move(elements);
  j["area"] = area;
  return j;
}

std::string cover_summary_text(const Mesh& mesh, long long cover) {
  const nlohmann::json j = cover_report_json(mesh, cover);
  std::string elements;
  for (const auto& e : j["elements"]) {
    if (!elements.empty()) elements += ' ';
    elements += std::to_string(e.get<std::size_t>());
  }
  std::string out;
  row(out, "physical cover", std::to_string(cover));
  row(out, "  node",
      std::to_string(j["node"].get<long long>()) + "  at (" +
          fmt_g(j["node_xy"][0].get<double>(), 10) + ", " +
          fmt_g(j["node_xy"][1].get<double>(), 10) + ") m");
  row(out, "  body", std::to_string(j["body"].get<long long>()));
  row(out, "  elements", std::to_string(j["elements"].size()) + ": " + elements);
  row(out, "  area", fmt_g(j["area"].get<double>(), 10) + " m²");
  return out;
}

}  // namespace nmm
