// The geometry of a scene: bodies (a polygon with holes and a material) and joints (polylines
// of a joint set), the two things nmm-preprocess cuts covers with, and which a run cannot
// change without preprocessing again (excavate removes bodies at the start of a run instead).
// The checks that need exact predicates (self-intersecting polygons, holes outside their body,
// overlapping bodies) are preprocess/scene_geometry.h's.
#pragma once

#include <cstddef>
#include <vector>

#include "common/scene/joint_sets.h"
#include "common/scene/materials.h"
#include "common/vec2.h"

namespace nmm {

class JsonReader;


struct BodyDef {
  int material = -1;        ///< index into SceneDef::materials
  Ring outer;               ///< outer boundary, m
  std::vector<Ring> holes;  ///< holes strictly inside `outer`, m
};

struct JointDef {
  int set = -1;              ///< index into SceneDef::joint_sets
  std::vector<Vec2> points;  ///< polyline, >= 2 points, no zero-length segment, m
};

/// bodies[i]: {material, outer: polygon, holes: [polygon, ...]}.
BodyDef read_body(const JsonReader& r, const std::vector<MaterialDef>& materials);

/// joints[i]: {set, points: polyline}.
JointDef read_joint(const JsonReader& r, const std::vector<JointSetDef>& sets);

/// An array of points (fixed_points, measure_points), m.
std::vector<Vec2> read_points(const JsonReader& r);

/// excavate: [body index, ...], each below `body_count`.
std::vector<int> read_excavate(const JsonReader& r, std::size_t body_count);

/// Signed area of a ring (shoelace), m². Positive for counter-clockwise.
double ring_signed_area(const Ring& ring);

/// Area of a body: outer minus holes, m².
double body_area(const BodyDef& body);

}  // namespace nmm
