// Cover cutting: the mathematical mesh, joints and body boundaries → physical covers, manifold
// elements, blocks and element loops (see cover_cutter.cpp for the method).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
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

/// A cut kept from one call to the next, for a scene that grows by joints (the re-cut check,
/// solver/fracture/recut_check.h, after every re-cut of a cracking run). cut() gives the mesh
/// build_mesh gives (the same cut, common/mesh_compare.h; elements, covers and blocks may be
/// numbered and loops started otherwise). When the scene is the kept one with joints appended —
/// the same bodies (rings and materials' indices), mesh size and gap-end switch, and every kept
/// joint unchanged, compared — only the new joints' segments are inserted into the kept exact
/// arrangement; any other scene is cut from nothing and kept.
class GrowingCut {
 public:
  GrowingCut();
  ~GrowingCut();
  GrowingCut(GrowingCut&&) noexcept;
  GrowingCut& operator=(GrowingCut&&) noexcept;

  /// The mesh of a scene that passed parse_scene() and check_scene_geometry(); throws as build_mesh.
  Mesh cut(const SceneDef& scene, const std::string& file);
  /// Calls that grew the kept cut, and calls that cut from nothing.
  std::size_t grown() const { return grown_; }
  std::size_t fresh() const { return fresh_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t grown_ = 0, fresh_ = 0;
};

}  // namespace nmm::pre
