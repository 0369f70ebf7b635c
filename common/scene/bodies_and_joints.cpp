// The geometry of a scene: see bodies_and_joints.h.
//
// Signed area (shoelace), taken relative to the first vertex p0:
//   A = ½ Σ_i (p_i − p0) × (p_{i+1} − p0)
#include "common/scene/bodies_and_joints.h"

#include <cmath>
#include <cstdint>
#include <string>

#include "common/scene/json_reader.h"

namespace nmm {

BodyDef read_body(const JsonReader& r, const std::vector<MaterialDef>& materials) {
  r.check_keys({"material", "outer", "holes"});
  BodyDef b;
  b.material = find_by_name(materials, r["material"], "material", "materials");
  b.outer = r["outer"].as_ring();
  if (const auto holes = r.optional("holes")) {
    holes->expect_array();
    for (std::size_t i = 0; i < holes->size(); ++i) b.holes.push_back((*holes)[i].as_ring());
  }
  return b;
}

JointDef read_joint(const JsonReader& r, const std::vector<JointSetDef>& sets) {
  r.check_keys({"set", "points"});
  JointDef j;
  j.set = find_by_name(sets, r["set"], "joint set", "joint_sets");
  j.points = r["points"].as_point_list(2, /*closed=*/false, "a joint");
  return j;
}

std::vector<Vec2> read_points(const JsonReader& r) {
  r.expect_array();
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < r.size(); ++i) points.push_back(r[i].as_point());
  return points;
}

std::vector<int> read_excavate(const JsonReader& r, std::size_t body_count) {
  r.expect_array();
  std::vector<int> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const std::int64_t b = r[i].as_integer(0);
    if (b >= static_cast<std::int64_t>(body_count))
      r[i].fail("no body " + std::to_string(b) + " (the scene has " + std::to_string(body_count) +
                ")");
    out.push_back(static_cast<int>(b));
  }
  return out;
}

double ring_signed_area(const Ring& ring) {
  // Shoelace relative to the first vertex: round-off proportional to the ring's own size rather
  // than to its distance from the origin.
  double twice = 0;
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) {
    const double ax = ring[i].x - ring[0].x, ay = ring[i].y - ring[0].y;
    const double bx = ring[i + 1].x - ring[0].x, by = ring[i + 1].y - ring[0].y;
    twice += ax * by - ay * bx;
  }
  return 0.5 * twice;
}

double body_area(const BodyDef& body) {
  double area = std::fabs(ring_signed_area(body.outer));
  for (const Ring& hole : body.holes) area -= std::fabs(ring_signed_area(hole));
  return area;
}

}  // namespace nmm
