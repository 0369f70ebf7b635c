// The single-joint specimen (reference/joint_specimen.h: the scene and its loading) run, and the
// jumps across the joint read off it. Shared by nmm-joint-study, nmm-study and
// tests/test_joint_law.cpp.
#pragma once

#include <string>
#include <vector>

#include "common/outcome.h"
#include "reference/joint_specimen.h"
#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::studies {

struct JointSpecimenResult {
  double closure = 0;  ///< m, vertical jump across the joint (below − above), > 0 closing
  double slip = 0;     ///< m, horizontal jump (above − below)
  double normal_stress = 0;  ///< Pa, mean effective normal stress over the 2 m joint (Σ N / 2 m)
  double travel = 0;   ///< m, the largest shear travel a closed contact remembers (Barton–Bandis)
  Outcome outcome;  ///< how the run ended
};

/// Runs the loaded specimen for `seconds` and reads the jumps between measure points 0 (above)
/// and 1 (below).
JointSpecimenResult run_joint_specimen(const Mesh& mesh, const SceneDef& scene, double seconds);

/// Load cycles: the specimen's top loads (`scene`'s, which must be the specimen loaded to
/// σ_top = max of `targets`) scaled by a time table to each normal stress of `targets` (Pa) in
/// turn — a 50 ms ramp, then a 100 ms hold — and the closure (m) read at the end of each hold.
/// Empty on a run that stops (how, in *outcome).
std::vector<double> run_closure_cycles(const Mesh& mesh, SceneDef scene,
                                       const std::vector<double>& targets, Outcome* outcome);

}  // namespace nmm::studies
