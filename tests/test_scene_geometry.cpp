// Geometric scene checks: each bad polygon is named by its JSON path.
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/scene.h"
#include "preprocess/scene_geometry.h"

namespace nmm::pre {
namespace {

SceneDef one_body(Ring outer, std::vector<Ring> holes = {}) {
  SceneDef s;
  s.materials.push_back({"rock", 2650, 1e10, 0.25, {}});
  BodyDef b;
  b.material = 0;
  b.outer = std::move(outer);
  b.holes = std::move(holes);
  s.bodies.push_back(b);
  s.mesh_size = 0.5;
  return s;
}

std::string where_of(const SceneDef& s) {
  try {
    check_scene_geometry(s, "scene.json");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.json");
    return e.where() + " | " + e.message();
  }
  return "";
}

const Ring kSquare{{0, 0}, {4, 0}, {4, 4}, {0, 4}};

TEST(SceneGeometry, ValidBodiesPass) {
  EXPECT_EQ(where_of(one_body(kSquare)), "");
  EXPECT_EQ(where_of(one_body({{0, 0}, {0, 4}, {4, 4}, {4, 0}})), "") << "clockwise is fine";
  EXPECT_EQ(where_of(one_body(kSquare, {{{1, 1}, {2, 1}, {2, 2}}, {{3, 3}, {3.5, 3}, {3.5, 3.5}}})), "");
  // A vertex in the middle of a straight edge is still a simple polygon.
  EXPECT_EQ(where_of(one_body({{0, 0}, {2, 0}, {4, 0}, {4, 4}, {0, 4}})), "");
}

TEST(SceneGeometry, BowTieIsSelfIntersecting) {
  const std::string w = where_of(one_body({{0, 0}, {4, 4}, {4, 0}, {0, 4}}));
  EXPECT_EQ(w.rfind("/bodies/0/outer/0 | self-intersecting polygon", 0), 0u) << w;
}

TEST(SceneGeometry, VertexTouchingAnotherEdgeIsSelfIntersecting) {
  // Point 3 (2, 0) lies on edge 0.
  const std::string w = where_of(one_body({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}));
  EXPECT_NE(w.find("self-intersecting"), std::string::npos) << w;
}

TEST(SceneGeometry, FoldBackAlongALineIsSelfIntersecting) {
  const std::string w = where_of(one_body({{0, 0}, {4, 0}, {2, 0}, {2, 3}}));
  EXPECT_NE(w.find("self-intersecting"), std::string::npos) << w;
}

TEST(SceneGeometry, HoleOutsideBody) {
  const std::string w = where_of(one_body(kSquare, {{{5, 5}, {6, 5}, {6, 6}}}));
  EXPECT_EQ(w, "/bodies/0/holes/0 | hole lies outside its body's outer boundary");
}

TEST(SceneGeometry, HoleTouchingOuterBoundary) {
  const std::string w = where_of(one_body(kSquare, {{{0, 1}, {2, 1}, {2, 2}}}));
  EXPECT_EQ(w.rfind("/bodies/0/holes/0 | hole touches or crosses the outer boundary", 0), 0u) << w;
}

TEST(SceneGeometry, HolesOverlappingOrNested) {
  std::string w = where_of(one_body(kSquare, {{{1, 1}, {3, 1}, {3, 3}}, {{2, 1.5}, {3.5, 1.5}, {3.5, 3.5}}}));
  EXPECT_EQ(w.rfind("/bodies/0/holes/1 | hole touches or crosses hole 0", 0), 0u) << w;
  w = where_of(one_body(kSquare, {{{1, 1}, {3, 1}, {3, 3}, {1, 3}}, {{1.5, 1.5}, {2, 1.5}, {2, 2}}}));
  EXPECT_EQ(w, "/bodies/0/holes/1 | hole lies inside hole 0 (nested holes)");
}

TEST(SceneGeometry, SelfIntersectingHole) {
  const std::string w = where_of(one_body(kSquare, {{{1, 1}, {3, 3}, {3, 1}, {1, 3}}}));
  EXPECT_EQ(w.rfind("/bodies/0/holes/0/0 | self-intersecting", 0), 0u) << w;
}

}  // namespace
}  // namespace nmm::pre
