// Absorbing (viscous) boundaries of a scene ("absorbing": [...]; docs/absorbing-boundaries.md):
// Lysmer–Kuhlemeyer dashpots on the boundary under a polyline, optionally letting an incoming
// wave in. The solver's side is solver/discretisation/absorbing_boundary.h.
#pragma once

#include <vector>

#include "common/scene/time_tables.h"
#include "common/vec2.h"

namespace nmm {

class JsonReader;

/// Lysmer–Kuhlemeyer dashpots on the body boundary under a polyline
/// (solver/discretisation/absorbing_boundary.h); with an input velocity the boundary is compliant
/// and lets that incoming wave in.
struct AbsorbingDef {
  std::vector<Vec2> points;  ///< polyline, >= 2 points, m
  TimeTable input_x;         ///< m/s, the incoming wave's particle velocity in x over time; empty: none
  TimeTable input_y;         ///< m/s, in y
};

/// absorbing: [{points: polyline, input_velocity: {x: TABLE, y: TABLE}}] (AbsorbingDef).
std::vector<AbsorbingDef> read_absorbing(const JsonReader& r);

}  // namespace nmm
