// Cover cutting: the mathematical mesh, joints and body boundaries → physical covers, manifold
// elements, blocks and element loops (see cover_cutter.cpp for the method).
#pragma once

#include <string>

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

}  // namespace nmm::pre
