// The NMM mesh: mathematical mesh, physical covers (PC), manifold elements (ME), blocks and the
// contact-candidate edges, as plain arrays indexed by integers (no pointer graphs).
//
// Definitions (docs/interface.md, docs/physics.md §1):
// - nodes, triangles: the equilateral mathematical mesh of side `mesh_size`, only the triangles
//   meeting the domain with positive area and their nodes. Triangles are counter-clockwise.
// - physical cover: a connected piece of (star of node ∩ body) minus joints. A joint ending inside
//   a star does not split it. Each PC carries `dofs_per_cover` unknowns.
// - manifold element: a connected piece of (triangle ∩ body) minus joints. Its boundary is one
//   counter-clockwise loop: a weakly simple polygon that runs along both faces of a joint ending
//   inside it (a slit), and reaches any hole through a zero-width bridge (kEdgeBridge), so that
//   the shoelace and simplex-integration formulas hold on it unchanged.
// - block: a connected piece of a body minus joints.
// - contact-candidate edge: a loop edge lying on a joint or a body boundary.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace nmm {

/// Where an element loop edge came from (bit flags; an edge may carry several).
enum EdgeOrigin : std::uint8_t {
  kEdgeMesh = 1,      ///< lies on a mathematical mesh edge
  kEdgeJoint = 2,     ///< lies on a joint (loop_edge_joint names it)
  kEdgeBoundary = 4,  ///< lies on a body boundary (outer or hole)
  kEdgeBridge = 8,    ///< zero-width bridge joining a hole to the element's outer boundary
  /// a gap end's extension: a narrow gap of a body boundary (a slot) carried on from its end to
  /// the edge of the triangle holding the end; it splits the covers of the stars that it and the
  /// gap separate, and nothing else (no contact; elements across it are one block)
  kEdgeExtension = 16,
};

struct Mesh {
  // ---- mathematical mesh --------------------------------------------------------------------
  double mesh_size = 0;               ///< m, side of the equilateral triangles
  int dofs_per_cover = 2;             ///< unknowns per physical cover (2: constant cover function)
  std::vector<double> node_xy;        ///< [2·node] m
  std::vector<std::int32_t> triangle_nodes;  ///< [3·triangle] node indices, counter-clockwise

  // ---- physical covers ----------------------------------------------------------------------
  std::vector<std::int32_t> cover_node;  ///< [pc] node whose star the cover lies in
  std::vector<std::int32_t> cover_body;  ///< [pc] body the cover lies in

  // ---- manifold elements --------------------------------------------------------------------
  std::vector<std::int32_t> element_triangle;  ///< [me] triangle the element lies in
  std::vector<std::int32_t> element_body;      ///< [me] body (index into the scene's bodies)
  std::vector<std::int32_t> element_block;     ///< [me] block
  std::vector<std::int32_t> element_covers;    ///< [3·me] PC of each triangle node, same order
  std::vector<std::int32_t> element_loop_offset;  ///< [me+1] CSR into the loop arrays
  std::vector<double> loop_xy;                    ///< [2·v] m, loop vertices, counter-clockwise
  std::vector<std::uint8_t> loop_edge_origin;     ///< [v] EdgeOrigin flags of edge v → next
  std::vector<std::int32_t> loop_edge_joint;      ///< [v] lowest joint index on the edge, or -1

  // ---- blocks -------------------------------------------------------------------------------
  std::vector<std::int32_t> block_body;  ///< [block] body the block belongs to

  // ---- contact-candidate edges (loop edges on joints or body boundaries) ----------------------
  std::vector<std::int32_t> contact_edge;           ///< [c] global loop vertex index v of edge v
  std::vector<std::int32_t> contact_edge_element;   ///< [c] element owning the edge
  std::vector<std::int32_t> contact_edge_opposite;  ///< [c] element across the edge, -1 if none

  // ---- provenance ---------------------------------------------------------------------------
  std::string tool = "nmm-preprocess";  ///< program that wrote the file
  std::string tool_version;              ///< version of that program
  std::string scene_file;                ///< scene file name as given on the command line
  std::string scene_text;                ///< the scene itself, verbatim (comments included)
  std::array<std::uint8_t, 32> scene_sha256{};  ///< SHA-256 of scene_text

  // ---- derived sizes ------------------------------------------------------------------------
  std::size_t node_count() const { return node_xy.size() / 2; }
  std::size_t triangle_count() const { return triangle_nodes.size() / 3; }
  std::size_t cover_count() const { return cover_node.size(); }
  std::size_t element_count() const { return element_triangle.size(); }
  std::size_t block_count() const { return block_body.size(); }
  std::size_t loop_vertex_count() const { return loop_xy.size() / 2; }
  /// Number of mathematical covers: nodes that carry at least one physical cover.
  std::size_t mathematical_cover_count() const;
};

/// Area of element e (shoelace over its loop), m².
double element_area(const Mesh& mesh, std::size_t e);

/// Sum of all element areas, m².
double total_area(const Mesh& mesh);

}  // namespace nmm
