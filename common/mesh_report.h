// What `nmm-inspect` reports about a mesh: a human summary and a JSON object.
// The JSON keys are part of the public contract (docs/interface.md, docs/inspect.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm {

/// An element is a sliver when its area is below this share of h² (h = mesh size): such pieces
/// come from joints passing very close to a node and make the stiffness matrix ill-conditioned.
constexpr double kSliverAreaFactor = 1e-6;

/// Parses the scene embedded in `mesh` and checks that it matches the mesh (every body index
/// used by elements, covers and blocks exists in the scene). `mesh_name` labels errors.
/// Throws InputError("<mesh_name> (embedded scene)", JSON path, message).
SceneDef embedded_scene(const Mesh& mesh, const std::string& mesh_name);

/// Statistics shared by the summary and the JSON report.
struct MeshStats {
  double area = 0;                  ///< m², sum of element areas (total_area)
  double scene_area = 0;            ///< m², sum of the scene bodies' areas (0 without a scene)
  double min_element_area = 0;      ///< m², 0 when there are no elements
  double max_element_area = 0;      ///< m²
  std::size_t sliver_elements = 0;  ///< elements with area < kSliverAreaFactor·h²
  std::size_t contact_edges_paired = 0;  ///< contact edges with an element across them
};
MeshStats mesh_stats(const Mesh& mesh, const SceneDef* scene);

/// Human summary, several lines, ending in a newline. `scene` may be null (mesh without a
/// readable scene): the scene's lines are then left out.
std::string mesh_summary_text(const Mesh& mesh, const SceneDef* scene);
/// Same, parsing the embedded scene first (InputError if it does not parse).
std::string mesh_summary_text(const Mesh& mesh);

/// The `--json` object: nodes, triangles, mathematical_covers, physical_covers,
/// manifold_elements, blocks, area and the extras listed in docs/inspect.md. With `full`, also
/// node_xy, triangle_nodes, physical_cover_node, physical_cover_body, block_body and elements.
/// `scene` may be null; element materials are then null.
nlohmann::json mesh_report_json(const Mesh& mesh, const SceneDef* scene, bool full);
/// Same, parsing the embedded scene first (InputError if it does not parse).
nlohmann::json mesh_report_json(const Mesh& mesh, bool full);

/// Everything about one physical cover (`--cover N`): node, node_xy, body, elements, area.
/// Throws InputError("", "--cover", ...) if `cover` is out of range.
nlohmann::json cover_report_json(const Mesh& mesh, long long cover);
std::string cover_summary_text(const Mesh& mesh, long long cover);

}  // namespace nmm
