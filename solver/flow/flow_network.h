// The flow network of a run (scene key "flow"; docs/flow.md): the joints of the mesh as cut,
// divided where the mechanics divides them — at every loop vertex a joint face has, so at joint
// intersections, at the element edges that cross a joint and at the joint's ends — into segments
// between nodes. A node is one point of the joint network, shared by both faces of a joint and
// by every joint through an intersection.
//
// Hydraulic aperture. At a segment end the faces' normal separation is
//   w = (ū₊ − ū₋)·n      (m; n the segment's unit normal, ū₊ / ū₋ the mean displacement of the
//                        loop vertices of the faces on the +n / −n side at that end)
// and the hydraulic aperture a = min(max, residual + max(0, w)): a closed joint (w ≤ 0, the
// contact springs' penetration) conducts with its residual aperture. Small rotations: n is the
// segment's normal in the mesh as cut.
//
// Conductance of a segment of length L with a linear between its ends a₁, a₂ (cubic law,
// q = −a³/(12μ)·∂φ/∂s, integrated exactly along the segment):
//   C = 1 / ∫ 12μ/a³ ds = a₁²·a₂² / (6μ·L·(a₁ + a₂))      (m³/(s·Pa) per m; a₁ = a₂: a³/(12μL))
// Volume per node (m³ per m of thickness): each segment gives its end node the half next to it,
//   V₁ += L/2·(3a₁ + a₂)/4,   so Σ V = ∫ a ds exactly.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::solve {

/// A piece of a joint between two nodes of the network.
struct FlowSegment {
  std::int32_t a = -1, b = -1;  ///< its end nodes
  std::int32_t joint = -1;      ///< the scene's joint it lies on
  double length = 0;            ///< m, in the mesh as cut
  double nx = 0, ny = 0;        ///< –, unit normal (left of a → b)
};

/// One loop vertex of a joint face at one end of a segment (for the faces' separation).
struct FlowFaceVertex {
  std::int32_t vertex = -1;  ///< global loop vertex index
  std::int8_t side = 0;      ///< +1: the face on the +n side of the segment, −1: the −n side
};

/// An element's loop edge on a joint, and the segment it lies on (the faces the pressure loads).
struct FlowFace {
  std::int32_t element = -1;
  std::int32_t vertex = -1, next = -1;  ///< the edge vertex → next (global loop vertex indices)
  std::int32_t segment = -1;
  bool reversed = false;                ///< vertex lies at the segment's b end
};

class FlowNetwork {
 public:
  FlowNetwork() = default;
  /// The network of the mesh's joints with the scene's flow boundaries and injections; an
  /// InputError naming `scene_name` and the JSON path for a boundary polyline that lies on no
  /// body boundary or an injection point next to no joint.
  FlowNetwork(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name);

  std::size_t nodes() const { return node_boundary_.size(); }
  const std::vector<FlowSegment>& segments() const { return segments_; }
  const std::vector<FlowFace>& faces() const { return faces_; }
  /// [2·node] m, where each node is in the mesh as cut.
  const std::vector<double>& node_xy() const { return node_xy_; }
  /// [node] the `boundaries` entry that holds its pressure, or -1 (a free node).
  const std::vector<std::int32_t>& node_boundary() const { return node_boundary_; }
  /// Per injection, the two nodes that take its rate and their shares (summing to 1).
  struct Share {
    std::int32_t a = -1, b = -1;
    double wa = 1, wb = 0;
  };
  const std::vector<Share>& injection_shares() const { return injection_shares_; }

  /// [2·segment] m, the hydraulic aperture at each segment's a and b end for loop displacements
  /// loop_u ([2·v] m; run_state.h).
  std::vector<double> apertures(const std::vector<double>& loop_u, double residual, double max) const;
  /// [2·segment] m, the faces' normal separation w at each segment end for loop displacements
  /// loop_u ([2·v] m), neither capped nor cut at 0 (0 where only one face reaches the end): the
  /// opening a pressure gives, for the coupling's compliance (flow_effect.h).
  std::vector<double> separations(const std::vector<double>& loop_u) const;
  /// Every loop vertex whose displacement the apertures read (with repeats).
  const std::vector<FlowFaceVertex>& end_vertices() const { return end_vertices_; }
  /// [node] m³ per m, the fluid volume each node holds for end apertures `ap` (header comment).
  std::vector<double> volumes(const std::vector<double>& ap) const;
  /// [segment] m³/(s·Pa) per m, the conductance of each segment for end apertures `ap`.
  std::vector<double> conductances(const std::vector<double>& ap, double viscosity) const;
  /// [2·v] Pa, for a mesh of `loop_vertices` loop vertices: the pressure `p` ([node] Pa) at the
  /// start and at the end of every joint face edge v → next, 0 on the other edges (the crack
  /// faces' load in the interaction integral: interaction_integral.h).
  std::vector<double> face_pressures(const std::vector<double>& p, std::size_t loop_vertices) const;
  /// [node] m, the mean aperture of the segment ends at each node (flow.csv).
  std::vector<double> node_apertures(const std::vector<double>& ap) const;
  /// [2·node] m, each node's displacement for loop displacements loop_u ([2·v] m): the mean of
  /// the face vertices at the node (both faces, every joint through it), so a frame draws the
  /// network where the faces are.
  std::vector<double> node_displacements(const std::vector<double>& loop_u) const;

 private:
  std::vector<double> node_xy_;
  std::vector<std::int32_t> node_boundary_;
  std::vector<FlowSegment> segments_;
  std::vector<FlowFace> faces_;
  /// CSR by segment end (2·segment + end): the face vertices there
  std::vector<std::int32_t> end_offset_;
  std::vector<FlowFaceVertex> end_vertices_;
  std::vector<Share> injection_shares_;
};

}  // namespace nmm::solve
