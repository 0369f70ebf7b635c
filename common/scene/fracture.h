// Fracturing of intact rock in a scene ("fracture": {crack_set}; docs/fracture.md): on when the
// block is present and some material has a strength (common/scene/materials.h). The solver's
// side is solver/fracture/.
#pragma once

namespace nmm {

class JsonReader;
struct SceneDef;

/// Fracturing of intact rock (scene key "fracture"; docs/fracture.md): on when present and some
/// material has a strength.
struct FractureDef {
  bool present = false;
  int crack_set = -1;  ///< joint set whose law the faces of new cracks use
  double tip_step = 0; ///< m, how far a tip grows at once by its toughness (0: the mesh size)
  /// A tip of a crack that carries fluid grows against the viscous fluid's apparent toughness
  /// where it exceeds K_Ic (solver/fracture/tip_growth.h; docs/flow.md "Hydraulic fracturing").
  bool viscous_tip = false;
};

/// fracture: {crack_set, tip_step, viscous_tip}. Reads the scene's joint sets (read before).
/// Fracturing goes with every cover order (docs/higher-order-covers.md "Fracturing"), bolts and
/// absorbing boundaries: a re-cut ties the bolts again to the pieces of rock and
/// lays the dashpots on the re-cut edges (docs/fracture.md "Bolts and absorbing boundaries").
FractureDef read_fracture(const JsonReader& r, const SceneDef& scene);

}  // namespace nmm
