// The single-joint specimen (data/single_joint.json: two 2 m × 1 m blocks, the joint at y = 1,
// measure points 0.1 mm above and below its middle): how it is loaded and what is read off it.
// Shared by nmm-joint-study, nmm-study and tests/test_joint_law.cpp so all three load it alike.
#pragma once

#include <string>

#include "mesh.h"
#include "scene.h"

namespace nmm::solve {

/// The specimen as a scene, without loads: one joint set (the joint between the blocks, the
/// scene's interface set), rock of Young's modulus E (Pa; ν 0.25, 2650 kg/m³, plane stress), mesh
/// size h (m), the base held along its bottom (fixed points at y = 0.02), measure points 0.1 mm
/// above and below the joint's middle, quasi-static steps (dynamic factor 0) of 1 ms.
SceneDef joint_specimen_scene(const JointSetDef& joint, double young, double h);

/// Replaces the scene's loads: normal stress σn (Pa) by 21 point loads on the 2 m top face (end
/// points half), and shear stress τ (Pa) by 10 point loads along the joint 2 cm above it (as a
/// shear box loads the whole face, with no overturning moment).
void load_joint_specimen(SceneDef& scene, double sigma_n, double tau);

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

}  // namespace nmm::solve
