// Water in the joints of a scene ("water": {...}; docs/contact.md "Water in the joints"): a
// phreatic surface (hydrostatic pressure below it) and per-joint pressures. The solver's side
// is solver/discretisation/joint_water.h.
#pragma once

#include <vector>

#include "common/vec2.h"

namespace nmm {

class JsonReader;
struct SceneDef;

/// Water in the joints: a pressure p (Pa) on both faces of every joint (and on every body
/// boundary) below the phreatic surface, or from a per-joint entry (solver/discretisation/joint_water.h).
struct JointWaterDef {
  int joint = -1;               ///< index into SceneDef::joints
  std::vector<double> at;       ///< m, distance along the joint from its first point (table rows)
  std::vector<double> pressure; ///< Pa, ≥ 0, one per row of `at` (one row: uniform)
  double fill_depth = -1;       ///< m, ≥ 0: filled from its lowest point to this height (hydrostatic); −1: the table
};
struct WaterDef {
  bool present = false;            ///< "water" given
  double density = 1000;           ///< kg/m³, ρw (γw = ρw·|g|)
  std::vector<Vec2> phreatic;      ///< m, water table polyline (empty: none), single-valued across gravity
  std::vector<JointWaterDef> joints;  ///< per-joint pressures, replacing the phreatic surface on those joints
};

/// water: {density, phreatic: polyline, joints: [{joint, pressure | fill_depth}]} (WaterDef).
/// Reads the scene's gravity (hydrostatic pressure needs it) and joints (read before).
WaterDef read_water(const JsonReader& r, const SceneDef& scene);

}  // namespace nmm
