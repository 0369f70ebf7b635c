// The single-joint specimen (reference/joint_specimen.h: the scene and its loading) run, and the
// jumps across the joint read off it. Shared by nmm-joint-study, nmm-study and
// tests/test_joint_law.cpp.
#pragma once

#include <string>

#include "joint_specimen.h"
#include "mesh.h"
#include "scene.h"

namespace nmm::studies {

struct JointSpecimenResult {
  double closure = 0;  ///< m, vertical jump across the joint (below − above), > 0 closing
  double slip = 0;     ///< m, horizontal jump (above − below)
  double normal_stress = 0;  ///< Pa, mean effective normal stress over the 2 m joint (Σ N / 2 m)
  double travel = 0;   ///< m, the largest shear travel a closed contact remembers (Barton–Bandis)
  std::string status;  ///< "ok" or why the run stopped
};

/// Runs the loaded specimen for `seconds` and reads the jumps between measure points 0 (above)
/// and 1 (below).
JointSpecimenResult run_joint_specimen(const Mesh& mesh, const SceneDef& scene, double seconds);

}  // namespace nmm::studies
