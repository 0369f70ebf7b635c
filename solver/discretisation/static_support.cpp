// Whether a step's system is held: see static_support.h.
#include "solver/discretisation/static_support.h"

#include "common/number_format.h"

#include <sstream>

#include "common/error.h"

namespace nmm::solve {

namespace {

/// "(x, y)" of cover c's node, m.
std::string cover_node_text(const Mesh& mesh, std::int32_t c) {
  std::ostringstream os;
  os << "(" << mesh.node_xy[2 * mesh.cover_node[c]] << ", " << mesh.node_xy[2 * mesh.cover_node[c] + 1]
     << ")";
  return os.str();
}

}  // namespace

std::vector<int> block_holds(const Model& model, const RunState& s) {
  const Mesh& mesh = model.mesh();
  std::vector<int> held(mesh.block_count(), 0);
  for (const TrackedPoint& p : s.fixed) ++held[mesh.element_block[p.element]];
  for (const auto& edges : model.support_edges())
    for (const BoundaryEdge& be : edges) held[mesh.element_block[be.element]] += 2;
  return held;
}

std::vector<std::uint8_t> free_pieces(const Model& model, const RunState& s) {
  const SceneDef& scene = model.scene();
  if (model.step_inertia() || !scene.fracture.present) return {};
  bool can_crack = false;
  for (const MaterialDef& m : scene.materials) can_crack = can_crack || m.strength.present;
  if (!can_crack) return {};
  const Mesh& mesh = model.mesh();
  const std::vector<int> held = block_holds(model, s);
  std::vector<std::uint8_t> body_held(scene.bodies.size(), 0);
  for (std::size_t b = 0; b < held.size(); ++b)
    if (held[b] >= 2) body_held[static_cast<std::size_t>(mesh.block_body[b])] = 1;
  std::vector<std::uint8_t> piece(mesh.element_count(), 0);
  bool any = false;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::size_t b = static_cast<std::size_t>(mesh.element_block[e]);
    piece[e] = held[b] < 2 && body_held[static_cast<std::size_t>(mesh.block_body[b])] ? 1 : 0;
    any = any || piece[e];
  }
  if (!any) piece.clear();
  return piece;
}

std::string unheld_block(const Model& model, const RunState& s) {
  const Mesh& mesh = model.mesh();
  const std::vector<int> held = block_holds(model, s);
  const std::vector<std::uint8_t> pieces = free_pieces(model, s);
  for (std::size_t b = 0; b < held.size(); ++b) {
    if (held[b] >= 2 || s.body_removed[mesh.block_body[b]]) continue;
    bool piece = false;  // a free piece takes inertia (free_pieces)
    for (std::size_t e = 0; e < pieces.size() && !piece; ++e)
      piece = pieces[e] && mesh.element_block[e] == static_cast<std::int32_t>(b);
    if (piece) continue;
    std::size_t e = 0;
    while (mesh.element_block[e] != static_cast<std::int32_t>(b)) ++e;
    const std::int32_t c = mesh.element_covers[3 * e];
    std::ostringstream os;
    os << "static run: block " << b << " (body " << mesh.block_body[b] << ") is held by "
       << held[b] << " fixed point" << (held[b] == 1 ? "" : "s")
       << ", so its covers (e.g. cover " << c << " at node " << cover_node_text(mesh, c)
       << ") are unconstrained: give each block two fixed points, or use DDA's static analysis "
          "(solver.static_mode \"dda\", the default) or a dynamic run";
    return os.str();
  }
  return "";
}

std::string not_positive_definite_message(const Mesh& mesh, const CoverSpace& space,
                                          int failed_unknown) {
  std::string m = "the system matrix is not positive definite";
  if (failed_unknown < 0) return m;
  const int c = space.cover_of_unknown(failed_unknown);
  // Its support says whether it is a block held by nothing or a cover next to void.
  int elements = 0;
  const double support = cover_support(mesh, c, elements);
  return m + " at cover " + std::to_string(c) + " (node " + cover_node_text(mesh, c) + "; " +
         std::to_string(elements) + (elements == 1 ? " element, " : " elements, ") + format_rough(support, 3) +
         " m² of support): it is unconstrained (held by no fixed point or closed contact); add fixed points or "
         "run dynamic";
}

double cover_support(const Mesh& mesh, int cover, int& elements) {
  double support = 0;
  elements = 0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k)
      if (mesh.element_covers[3 * e + k] == cover) support += element_area(mesh, e), ++elements;
  return support;
}

}  // namespace nmm::solve
