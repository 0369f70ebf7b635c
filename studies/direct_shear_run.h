// The displacement-controlled direct shear (reference/direct_shear.h: the scene and Barton's
// closed form) run, and its τ–δ curve read off at regular times. Shared by nmm-joint-study and
// tests/test_barton_bandis.cpp.
#pragma once

#include <string>
#include <vector>

#include "common/outcome.h"
#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::studies {

/// One reading of the shear box.
struct DirectShearSample {
  double time = 0;           ///< s
  double slip = 0;           ///< m, horizontal jump across the joint (measure points 0 − 1)
  double closure = 0;        ///< m, vertical jump (below − above), > 0 closing
  double travel = 0;         ///< m, the mean shear travel the closed contacts remember
  double shear_stress = 0;   ///< Pa, |Σ contact shear force| over the faces' overlap, 2 m − slip
  double normal_stress = 0;  ///< Pa, Σ contact normal force over the overlap
  /// m, the faces' separation averaged along the joint (Σ L·(gap + dilation) / Σ L over the closed
  /// contacts; < 0 while the springs are compressed): what a row of gauges along the joint
  /// reads, where the pair of measure points reads one place of a block that may tilt
  double face_gap = 0;
};

struct DirectShearRun {
  std::vector<DirectShearSample> samples;  ///< at every `every` steps' time, the first at t = 0
  Outcome outcome;                         ///< how the run ended
};

/// Runs the scene (1 ms steps) for `steps` steps, reading it every `every` steps.
DirectShearRun run_direct_shear(const Mesh& mesh, const SceneDef& scene, int steps, int every);

}  // namespace nmm::studies
