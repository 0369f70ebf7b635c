// Cover cutting: the mathematical mesh, joints and body boundaries → physical covers, manifold
// elements, blocks and element loops (see cover_cutter.cpp for the method).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::pre {

/// Where the cover cutter spent its time, s.
struct CutTimings {
  double mesh_generation = 0;  ///< mathematical mesh and curve list
  double arrangement = 0;      ///< CGAL sweep of all curves
  double labelling = 0;        ///< faces → triangles, bodies, bridges for holes
  double covers = 0;           ///< elements, loops, physical covers, blocks, contact edges
};

/// Builds the mesh of a scene that passed parse_scene() and check_scene_geometry().
/// Throws InputError(file, "/bodies/i", ...) when bodies overlap.
Mesh build_mesh(const SceneDef& scene, const std::string& file, CutTimings* timings = nullptr);

/// A cut of part of the scene (preprocess/recut.h uses it when a crack grows).
struct RegionCut {
  /// The elements of the listed triangles, with their loops and contact edges exactly as
  /// build_mesh gives them; physical covers as the pieces of the listed triangles' node stars
  /// (exact where a node's six triangles are all listed); blocks not meaningful.
  Mesh mesh;
  /// [mesh triangle] the lattice node indices of each kept triangle (make_lattice's numbering)
  std::vector<std::array<std::int32_t, 3>> lattice_triangles;
};
/// Cuts only the lattice triangles listed (by their three lattice node indices, any order), with
/// the scene's joints and body boundaries: the same arrangement code, on the curves that reach
/// them. The scene must be one build_mesh accepts.
RegionCut cut_region(const SceneDef& scene, const std::vector<std::array<std::int32_t, 3>>& lattice_triangles,
                     const std::string& file);

}  // namespace nmm::pre
