// The single-joint specimen (data/single_joint.json: two 2 m × 1 m blocks, the joint at y = 1,
// measure points 0.1 mm above and below its middle): the scene with the seed paper's joint laws
// selected, and how it is loaded. Its closed form is the joint law itself (Bandis–Barton closure,
// hyperbolic shear: solver/contact/joint_law.h, docs/physics.md). Shared by nmm-joint-study, nmm-study
// and tests/test_joint_law.cpp so all three load it alike; studies/joint_specimen_run.h runs it.
#pragma once

#include <string>

#include "common/scene.h"

namespace nmm::reference {

/// Reads the scene file at `path` with every joint set's laws switched to Bandis–Barton
/// (normal) and hyperbolic (shear), so kni and vm are derived from JRC, JCS and σc (the seed
/// paper's studies run data/single_joint.json and data/tunnel.json this way). InputError when
/// the file is no scene or its joint_sets is no object.
SceneDef scene_with_joint_laws(const std::string& path);

/// The specimen: scene_with_joint_laws(path), which must have exactly one joint set and two
/// measure points, just above and below the joint (InputError naming the key otherwise).
SceneDef joint_specimen_scene(const std::string& path);

/// The seed paper's joint of the direct-shear study: Bandis–Barton closure (Kni 15.35 GPa/m,
/// Vm 0.227 mm), hyperbolic shear (Ksi 10 GPa/m, Rf 0.9), φ 30°.
JointSetDef seed_shear_joint();

/// The specimen built from one joint set (the joint between the blocks, the scene's interface
/// set), without loads: rock of Young's modulus E (Pa; ν 0.25, 2650 kg/m³, plane stress), mesh
/// size h (m), the base held along its bottom (fixed points at y = 0.02), measure points 0.1 mm
/// above and below the joint's middle, quasi-static steps (dynamic factor 0) of 1 ms.
SceneDef joint_specimen_scene(const JointSetDef& joint, double young, double h);

/// Replaces the scene's loads: normal stress σn (Pa) by 21 point loads on the 2 m top face (end
/// points half), and shear stress τ (Pa) by 10 point loads along the joint 2 cm above it (as a
/// shear box loads the whole face, with no overturning moment).
void load_joint_specimen(SceneDef& scene, double sigma_n, double tau);

}  // namespace nmm::reference
