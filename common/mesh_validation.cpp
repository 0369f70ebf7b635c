// The internal consistency of a mesh: see mesh_validation.h. Each violation is reported with
// the mesh file's section that holds the array at fault.
#include "common/mesh_validation.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/error.h"
#include "common/number_format.h"

namespace nmm {

namespace {

constexpr const char* kTagMeta = "META";
// Highest-order cover functions in use need 12 unknowns; the bound stops an absurd value from
// making a solver allocate cover_count × dofs_per_cover of nonsense.
constexpr int kMaxDofsPerCover = 64;

[[noreturn]] void bad(const std::string& name, const char* tag, const std::string& message) {
  throw InputError(name, std::string("section ") + tag, message);
}

std::string n(std::int64_t v) {
  return std::to_string(v);
}

void check_size(const std::string& name, const char* tag, const char* array, std::size_t actual,
                std::size_t expected, const std::string& because) {
  if (actual != expected)
    bad(name, tag,
        std::string(array) + " has " + n(static_cast<std::int64_t>(actual)) + " entries, but " +
            because);
}

void check_finite(const std::string& name, const char* tag, const char* what,
                  const std::vector<double>& xy) {
  for (std::size_t i = 0; i < xy.size(); ++i)
    if (!std::isfinite(xy[i]))
      bad(name, tag,
          std::string(what) + " " + n(static_cast<std::int64_t>(i / 2)) + " coordinate " +
              (i % 2 ? "y" : "x") + " is " + format_number(xy[i]));
}

}  // namespace

void validate_mesh(const Mesh& mesh, const std::string& name) {
  // ---- META
  if (!(std::isfinite(mesh.mesh_size) && mesh.mesh_size > 0))
    bad(name, kTagMeta,
        "mesh_size is " + format_number(mesh.mesh_size) + "; it must be a positive finite length");
  if (mesh.dofs_per_cover < 1 || mesh.dofs_per_cover > kMaxDofsPerCover)
    bad(name, kTagMeta,
        "dofs_per_cover is " + n(mesh.dofs_per_cover) + "; it must be between 1 and " +
            n(kMaxDofsPerCover));

  // ---- nodes and triangles
  if (mesh.node_xy.size() % 2 != 0)
    bad(name, "NODEXY",
        "node_xy has " + n(static_cast<std::int64_t>(mesh.node_xy.size())) +
            " values, not a whole number of (x, y) pairs");
  check_finite(name, "NODEXY", "node", mesh.node_xy);
  const std::int64_t nodes = static_cast<std::int64_t>(mesh.node_count());
  if (mesh.triangle_nodes.size() % 3 != 0)
    bad(name, "TRINODES",
        "triangle_nodes has " + n(static_cast<std::int64_t>(mesh.triangle_nodes.size())) +
            " values, not a multiple of 3");
  for (std::size_t i = 0; i < mesh.triangle_nodes.size(); ++i) {
    const std::int64_t v = mesh.triangle_nodes[i];
    if (v < 0 || v >= nodes)
      bad(name, "TRINODES",
          "triangle " + n(static_cast<std::int64_t>(i / 3)) + " node " +
              n(static_cast<std::int64_t>(i % 3)) + " is " + n(v) + ", but there are " + n(nodes) +
              " nodes");
  }
  const std::int64_t triangles = static_cast<std::int64_t>(mesh.triangle_count());

  // ---- physical covers
  const std::size_t covers = mesh.cover_count();
  for (std::size_t c = 0; c < covers; ++c) {
    const std::int64_t v = mesh.cover_node[c];
    if (v < 0 || v >= nodes)
      bad(name, "COVNODE",
          "cover " + n(static_cast<std::int64_t>(c)) + " node is " + n(v) + ", but there are " +
              n(nodes) + " nodes");
  }
  check_size(name, "COVBODY", "cover_body", mesh.cover_body.size(), covers,
             "there are " + n(static_cast<std::int64_t>(covers)) + " covers (cover_node)");
  for (std::size_t c = 0; c < covers; ++c)
    if (mesh.cover_body[c] < 0)
      bad(name, "COVBODY",
          "cover " + n(static_cast<std::int64_t>(c)) + " body is " + n(mesh.cover_body[c]) +
              "; body indices are >= 0");

  // ---- blocks
  const std::int64_t blocks = static_cast<std::int64_t>(mesh.block_count());
  for (std::size_t b = 0; b < mesh.block_body.size(); ++b)
    if (mesh.block_body[b] < 0)
      bad(name, "BLKBODY",
          "block " + n(static_cast<std::int64_t>(b)) + " body is " + n(mesh.block_body[b]) +
              "; body indices are >= 0");

  // ---- manifold elements
  const std::size_t elements = mesh.element_count();
  const std::int64_t elements64 = static_cast<std::int64_t>(elements);
  const std::string per_element = "there are " + n(elements64) + " elements (element_triangle)";
  for (std::size_t e = 0; e < elements; ++e) {
    const std::int64_t t = mesh.element_triangle[e];
    if (t < 0 || t >= triangles)
      bad(name, "ELTRI",
          "element " + n(static_cast<std::int64_t>(e)) + " triangle is " + n(t) +
              ", but there are " + n(triangles) + " triangles");
  }
  check_size(name, "ELBODY", "element_body", mesh.element_body.size(), elements, per_element);
  for (std::size_t e = 0; e < elements; ++e)
    if (mesh.element_body[e] < 0)
      bad(name, "ELBODY",
          "element " + n(static_cast<std::int64_t>(e)) + " body is " + n(mesh.element_body[e]) +
              "; body indices are >= 0");
  check_size(name, "ELBLOCK", "element_block", mesh.element_block.size(), elements, per_element);
  for (std::size_t e = 0; e < elements; ++e) {
    const std::int64_t b = mesh.element_block[e];
    if (b < 0 || b >= blocks)
      bad(name, "ELBLOCK",
          "element " + n(static_cast<std::int64_t>(e)) + " block is " + n(b) + ", but there are " +
              n(blocks) + " blocks");
    // A block is a piece of one body, so its elements lie in that body.
    if (mesh.block_body[static_cast<std::size_t>(b)] != mesh.element_body[e])
      bad(name, "ELBLOCK",
          "element " + n(static_cast<std::int64_t>(e)) + " is in body " + n(mesh.element_body[e]) +
              ", but its block " + n(b) + " is in body " +
              n(mesh.block_body[static_cast<std::size_t>(b)]));
  }
  check_size(name, "ELCOVERS", "element_covers", mesh.element_covers.size(), 3 * elements,
             "3 × " + n(elements64) + " elements need " + n(3 * elements64));
  for (std::size_t e = 0; e < elements; ++e) {
    const std::size_t tri = static_cast<std::size_t>(mesh.element_triangle[e]);
    for (std::size_t k = 0; k < 3; ++k) {
      const std::int64_t c = mesh.element_covers[3 * e + k];
      const std::string which = "element " + n(static_cast<std::int64_t>(e)) + " cover " +
                                n(static_cast<std::int64_t>(k));
      if (c < 0 || c >= static_cast<std::int64_t>(covers))
        bad(name, "ELCOVERS",
            which + " is " + n(c) + ", but there are " + n(static_cast<std::int64_t>(covers)) +
                " physical covers");
      // Cover k of an element is the cover of the element's triangle's node k (same order).
      const std::int32_t node = mesh.cover_node[static_cast<std::size_t>(c)];
      const std::int32_t tri_node = mesh.triangle_nodes[3 * tri + k];
      if (node != tri_node)
        bad(name, "ELCOVERS",
            which + " is " + n(c) + " on node " + n(node) + ", but node " +
                n(static_cast<std::int64_t>(k)) + " of triangle " +
                n(static_cast<std::int64_t>(tri)) + " is " + n(tri_node));
      // A physical cover is a piece of one body, so every element it covers lies in that body.
      const std::int32_t cover_body = mesh.cover_body[static_cast<std::size_t>(c)];
      if (cover_body != mesh.element_body[e])
        bad(name, "ELCOVERS",
            which + " is " + n(c) + " in body " + n(cover_body) + ", but the element is in body " +
                n(mesh.element_body[e]));
    }
  }

  // ---- element loops
  if (mesh.loop_xy.size() % 2 != 0)
    bad(name, "LOOPXY",
        "loop_xy has " + n(static_cast<std::int64_t>(mesh.loop_xy.size())) +
            " values, not a whole number of (x, y) pairs");
  check_finite(name, "LOOPXY", "loop vertex", mesh.loop_xy);
  const std::size_t vertices = mesh.loop_vertex_count();
  const std::int64_t vertices64 = static_cast<std::int64_t>(vertices);
  const auto& off = mesh.element_loop_offset;
  check_size(name, "ELLOOPS", "element_loop_offset", off.size(), elements + 1,
             "there are " + n(elements64) + " elements, so " + n(elements64 + 1) + " are needed");
  if (off[0] != 0)
    bad(name, "ELLOOPS", "element_loop_offset[0] is " + n(off[0]) + "; it must be 0");
  for (std::size_t e = 0; e < elements; ++e) {
    const std::int64_t len = std::int64_t{off[e + 1]} - off[e];
    if (len < 3)
      bad(name, "ELLOOPS",
          "element " + n(static_cast<std::int64_t>(e)) + " loop has " + n(len) +
              " vertices (element_loop_offset " + n(off[e]) + " to " + n(off[e + 1]) +
              "); a loop needs at least 3");
  }
  if (off[elements] != vertices64)
    bad(name, "ELLOOPS",
        "element_loop_offset ends at " + n(off[elements]) + ", but there are " + n(vertices64) +
            " loop vertices");
  check_size(name, "LOOPORIG", "loop_edge_origin", mesh.loop_edge_origin.size(), vertices,
             "there are " + n(vertices64) + " loop vertices");
  constexpr unsigned kKnownOrigins = kEdgeMesh | kEdgeJoint | kEdgeBoundary | kEdgeBridge | kEdgeExtension;
  for (std::size_t v = 0; v < vertices; ++v) {
    const unsigned flags = mesh.loop_edge_origin[v];
    if (flags == 0 || (flags & ~kKnownOrigins) != 0)
      bad(name, "LOOPORIG",
          "loop vertex " + n(static_cast<std::int64_t>(v)) + " edge origin flags are " + n(flags) +
              "; they must be a nonzero combination of 1, 2, 4, 8 and 16");
  }
  check_size(name, "LOOPJNT", "loop_edge_joint", mesh.loop_edge_joint.size(), vertices,
             "there are " + n(vertices64) + " loop vertices");
  for (std::size_t v = 0; v < vertices; ++v) {
    const std::int64_t j = mesh.loop_edge_joint[v];
    const bool on_joint = (mesh.loop_edge_origin[v] & kEdgeJoint) != 0;
    if (j < -1 || on_joint != (j >= 0))
      bad(name, "LOOPJNT",
          "loop vertex " + n(static_cast<std::int64_t>(v)) + " edge joint is " + n(j) +
              (on_joint ? ", but the edge is marked as lying on a joint"
                        : ", but the edge is not marked as lying on a joint (-1 expected)"));
  }

  // ---- contact-candidate edges
  const std::size_t contacts = mesh.contact_edge.size();
  const std::string per_contact =
      "there are " + n(static_cast<std::int64_t>(contacts)) + " contact edges (contact_edge)";
  check_size(name, "CEELEM", "contact_edge_element", mesh.contact_edge_element.size(), contacts,
             per_contact);
  check_size(name, "CEOPP", "contact_edge_opposite", mesh.contact_edge_opposite.size(), contacts,
             per_contact);
  for (std::size_t c = 0; c < contacts; ++c) {
    const std::string which = "contact edge " + n(static_cast<std::int64_t>(c));
    const std::int64_t e = mesh.contact_edge_element[c];
    if (e < 0 || e >= elements64)
      bad(name, "CEELEM",
          which + " element is " + n(e) + ", but there are " + n(elements64) + " elements");
    const std::int64_t v = mesh.contact_edge[c];
    const std::int64_t first = off[static_cast<std::size_t>(e)];
    const std::int64_t end = off[static_cast<std::size_t>(e) + 1];
    if (v < first || v >= end)
      bad(name, "CEDGE",
          which + " is loop vertex " + n(v) + ", outside the loop of its element " + n(e) +
              " (vertices " + n(first) + " to " + n(end - 1) + ")");
    if ((mesh.loop_edge_origin[static_cast<std::size_t>(v)] & (kEdgeJoint | kEdgeBoundary)) == 0)
      bad(name, "CEDGE",
          which + " is loop vertex " + n(v) +
              ", whose edge lies neither on a joint nor on a body boundary");
    const std::int64_t o = mesh.contact_edge_opposite[c];
    if (o < -1 || o >= elements64)
      bad(name, "CEOPP",
          which + " opposite element is " + n(o) + ", but there are " + n(elements64) +
              " elements (-1 for none)");
  }
}

}  // namespace nmm
