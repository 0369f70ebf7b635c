// Scene definition: everything a scene file (JSON with comments) says, parsed and validated once
// into plain definition structs. Contract: docs/interface.md ("Scene file").
//
// Units are SI throughout: m, kg, s, N, Pa; 2D with unit thickness. Forces are N per metre of
// thickness. Materials and joint sets are referred to by index into the sorted-by-name vectors
// below (the JSON objects are ordered by key, so the indices are deterministic).
//
// SceneDef is the one struct users of a scene see. Each part of the scene — its definition
// structs and the reader of its keys — is a file pair of common/scene/, all written with the one
// JSON reader common/scene/json_reader.h, which names the JSON path of every mistake:
//   materials            materials and the strength of intact rock
//   joint_laws           a joint set's normal and shear laws
//   joint_sets           joint sets, and the statistics of a generated set (DFN)
//   bodies_and_joints    bodies, joints, points, excavation; areas
//   solver_settings      the solver block
//   time_tables          time tables, inline or from a CSV file
//   loads_and_supports   point loads, supports, tractions, base acceleration
//   insitu_stress        the initial stress
//   water                water in the joints
//   fracture             fracturing of intact rock
//   bolts                rock bolts and cables
//   absorbing            absorbing boundaries
//   flow                 fluid flow along the joints
// parse_scene() reads them in a fixed order (scene.cpp) and checks structure, types and physical
// ranges (everything that needs no geometry kernel). The geometric checks that need exact
// predicates (self-intersecting polygons, holes outside their body, overlapping bodies) live in
// preprocess/scene_geometry.h.
#pragma once

#include <string>
#include <vector>

#include "common/scene/absorbing.h"
#include "common/scene/bodies_and_joints.h"
#include "common/scene/bolts.h"
#include "common/scene/flow.h"
#include "common/scene/fracture.h"
#include "common/scene/insitu_stress.h"
#include "common/scene/joint_laws.h"
#include "common/scene/joint_sets.h"
#include "common/scene/json_text.h"
#include "common/scene/limits.h"
#include "common/scene/loads_and_supports.h"
#include "common/scene/materials.h"
#include "common/scene/solver_settings.h"
#include "common/scene/time_tables.h"
#include "common/scene/water.h"
#include "common/vec2.h"

namespace nmm {

enum class PlaneKind { strain, stress };

struct SceneDef {
  std::string name;                     ///< free text, "" if absent
  bool has_gravity = false;             ///< "gravity" present
  Vec2 gravity;                         ///< m/s²
  PlaneKind plane = PlaneKind::strain;  ///< plane strain (default) or plane stress
  std::vector<MaterialDef> materials;   ///< sorted by name
  std::vector<JointSetDef> joint_sets;  ///< sorted by name
  std::vector<BodyDef> bodies;
  std::vector<JointDef> joints;
  int interface_set = -1;  ///< joint set for touching bodies, -1 if absent
  double mesh_size = 0;    ///< m, side of the equilateral mathematical triangles
  /// "mesh.split_gap_ends": the end of a body-boundary gap narrower than the mesh (a slot) is
  /// carried on to the edge of its triangle for the covers, which it then splits (cover_cutter.cpp
  /// step 5); false (default): covers are the connected pieces of star ∩ body minus joints
  bool split_gap_ends = false;
  std::vector<Vec2> fixed_points;    ///< m
  std::vector<LoadDef> loads;
  std::vector<TimeTable> load_tables;  ///< [load] factor on its force over time (empty: 1); may be shorter than loads
  std::vector<Vec2> measure_points;  ///< m
  std::vector<SupportDef> supports;
  std::vector<TractionDef> tractions;
  InsituStressDef insitu_stress;
  std::vector<int> excavate;         ///< bodies removed at the start of this run
  TimeTable base_acceleration_x;     ///< m/s², ground acceleration in x over time; empty: none
  TimeTable base_acceleration_y;     ///< m/s², in y
  WaterDef water;                    ///< water pressure in the joints (absent: dry)
  FractureDef fracture;              ///< intact rock that breaks (absent: it never does)
  std::vector<BoltDef> bolts;        ///< rock bolts and cables, numbered from 0 in this order
  std::vector<AbsorbingDef> absorbing;  ///< absorbing (viscous) boundaries
  FlowDef flow;                      ///< fluid flow along the joints (absent: none)
  SolverDef solver;
};

/// Parses scene text (JSON, // and /* */ comments allowed) and validates it.
/// Throws InputError(file, JSON path, message) on the first problem found.
SceneDef parse_scene(const std::string& text, const std::string& file);

/// Validates an already parsed JSON document as a scene (used after merge patches).
SceneDef scene_from_json(const nlohmann::json& doc, const std::string& file);

}  // namespace nmm
