// The Kirsch opening's wall read off a solved model (the scene and the closed form:
// reference/kirsch.h; docs/physics.md §5): hoop stress and radial displacement along the wall
// against Kirsch, at any cover order. Used by tests/test_rock_setups.cpp and nmm-study.
#pragma once

#include <cstddef>

#include "reference/kirsch.h"
#include "common/mesh.h"

namespace nmm::solve {
class TimeStepper;
}  // namespace nmm::solve

namespace nmm::studies {

/// What is read off a solved model along the wall, against the closed form.
struct KirschWall {
  /// RMS error of σθ at the wall points, relative to max |σθ(a)|: each wall element's stress
  /// field evaluated at the ends of its wall edges (the VTU's vertex_stress at n ≥ 1, the element
  /// stress at n = 0), against σθ(a, θ) there.
  double hoop_wall = 0;
  /// The same with each wall element's mean stress at its centroid against σθ at the centroid
  /// (docs/solver.md's earlier read-off, kind to constant-stress elements).
  double hoop_centroid = 0;
  /// σθ (Pa, compression positive) at the side wall (a, 0), where it peaks for K0 < 3, from the
  /// element(s) with a wall vertex there, and Kirsch's value there.
  double side_wall_hoop = 0, side_wall_exact = 0;
  /// RMS error of u_r at the wall vertices (θ strictly between 0 and 90°), relative to
  /// max |u_r(a)|.
  double radial = 0;
  std::size_t wall_points = 0;  ///< (element, wall vertex) samples behind hoop_wall
};

/// Reads the wall of a solved Kirsch model (mesh and stepper of reference::kirsch_scene(k)).
KirschWall kirsch_wall(const reference::KirschSetup& k, const Mesh& mesh, const solve::TimeStepper& st);

}  // namespace nmm::studies
