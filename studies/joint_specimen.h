// The single-joint specimen (data/single_joint.json: two 2 m × 1 m blocks, the joint at y = 1,
// measure points 0.1 mm above and below its middle): how it is loaded and what is read off it.
// Shared by nmm-joint-study, nmm-study and tests/test_joint_law.cpp so all three load it alike.
#pragma once

#include <string>

#include "mesh.h"
#include "scene.h"

namespace nmm::solve {

/// Replaces the scene's loads: normal stress σn (Pa) by 21 point loads on the 2 m top face (end
/// points half), and shear stress τ (Pa) by 10 point loads along the joint 2 cm above it (as a
/// shear box loads the whole face, with no overturning moment).
void load_joint_specimen(SceneDef& scene, double sigma_n, double tau);

struct JointSpecimenResult {
  double closure = 0;  ///< m, vertical jump across the joint (below − above), > 0 closing
  double slip = 0;     ///< m, horizontal jump (above − below)
  std::string status;  ///< "ok" or why the run stopped
};

/// Runs the loaded specimen for `seconds` and reads the jumps between measure points 0 (above)
/// and 1 (below).
JointSpecimenResult run_joint_specimen(const Mesh& mesh, const SceneDef& scene, double seconds);

}  // namespace nmm::solve
