// Cover cutting against known answers: the seed paper's Fig. 2 (a crack splits the covers it
// crosses, a crack tip leaves its cover whole), area conservation on random joint networks and
// every degenerate case named in issue 2.
//
// Lattice used below (cover_cutter.cpp): node (i, j) at x = (i + ½·(j mod 2))·h, y = j·h·√3/2.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

#include "preprocess/cover_cutter.h"
#include "preprocess/loop_area.h"
#include "common/error.h"
#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::pre {
namespace {

SceneDef box_scene(double x0, double y0, double x1, double y1, double h) {
  SceneDef s;
  s.materials.push_back({"rock", 2650, 1e10, 0.25, {}});
  JointSetDef js;
  js.name = "j";
  js.friction_deg = 30;
  js.normal.kn = 1e11;
  js.shear.ks = 4e10;
  s.joint_sets.push_back(js);
  BodyDef b;
  b.material = 0;
  b.outer = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  s.bodies.push_back(b);
  s.mesh_size = h;
  return s;
}

void add_joint(SceneDef& s, std::vector<Vec2> pts) { s.joints.push_back({0, std::move(pts)}); }

double scene_area(const SceneDef& s) {
  double a = 0;
  for (const BodyDef& b : s.bodies) a += body_area(b);
  return a;
}

std::vector<double> block_areas(const Mesh& m) {
  std::vector<double> a(m.block_count(), 0.0);
  for (std::size_t e = 0; e < m.element_count(); ++e) a[m.element_block[e]] += element_area(m, e);
  std::sort(a.begin(), a.end());
  return a;
}

// Physical covers per node, keyed by node coordinates rounded to 1e-9.
std::map<std::pair<long long, long long>, int> covers_per_node(const Mesh& m) {
  std::map<std::pair<long long, long long>, int> c;
  for (std::int32_t n : m.cover_node) {
    const long long x = std::llround(m.node_xy[2 * n] * 1e9);
    const long long y = std::llround(m.node_xy[2 * n + 1] * 1e9);
    ++c[{x, y}];
  }
  return c;
}

int covers_at(const Mesh& m, double x, double y) {
  const auto c = covers_per_node(m);
  const auto it = c.find({std::llround(x * 1e9), std::llround(y * 1e9)});
  return it == c.end() ? 0 : it->second;
}

// Structural invariants every mesh must satisfy.
void expect_consistent(const Mesh& m, const SceneDef& s) {
  const double area = scene_area(s);
  EXPECT_NEAR(total_area(m), area, 1e-9 * area);
  ASSERT_EQ(m.element_covers.size(), 3 * m.element_count());
  std::vector<int> elements_of_cover(m.cover_count(), 0);
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    EXPECT_GE(element_area(m, e), 0.0) << "element " << e << " is clockwise";
    const std::int32_t t = m.element_triangle[e];
    for (int k = 0; k < 3; ++k) {
      const std::int32_t pc = m.element_covers[3 * e + k];
      ASSERT_GE(pc, 0);
      EXPECT_EQ(m.cover_node[pc], m.triangle_nodes[3 * t + k]);
      EXPECT_EQ(m.cover_body[pc], m.element_body[e]);
      ++elements_of_cover[pc];
    }
    EXPECT_EQ(m.block_body[m.element_block[e]], m.element_body[e]);
  }
  for (int n : elements_of_cover) EXPECT_GT(n, 0);
  EXPECT_EQ(m.mathematical_cover_count(), m.node_count());
}

TEST(CoverCutter, UncutSquareHasOneCoverPerNode) {
  const SceneDef s = box_scene(0, 0, 4, 3, 0.5);
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  EXPECT_EQ(m.block_count(), 1u);
  // star ∩ square is convex, hence connected: exactly one cover per node.
  EXPECT_EQ(m.cover_count(), m.node_count());
  // No joints: only the outer boundary gives contact candidates; its length is the perimeter.
  double len = 0;
  for (std::size_t c = 0; c < m.contact_edge.size(); ++c) {
    const std::int32_t v = m.contact_edge[c];
    const std::int32_t e = m.contact_edge_element[c];
    const std::int32_t last = m.element_loop_offset[e + 1] - 1;
    const std::int32_t w = v == last ? m.element_loop_offset[e] : v + 1;
    len += std::hypot(m.loop_xy[2 * w] - m.loop_xy[2 * v], m.loop_xy[2 * w + 1] - m.loop_xy[2 * v + 1]);
    EXPECT_EQ(m.contact_edge_opposite[c], -1);
  }
  EXPECT_NEAR(len, 14.0, 1e-12);
}

// An edge crack typed along the node row y = 0 from either side of a 1 m strip, 0.3 m long, h =
// 0.05 m: node 6 lies at 6 × 0.05 = 0.30000000000000004, node 14 at 0.7000000000000001. Typed from
// the left, the crack ended 5.6e-17 m short of node 6, so the edge from node 5 was not cut to its
// end and node 5's star stayed whole (its faces tied one node before the tip); from the right it ran
// an ulp past node 14 and split node 15's star. Snapped onto its node, either way every star it
// crosses splits and the tip's star stays whole: the two meshes mirror each other cover for cover.
TEST(CoverCutter, AJointEndWithinRoundOffOfANodeEndsOnIt) {
  auto covers_on_row = [](Vec2 from, Vec2 to) {
    SceneDef s = box_scene(0, -1, 1, 1, 0.05);
    add_joint(s, {from, to});
    const Mesh m = build_mesh(s, "t");
    expect_consistent(m, s);
    std::map<long, int> at;  // node x in units of 1e-6 m → its physical covers
    for (std::size_t pc = 0; pc < m.cover_count(); ++pc) {
      const Vec2 n{m.node_xy[2 * m.cover_node[pc]], m.node_xy[2 * m.cover_node[pc] + 1]};
      if (n.y == 0) ++at[std::lround(n.x * 1e6)];
    }
    return at;
  };
  const std::map<long, int> left = covers_on_row({0, 0}, {0.3, 0}), right = covers_on_row({1, 0}, {0.7, 0});
  for (int k = 0; k <= 20; ++k) {
    const long x = 50000L * k, mirror = 1000000L - x;
    EXPECT_EQ(left.at(x), k < 6 ? 2 : 1) << "node at x = " << x * 1e-6;
    EXPECT_EQ(left.at(x), right.at(mirror)) << "node at x = " << x * 1e-6;
  }
}

// Seed paper Fig. 2: a crack AB inside the body. With h = 1 and the crack on y = 0.3 from
// x = -1.2 to x = 2.2, the stars crossed from side to side are those of nodes (0,0), (1,0)
// [row 0] and (-0.5, √3/2), (0.5, √3/2), (1.5, √3/2) [row 1]: each splits into two physical
// covers. The stars holding a tip, (-1,0), (2,0), (-1.5,√3/2), (2.5,√3/2), stay whole.
TEST(CoverCutter, SeedFig2CrackSplitsCrossedCoversAndTipLeavesCoverWhole) {
  SceneDef s = box_scene(-5, -5, 5, 5, 1.0);
  add_joint(s, {{-1.2, 0.3}, {2.2, 0.3}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  const double r = std::sqrt(3.0) / 2;
  for (double x : {0.0, 1.0}) EXPECT_EQ(covers_at(m, x, 0), 2) << "node " << x << ",0";
  for (double x : {-0.5, 0.5, 1.5}) EXPECT_EQ(covers_at(m, x, r), 2) << "node " << x << ",r";
  for (double x : {-1.0, 2.0}) EXPECT_EQ(covers_at(m, x, 0), 1) << "tip node " << x << ",0";
  for (double x : {-1.5, 2.5}) EXPECT_EQ(covers_at(m, x, r), 1) << "tip node " << x << ",r";
  EXPECT_EQ(m.cover_count(), m.node_count() + 5);
  EXPECT_EQ(m.block_count(), 1u) << "an interior crack does not split the body";
  // The two tip elements keep one element each, with the crack as a slit in their loop.
  int slit_loops = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    int joint_edges = 0;
    for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v)
      joint_edges += (m.loop_edge_origin[v] & kEdgeJoint) ? 1 : 0;
    if (joint_edges >= 2) {
      ++slit_loops;
      // A slit runs along both faces of the crack: the element is still counter-clockwise
      // and the crack edges' opposite element is the element itself.
      for (std::size_t c = 0; c < m.contact_edge.size(); ++c)
        if (m.contact_edge_element[c] == static_cast<std::int32_t>(e)) {
          EXPECT_EQ(m.contact_edge_opposite[c], static_cast<std::int32_t>(e));
        }
    }
  }
  EXPECT_EQ(slit_loops, 2);
}

// A slot narrower than the mesh (mesh.split_gap_ends, cover_cutter.cpp step 5): Petersson's beam's
// 10 mm slot, 0.1 m deep, at h 0.025 m. Its flat end (y 0.1 m, x 1.095–1.105 m) lies in the
// triangle (1.1, 0.0866), (1.1125, 0.1083), (1.0875, 0.1083); the node (1.1, 0.0866) lies in the
// slot and its star reaches round the end, so by default its one cover holds both walls. With
// the split the end is carried on up x = 1.1 to the triangle's top edge: that triangle is two
// elements, the node has one cover per wall, the top edge's two nodes keep one each (their
// stars join round the extension's end), the body stays one block and no contact lies on the
// extension. A slot wider than h has no such end and is cut as before.
SceneDef slot_scene(double width, bool split) {
  SceneDef s = box_scene(0, 0, 2.2, 0.2, 0.025);
  const double a = 1.1 - width / 2, b = 1.1 + width / 2;
  s.bodies[0].outer = {{0, 0}, {a, 0}, {a, 0.1}, {b, 0.1}, {b, 0}, {2.2, 0}, {2.2, 0.2}, {0, 0.2}};
  s.split_gap_ends = split;
  return s;
}

TEST(CoverCutter, NarrowSlotEndSplitsTheCoversReachingRoundIt) {
  const double r = 0.025 * std::sqrt(3.0) / 2;
  const SceneDef joined_scene = slot_scene(0.01, false), split_scene = slot_scene(0.01, true);
  const Mesh joined = build_mesh(joined_scene, "t"), split = build_mesh(split_scene, "t");
  expect_consistent(joined, joined_scene);
  expect_consistent(split, split_scene);
  EXPECT_EQ(covers_at(joined, 1.1, 4 * r), 1);
  EXPECT_EQ(covers_at(split, 1.1, 4 * r), 2);
  EXPECT_EQ(covers_at(split, 1.0875, 5 * r), 1);
  EXPECT_EQ(covers_at(split, 1.1125, 5 * r), 1);
  EXPECT_EQ(split.cover_count(), joined.cover_count() + 1);
  EXPECT_EQ(split.element_count(), joined.element_count() + 1);
  EXPECT_EQ(split.block_count(), 1u);
  // The extension: one loop edge on each side, on x = 1.1 from the slot's end to the top edge.
  int on_extension = 0;
  for (std::size_t e = 0; e < split.element_count(); ++e)
    for (std::int32_t v = split.element_loop_offset[e]; v < split.element_loop_offset[e + 1]; ++v) {
      if (!(split.loop_edge_origin[v] & kEdgeExtension)) continue;
      ++on_extension;
      const std::int32_t w = v + 1 < split.element_loop_offset[e + 1] ? v + 1 : split.element_loop_offset[e];
      EXPECT_EQ(split.loop_xy[2 * v], 1.1);
      EXPECT_EQ(split.loop_xy[2 * w], 1.1);
      EXPECT_NEAR(std::abs(split.loop_xy[2 * w + 1] - split.loop_xy[2 * v + 1]), 5 * r - 0.1, 1e-12);
    }
  EXPECT_EQ(on_extension, 2);
  for (std::int32_t v : split.contact_edge) EXPECT_FALSE(split.loop_edge_origin[v] & kEdgeExtension);
  // 30 mm is wider than h: no gap end, the same mesh with or without the key.
  const Mesh wide_joined = build_mesh(slot_scene(0.03, false), "t"), wide_split = build_mesh(slot_scene(0.03, true), "t");
  EXPECT_EQ(wide_split.element_count(), wide_joined.element_count());
  EXPECT_EQ(wide_split.element_covers, wide_joined.element_covers);
}

TEST(CoverCutter, ThroughJointMakesTwoBlocksWithExactAreas) {
  SceneDef s = box_scene(0, 0, 4, 2, 0.3);
  add_joint(s, {{1.0, -1.0}, {3.0, 3.0}});  // y = 2x - 3 crosses y=0 at 1.5, y=2 at 2.5
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  ASSERT_EQ(m.block_count(), 2u);
  const auto a = block_areas(m);
  // Left trapezoid: bases 1.5 (y = 0) and 2.5 (y = 2), height 2 → 4 m²; the right one too.
  EXPECT_NEAR(a[0], 4.0, 1e-12);
  EXPECT_NEAR(a[1], 4.0, 1e-12);
}

TEST(CoverCutter, JointThroughMeshNodes) {
  // x = 0 passes through the nodes of even rows and crosses the odd rows' horizontal edges.
  SceneDef s = box_scene(-3, -3, 3, 3, 0.5);
  add_joint(s, {{0, -4}, {0, 4}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  ASSERT_EQ(m.block_count(), 2u);
  const auto a = block_areas(m);
  EXPECT_NEAR(a[0], 18.0, 1e-12);
  EXPECT_NEAR(a[1], 18.0, 1e-12);
  EXPECT_EQ(covers_at(m, 0, 0), 2);
}

TEST(CoverCutter, JointAlongMeshEdgesSplitsCoversOnTheLine) {
  SceneDef s = box_scene(-3, -3, 3, 3, 0.5);
  add_joint(s, {{-4, 0}, {4, 0}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  ASSERT_EQ(m.block_count(), 2u);
  // The joint lies on mesh edges: no triangle is cut, so elements = triangles.
  EXPECT_EQ(m.element_count(), m.triangle_count());
  for (double x = -3; x <= 3; x += 0.5) EXPECT_EQ(covers_at(m, x, 0), 2) << x;
  // Loop edges on the joint are also mesh edges.
  int both = 0;
  for (std::uint8_t o : m.loop_edge_origin) both += (o & kEdgeJoint) && (o & kEdgeMesh);
  EXPECT_EQ(both, 2 * 12);  // 12 edges of length 0.5, seen from both sides
}

TEST(CoverCutter, JointsCrossingAtANode) {
  SceneDef s = box_scene(-3, -3, 3, 3, 0.5);
  add_joint(s, {{-4, 0}, {4, 0}});
  add_joint(s, {{0, -4}, {0, 4}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  ASSERT_EQ(m.block_count(), 4u);
  for (double a : block_areas(m)) EXPECT_NEAR(a, 9.0, 1e-12);
  EXPECT_EQ(covers_at(m, 0, 0), 4);
}

TEST(CoverCutter, JointEndingAtANodeLeavesThatCoverWhole) {
  SceneDef s = box_scene(-3, -3, 3, 3, 0.5);
  add_joint(s, {{-4, 0}, {0, 0}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  EXPECT_EQ(m.block_count(), 1u);
  EXPECT_EQ(covers_at(m, 0, 0), 1) << "the tip is the centre of this star";
  for (double x = -3; x <= -0.5; x += 0.5) EXPECT_EQ(covers_at(m, x, 0), 2) << x;
  EXPECT_EQ(covers_at(m, 0.5, 0), 1);
}

TEST(CoverCutter, OverlappingCollinearJointsActAsOne) {
  SceneDef s = box_scene(-3, -3, 3, 3, 0.5);
  add_joint(s, {{-4, 0.2}, {1, 0.2}});
  add_joint(s, {{-1, 0.2}, {4, 0.2}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  ASSERT_EQ(m.block_count(), 2u);
  const auto a = block_areas(m);
  EXPECT_NEAR(a[0], 6 * 2.8, 1e-12);
  EXPECT_NEAR(a[1], 6 * 3.2, 1e-12);
  // Where the joints overlap, the edge names the lower joint index.
  for (std::size_t v = 0; v < m.loop_edge_joint.size(); ++v) {
    if (!(m.loop_edge_origin[v] & kEdgeJoint)) continue;
    const double x = m.loop_xy[2 * v];
    if (x > -0.99 && x < 0.99) {
      EXPECT_EQ(m.loop_edge_joint[v], 0);
    }
  }
}

TEST(CoverCutter, TJunction) {
  SceneDef s = box_scene(-3, -3, 3, 3, 0.5);
  add_joint(s, {{-4, 0.37}, {4, 0.37}});
  add_joint(s, {{0.11, -4}, {0.11, 0.37}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  ASSERT_EQ(m.block_count(), 3u);
  const auto a = block_areas(m);
  // Below y = 0.37 the stem splits 2.89 × 3.37 from 3.11 × 3.37; above it 6 × 2.63.
  EXPECT_NEAR(a[0], 2.89 * 3.37, 1e-12);
  EXPECT_NEAR(a[1], 3.11 * 3.37, 1e-12);
  EXPECT_NEAR(a[2], 6 * 2.63, 1e-12);
}

TEST(CoverCutter, JointOnBodyBoundaryChangesNothing) {
  SceneDef s = box_scene(-3, -3, 3, 3, 0.5);
  const Mesh plain = build_mesh(s, "t");
  add_joint(s, {{-4, 3}, {4, 3}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  EXPECT_EQ(m.block_count(), 1u);
  EXPECT_EQ(m.cover_count(), plain.cover_count());
  EXPECT_EQ(m.element_count(), plain.element_count());
  // The top side, 6 m long, is now both boundary and joint.
  double on_both = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e)
    for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v) {
      const std::int32_t w = v + 1 == m.element_loop_offset[e + 1] ? m.element_loop_offset[e] : v + 1;
      if ((m.loop_edge_origin[v] & kEdgeJoint) && (m.loop_edge_origin[v] & kEdgeBoundary))
        on_both += std::abs(m.loop_xy[2 * w] - m.loop_xy[2 * v]);
    }
  EXPECT_NEAR(on_both, 6.0, 1e-12);
}

TEST(CoverCutter, JointPassingOneNanoHBesideANodeKeepsSliversAndArea) {
  const double h = 0.5, eps = 1e-9 * h;
  SceneDef s = box_scene(-3, -3, 3, 3, h);
  add_joint(s, {{eps, -4}, {eps, 4}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  ASSERT_EQ(m.block_count(), 2u);
  const auto a = block_areas(m);
  EXPECT_NEAR(a[0], 6 * (3 - eps), 1e-12);
  EXPECT_NEAR(a[1], 6 * (3 + eps), 1e-12);
  int slivers = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e)
    slivers += element_area(m, e) < 1e-6 * h * h ? 1 : 0;
  EXPECT_GT(slivers, 0) << "the slivers beside the even-row nodes are kept, not merged";
  // Nodes at x = 0 see the joint pass beside them: their stars are split.
  EXPECT_EQ(covers_at(m, 0, 0), 2);
}

TEST(CoverCutter, JointWhollyInsideOneTriangleIsBridged) {
  SceneDef s = box_scene(-3, -3, 3, 3, 1.0);
  add_joint(s, {{0.4, 0.2}, {0.6, 0.25}});  // inside the triangle (0,0),(1,0),(0.5,0.87)
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  EXPECT_EQ(m.block_count(), 1u);
  EXPECT_EQ(m.cover_count(), m.node_count());
  EXPECT_EQ(m.element_count(), m.triangle_count());
  int bridges = 0;
  for (std::uint8_t o : m.loop_edge_origin) bridges += (o & kEdgeBridge) ? 1 : 0;
  EXPECT_EQ(bridges, 2) << "one bridge, walked both ways";
}

TEST(CoverCutter, SmallBodyHoleInsideOneTriangle) {
  SceneDef s = box_scene(-3, -3, 3, 3, 1.0);
  s.bodies[0].holes.push_back({{0.4, 0.1}, {0.6, 0.1}, {0.5, 0.3}});
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  EXPECT_NEAR(total_area(m), 36 - 0.02, 1e-12);
  EXPECT_EQ(m.element_count(), m.triangle_count());
}

TEST(CoverCutter, TouchingBodiesStaySeparate) {
  SceneDef s = box_scene(0, 0, 2, 2, 0.5);
  BodyDef b;
  b.material = 0;
  b.outer = {{2, 0.3}, {4, 0.3}, {4, 1.7}, {2, 1.7}};
  s.bodies.push_back(b);
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  ASSERT_EQ(m.block_count(), 2u);
  EXPECT_NE(m.block_body[0], m.block_body[1]);
  // The shared edge x = 2, 0.3 ≤ y ≤ 1.7: candidates on both sides facing the other body.
  double facing = 0;
  for (std::size_t c = 0; c < m.contact_edge.size(); ++c) {
    const std::int32_t opp = m.contact_edge_opposite[c];
    if (opp < 0) continue;
    EXPECT_NE(m.element_body[opp], m.element_body[m.contact_edge_element[c]]);
    const std::int32_t v = m.contact_edge[c], e = m.contact_edge_element[c];
    const std::int32_t w = v + 1 == m.element_loop_offset[e + 1] ? m.element_loop_offset[e] : v + 1;
    facing += std::abs(m.loop_xy[2 * w + 1] - m.loop_xy[2 * v + 1]);
  }
  EXPECT_NEAR(facing, 2 * 1.4, 1e-12);
}

TEST(CoverCutter, OverlappingBodiesAreRejected) {
  SceneDef s = box_scene(0, 0, 2, 2, 0.5);
  BodyDef b;
  b.material = 0;
  b.outer = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};
  s.bodies.push_back(b);
  try {
    build_mesh(s, "scene.json");
    FAIL() << "overlap not detected";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "/bodies/1");
    EXPECT_NE(e.message().find("overlaps body 0"), std::string::npos) << e.what();
  }
}

TEST(CoverCutter, BodyInsideAnotherBodyIsRejected) {
  SceneDef s = box_scene(0, 0, 4, 4, 0.5);
  BodyDef b;
  b.material = 0;
  b.outer = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  s.bodies.push_back(b);
  EXPECT_THROW(build_mesh(s, "t"), InputError);
}

TEST(CoverCutter, BodyInsideAHoleIsFine) {
  SceneDef s = box_scene(0, 0, 4, 4, 0.5);
  s.bodies[0].holes.push_back({{1, 1}, {3, 1}, {3, 3}, {1, 3}});
  BodyDef b;
  b.material = 0;
  b.outer = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};  // fills the hole exactly: touches all round
  s.bodies.push_back(b);
  const Mesh m = build_mesh(s, "t");
  expect_consistent(m, s);
  EXPECT_EQ(m.block_count(), 2u);
  EXPECT_NEAR(total_area(m), 16.0, 1e-12);
}

TEST(CoverCutter, RandomJointNetworksConserveArea) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 11);
    SceneDef s = box_scene(0, 0, 10, 10, 0.7);
    s.bodies[0].holes.push_back({{4, 4}, {6, 4.5}, {5.5, 6}, {4.2, 5.5}});
    for (int j = 0; j < 40; ++j) {
      std::vector<Vec2> pts{{u(rng), u(rng)}, {u(rng), u(rng)}};
      if (j % 5 == 0) pts.push_back({u(rng), u(rng)});
      add_joint(s, pts);
    }
    const Mesh m = build_mesh(s, "t");
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_consistent(m, s);
    EXPECT_GT(m.block_count(), 1u);
  }
}

TEST(CoverCutter, SameSceneSameMesh) {
  SceneDef s = box_scene(0, 0, 10, 10, 0.7);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 11);
  for (int j = 0; j < 30; ++j) add_joint(s, {{u(rng), u(rng)}, {u(rng), u(rng)}});
  const Mesh a = build_mesh(s, "t"), b = build_mesh(s, "t");
  EXPECT_EQ(a.loop_xy, b.loop_xy);
  EXPECT_EQ(a.element_covers, b.element_covers);
  EXPECT_EQ(a.element_block, b.element_block);
  EXPECT_EQ(a.contact_edge_opposite, b.contact_edge_opposite);
}

}  // namespace
}  // namespace nmm::pre

namespace nmm {
namespace {

// A bow-tie needle four vertices long whose rounded loop encloses exactly no area (checked in
// rationals): summed in doubles from its four corners it reads 0, 0, +2.7e-20 and −2.7e-20 m².
// The cutter keeps a face whose loop encloses positive area, so a cut whose arrangement starts
// this loop at its third corner kept an element the same cut starting at its first dropped.
TEST(LoopArea, TheSignOfANeedleDoesNotDependOnTheCornerItsLoopStartsAt) {
  const std::vector<Vec2> needle{{1.1039200385961945, 0.2251440608216108},
                                 {1.1664200385961945, 0.1979896145240991},
                                 {1.1226700385961945, 0.21699772693235728},
                                 {1.1476700385961944, 0.20613594841335262}};
  int positive_in_doubles = 0, negative_in_doubles = 0;
  for (std::size_t r = 0; r < needle.size(); ++r) {
    std::vector<Vec2> loop(needle.begin() + static_cast<std::ptrdiff_t>(r), needle.end());
    loop.insert(loop.end(), needle.begin(), needle.begin() + static_cast<std::ptrdiff_t>(r));
    EXPECT_EQ(pre::loop_area_sign(loop.data(), loop.size()), 0) << "starting at corner " << r;
    double twice_area = 0;  // the rule the cutter had: the double sum about the first corner
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2 o = loop[0], p = loop[i], q = loop[(i + 1) % loop.size()];
      twice_area += (p.x - o.x) * (q.y - o.y) - (q.x - o.x) * (p.y - o.y);
    }
    positive_in_doubles += twice_area > 0;
    negative_in_doubles += twice_area < 0;
  }
  // The case is one that tells the rules apart: the double sum's sign moves with the start.
  EXPECT_EQ(positive_in_doubles, 1);
  EXPECT_EQ(negative_in_doubles, 1);
}

TEST(LoopArea, ATriangleAnticlockwiseIsPositiveAndClockwiseNegative) {
  const std::vector<Vec2> ccw{{0.1, 0.1}, {0.3, 0.1}, {0.1, 0.7}};
  const std::vector<Vec2> cw{{0.1, 0.1}, {0.1, 0.7}, {0.3, 0.1}};
  EXPECT_EQ(pre::loop_area_sign(ccw.data(), ccw.size()), 1);
  EXPECT_EQ(pre::loop_area_sign(cw.data(), cw.size()), -1);
  // A sliver one ulp off its line: positive however small, as the exact cut sees it.
  const double y = std::nextafter(0.2, 1.0);
  const std::vector<Vec2> sliver{{0.1, 0.2}, {0.9, 0.2}, {0.5, y}};
  EXPECT_EQ(pre::loop_area_sign(sliver.data(), sliver.size()), 1);
}

}  // namespace
}  // namespace nmm
