// Contact detection between manifold-element boundary edges that lie on joints or body
// boundaries (the mesh's contact-candidate edges): see contact_detection.cpp for the rules.
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"

namespace nmm::solve {

/// What does not change during a run: which loop vertices and edges can touch, and which
/// (vertex, element) pairs move together and so can never be in contact.
struct ContactTopology {
  std::vector<std::int32_t> next;        ///< [v] next loop vertex of v in its element
  std::vector<std::int32_t> prev;        ///< [v] previous loop vertex of v in its element
  std::vector<std::int32_t> element_of;  ///< [v] element whose loop holds v
  std::vector<std::int32_t> block_of;    ///< [element] block
  std::vector<std::uint8_t> corner;      ///< [v] 1 if v is a corner of its block's boundary
  /// [v] the joint a flat vertex's candidate edges all lie on (loop_edge_joint), or -1: a face of
  /// that joint, whose side of the single pass is decided once, by its normal as cut
  std::vector<std::int32_t> face_joint;
  /// [v] 1 if the face of face_joint[v] that v lies on is the side that does not touch (its
  /// normal as cut points up, or along +x): the two faces of a joint are opposite exactly there
  std::vector<std::uint8_t> face_master;
  std::vector<std::int32_t> edge_joint;  ///< [v] joint of edge v → next[v], or -1 (loop_edge_joint)
  std::vector<std::int32_t> first_vertex;  ///< [element] first loop vertex
  /// CSR: the elements of the same block sharing a mesh node with each element (itself
  /// included): where a vertex that sinks through an edge of that element can end up.
  std::vector<std::int32_t> near_offset, near_elements;
  std::vector<std::uint8_t> edge_candidate;  ///< [v] 1 if edge v → next[v] can touch
  std::vector<std::int32_t> edges;     ///< candidate edges, by their first vertex
  std::vector<std::int32_t> vertices;  ///< loop vertices with at least one candidate edge
  /// Sorted (vertex, element) pairs that are continuous: the vertex coincides with a vertex of
  /// that element and both see the same covers with the same weights there.
  std::vector<std::pair<std::int32_t, std::int32_t>> continuous;
  std::vector<std::int32_t> continuous_offset;  ///< [v+1] CSR of `continuous` by vertex
  /// CSR over loop vertices: the candidate vertices of other blocks that start at the same point
  /// (the two faces of a joint at one of its points, which make one contact between them).
  std::vector<std::int32_t> mirror_offset, mirrors;
  double mesh_size = 0;  ///< m
  /// m, how deep a vertex on the other side of a flat stretch must poke in before it too is held
  /// (beyond any closure a joint law allows: max(1e-4·h, 2·Vm))
  double master_depth = 0;
  bool is_continuous(std::int32_t vertex, std::int32_t element) const;
};

ContactTopology build_contact_topology(const Mesh& mesh);

/// A vertex P (of element A) facing an edge Q2 → Q3 (of element B) within the search distance.
struct ContactCandidate {
  std::int32_t vertex;   ///< global loop vertex P
  std::int32_t edge;     ///< first vertex Q2 of the edge (Q3 = next[Q2])
  std::int32_t elem_a;   ///< element of P
  std::int32_t elem_b;   ///< element of the edge
  double omega;          ///< –, P projects to Q2 + ω (Q3 − Q2), ω in [0, 1]
  double gap;            ///< m, (P − Q2)·n with n the edge's outward normal; < 0: penetration
};

struct DetectionStats {
  std::size_t pairs_tested = 0;  ///< vertex–edge pairs that reached the narrow phase
  std::size_t contacts = 0;      ///< candidates kept
  std::size_t list_builds = 0;   ///< Verlet lists built (the others reused the last one)
  double seconds = 0;            ///< s, wall time in detection (ContactSet::begin_step)
  /// s, the calling thread's CPU time in detection (on a loaded machine the wall time above
  /// includes the time the thread waited for a core)
  double cpu_seconds = 0;
};

/// The blocks each loop vertex was in closed contact with after the last step: sorted, unique
/// (vertex, block) pairs (a vertex at a concave junction can be closed against two blocks).
struct ClosedContacts {
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  /// m, [pairs]: how deep each pair's vertex was against that block at the end of the last step
  /// (empty: as deep as closed_depth allows)
  std::vector<double> depth;
  /// [pairs] 1: the pair is a face of a cohesive crack that still carries tension (cohesive_law.h,
  /// κ < w_c); empty: none is. Such a vertex is looked for on the master side too (below).
  std::vector<char> holds;
  /// [vertices + 1] where each vertex's pairs start (index()); empty: range() and with() search
  /// `pairs` instead. Detection looks up every vertex and its coincident ones: with a binary
  /// search each it took 70 ms per step of the 10,000-block wall (85,000 pairs), 45 ms indexed.
  std::vector<std::int32_t> first;
  /// Fills `first` for vertices 0 .. vertices − 1 (pairs sorted).
  void index(std::size_t vertices);
  /// [first, last) of vertex v's pairs.
  std::pair<std::size_t, std::size_t> range(std::int32_t v) const;
  bool with(std::int32_t v, std::int32_t block) const;
  /// v's pair with `block` is a cohesive face that holds (`holds`).
  bool holds_with(std::int32_t v, std::int32_t block) const;
  /// m, how deep v was against `block` (`unknown` where `depth` is empty); −1: not closed.
  double depth_with(std::int32_t v, std::int32_t block, double unknown) const;
};

/// Detection's Verlet list: for each candidate vertex (ContactTopology::vertices, in order), the
/// candidate edges of other elements, not continuous with it, that were within `reach` of it
/// when the list was built, ascending. detect_contacts reuses it while no loop vertex has moved
/// more than half of (reach − what the search needs) since then, and builds it anew otherwise.
/// Only a cache: the contacts found do not depend on when it was built.
/// A candidate edge's start (m), unit tangent, length (m), first vertex and element at one call.
struct CandidateEdgeFrame {
  double x, y, tx, ty, l;
  std::int32_t q2, element;
  bool usable;  ///< not degenerate
};

struct CandidateList {
  double reach = 0;                  ///< m, the distance it was built for
  std::vector<double> xy;            ///< [2·v] m, loop vertex positions when it was built
  std::vector<std::int32_t> offset;  ///< [vertices + 1] CSR into `edges`
  std::vector<std::int32_t> edges;   ///< indices into ContactTopology::edges
  std::size_t builds = 0;            ///< times built
  // Each call's working arrays, kept between calls so that a step allocates none of them (their
  // contents are rewritten by every call: no state of the run).
  std::vector<CandidateEdgeFrame> frames;        ///< [candidate edge] this call's frames
  std::vector<std::int32_t> first_out;  ///< [loop vertex] −1 between calls
  std::vector<char> drop;               ///< [contact found]
  std::size_t last_found = 0;           ///< contacts the last call found before the joint-point rule
};

/// Element pairs (a, b) with a vertex of a and an edge of b within the search distance, facing
/// or not: the pairs that may come into contact soon (for the sparsity pattern). Sorted, unique.
using ElementPairs = std::vector<std::pair<std::int32_t, std::int32_t>>;

/// Finds, for every candidate vertex and every other block, the one edge of that block it faces
/// within distance d0 (m), from the candidates of a Verlet list (`list`, kept by the caller
/// between calls; built by a uniform grid over the edges, cost about linear in the number of
/// edges, whenever a vertex has moved too far for it; without one, built for this call) and the
/// narrow-phase rules. `closed` lists the blocks each vertex was in closed contact with after
/// the last step: against such a block a vertex may be inside its elements by up to
/// min(0.3·h, d0); against any other by up to `shallow` (m) at most, a depth only a contact can
/// explain (a vertex deeper inside without having come in through a contact is near that edge
/// from the wrong side). `open_gap` (m, at most d0; < 0: d0): contacts open wider than this are
/// not found — the stepper's reach check (time_stepper.cpp) redoes a step in which a vertex
/// moves more than half of it; a closed contact is still followed as deep as d0 allows, and
/// where one may be deeper than open_gap, d0 is looked to (the contacts found are d0's whose
/// gap is at most open_gap).
/// `removed` ([element], optional): elements out of the model (excavated, debris), whose contacts
/// the caller drops. The list leaves out the vertices and edges of blocks all of whose elements
/// are out (debris blocks, held where they broke off, crowded a shattered rock's grid cells): the
/// contacts the caller keeps are the same, since such a vertex's or edge's contacts are all
/// dropped, and so is every contact the one-per-point rule weighs against one of them (its
/// vertex is on that edge, or its edge ends at that vertex). Not a block with only some elements
/// out: a removed vertex there may outweigh, at one point, a contact the caller keeps. A list
/// built for one `removed` is not reused for another (the caller resets it).
std::vector<ContactCandidate> detect_contacts(const ContactTopology& topo,
                                              const std::vector<double>& loop_xy, double d0,
                                              double shallow,
                                              const ClosedContacts& closed,
                                              DetectionStats* stats = nullptr,
                                              ElementPairs* near = nullptr,
                                              CandidateList* list = nullptr,
                                              double open_gap = -1,
                                              const std::vector<std::uint8_t>* removed = nullptr);

}  // namespace nmm::solve
