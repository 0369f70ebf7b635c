// The stress intensity factors at the crack tips of a run's state (docs/crack-tips.md,
// docs/interface.md "Crack tips and LEFM"): the tips of the scene's joints and of the cracks grown
// in the run that end inside a body (crack_tips.h), each with K_I and K_II by the interaction
// integral over its domain (interaction_integral.h) and the direction of the maximum tangential
// stress (Erdogan–Sih: θ = mts_angle(K_I, K_II) from the crack's direction), where the tip is
// now (moved as the loop vertex at the end of its slit or crack). What crack_tips.csv writes at
// every output step (solver/stepping/fracture_effect.h) and the Python module gives.
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/run_state.h"
#include "solver/fracture/crack_tips.h"
#include "solver/fracture/fracture.h"

namespace nmm::solve {

/// One tip at one step, as crack_tips.csv has it.
struct TipReading {
  int tip = -1;          ///< its number (crack_tips.h)
  double x = 0, y = 0;   ///< m, where the tip is now
  double k1 = 0, k2 = 0; ///< Pa·√m, K_I (> 0 opens) and K_II
  double angle_deg = 0;  ///< deg counter-clockwise from +x: the maximum tangential stress direction
  double radius = 0;     ///< m, the domain the integral ran over
};

/// The tips of state s on `mesh` (of `scene`, the cover space `space`) and of the crack segments
/// `cracks`, numbered by `finder`, with their K. Elements excavated in s or marked in `debris`
/// ([me] 1, or empty) are out of the integral; `loaded` ([loop vertex] 1: the face from that
/// vertex to the next carries a traction — the closed contacts': Effect::loaded_faces) marks the
/// crack faces whose traction the integral counts.
std::vector<TipReading> read_crack_tips(const Mesh& mesh, const SceneDef& scene, const CoverSpace& space,
                                        const RunState& s, const std::vector<CrackSegment>& cracks,
                                        const std::vector<std::uint8_t>& debris,
                                        const std::vector<std::uint8_t>& loaded, CrackTipFinder& finder,
                                        const std::vector<double>* pressure = nullptr);

}  // namespace nmm::solve
