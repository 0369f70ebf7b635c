// What holds and loads a scene's bodies, apart from gravity: point loads (with a time table
// each), supports along the boundary (held, or moving at a velocity with a velocity history),
// tractions on the boundary, and a ground motion (base acceleration). Fixed points are plain
// points (common/scene/bodies_and_joints.h read_points). The solver applies them in
// solver/discretisation/boundary_conditions.h (docs/staged-analysis.md).
#pragma once

#include <vector>

#include "common/scene/time_tables.h"
#include "common/vec2.h"

namespace nmm {

class JsonReader;

struct LoadDef {
  Vec2 point;  ///< m, where the force acts
  Vec2 force;  ///< N per unit thickness
};

/// Supports along the body boundary under a polyline: the covers of the ME edges lying on it are
/// held by penalty springs in x, y or both (solver/discretisation/boundary_conditions.h).
struct SupportDef {
  std::vector<Vec2> points;  ///< polyline, >= 2 points, m
  bool fix_x = false;        ///< held in x
  bool fix_y = false;        ///< held in y
  /// m/s, the held position moves at this velocity from t = 0 (UDEC's `boundary xvelocity`):
  /// held at u = velocity·t in its held directions; zero in a free direction. 0: held in place
  Vec2 velocity;
  /// –, a factor on the velocity over time (UDEC's velocity history): held at
  /// u = velocity·∫0^t f dt' (support_travel()); empty: f = 1
  TimeTable table;
};

/// Traction on the body boundary under a polyline (solver/discretisation/boundary_conditions.h).
struct TractionDef {
  std::vector<Vec2> points;  ///< polyline, >= 2 points, m
  double normal = 0;         ///< Pa, along the outward normal (< 0 pushes into the body)
  double shear = 0;          ///< Pa, along the polyline's direction
  bool from_insitu = false;  ///< the traction is σ_insitu(x)·n instead (matches the in-situ stress)
  TimeTable table;           ///< factor on the traction over time; empty: 1
};

/// loads: [{point, force, table}]: the loads, and one time table per load (empty: factor 1).
void read_loads(const JsonReader& r, std::vector<LoadDef>& loads, std::vector<TimeTable>& tables);

/// supports: [{points: polyline, fix: x | y | xy, velocity: [vx, vy], table}].
std::vector<SupportDef> read_supports(const JsonReader& r);

/// tractions: [{points: polyline, normal, shear | from_insitu: true, table}].
std::vector<TractionDef> read_tractions(const JsonReader& r);

/// base_acceleration: {x: TABLE, y: TABLE} (m/s² over time; a table left out: none).
void read_base_acceleration(const JsonReader& r, TimeTable& x, TimeTable& y);

}  // namespace nmm
