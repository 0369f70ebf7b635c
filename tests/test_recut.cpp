// Re-cutting where a new joint crosses (preprocess/recut.h) gives the mesh a whole cut of the
// scene with that joint gives: the same elements (loops, bodies, edge origins and joints) in every
// triangle, the same physical covers (the same partition of element corners), the same blocks and
// contact edges — compared up to the order of elements within a triangle and the start of each
// loop, which the arrangement may pick differently. And the map back to the old mesh names, for
// every new element, cover and vertex, the old one it is a piece of.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "common/lattice.h"
#include "common/mesh_compare.h"
#include "common/ring_geometry.h"
#include "preprocess/cover_cutter.h"
#include "preprocess/recut.h"
#include "reference/scene_pieces.h"

namespace nmm {
namespace {

SceneDef two_bodies() {
  SceneDef s = reference::interface_scene(0.5, 30);
  s.bodies = {reference::box(0, 0, 6, 2), reference::box(1, 2, 5, 4)};
  JointDef j;  // an older joint ending inside the lower body
  j.set = 0;
  j.points = {{0.3, 0.7}, {2.6, 1.3}};
  s.joints.push_back(j);
  return s;
}

// Adds a joint and checks recut against a whole cut; returns the map.
pre::RecutMap check_recut(SceneDef s, const std::vector<Vec2>& points, const char* what) {
  const Mesh old = pre::build_mesh(s, "old");
  JointDef crack;
  crack.set = 0;
  crack.points = points;
  s.joints.push_back(crack);
  const Mesh whole = pre::build_mesh(s, "whole");
  pre::RecutMap map;
  const Mesh m = pre::recut(old, s, s.joints.size() - 1, "recut", map);
  std::printf("%s: %zu triangles touched, %zu cut again of %zu; elements %zu → %zu (whole cut %zu), covers "
              "%zu → %zu, blocks %zu → %zu\n",
              what, map.cut_triangles.size(), map.region_triangles, old.triangle_count(), old.element_count(),
              m.element_count(), whole.element_count(), old.cover_count(), m.cover_count(), old.block_count(),
              m.block_count());
  EXPECT_GT(map.cut_triangles.size(), 0u) << what;
  EXPECT_LT(map.region_triangles, old.triangle_count() / 2) << what << ": only the neighbourhood is cut again";
  EXPECT_EQ(m.element_count(), whole.element_count()) << what;
  EXPECT_EQ(m.cover_count(), whole.cover_count()) << what;
  EXPECT_EQ(m.block_count(), whole.block_count()) << what;
  EXPECT_EQ(mesh_difference(m, whole), "") << what << ": the same elements, covers, blocks and contact edges";
  EXPECT_NEAR(total_area(m), total_area(old), 1e-9 * total_area(old)) << what;
  // The map: every new element lies in its parent (same triangle, area no larger), every new
  // cover is a piece of an old cover of its node, and a vertex's parent is at the same point.
  EXPECT_EQ(map.element_parent.size(), m.element_count());
  EXPECT_EQ(map.cover_parent.size(), m.cover_count());
  EXPECT_EQ(map.vertex_parent.size(), m.loop_vertex_count());
  std::vector<double> child_area(old.element_count(), 0.0);
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    const std::int32_t p = map.element_parent[e];
    EXPECT_GE(p, 0) << what;
    if (p < 0) continue;
    EXPECT_EQ(old.element_triangle[p], m.element_triangle[e]) << what;
    child_area[p] += element_area(m, e);
  }
  for (std::size_t p = 0; p < old.element_count(); ++p)
    EXPECT_NEAR(child_area[p], element_area(old, p), 1e-9 * old.mesh_size * old.mesh_size)
        << what << ": the pieces of element " << p << " fill it";
  for (std::size_t c = 0; c < m.cover_count(); ++c) {
    EXPECT_GE(map.cover_parent[c], 0) << what;
    if (map.cover_parent[c] < 0) continue;
    EXPECT_EQ(old.cover_node[map.cover_parent[c]], m.cover_node[c]) << what;
  }
  for (std::size_t v = 0; v < m.loop_vertex_count(); ++v)
    if (map.vertex_parent[v] >= 0) {
      EXPECT_EQ(old.loop_xy[2 * map.vertex_parent[v]], m.loop_xy[2 * v]);
      EXPECT_EQ(old.loop_xy[2 * map.vertex_parent[v] + 1], m.loop_xy[2 * v + 1]);
    }
  return map;
}

}  // namespace

// A region of every triangle is the whole cut, array for array.
// The comparison itself: a loop vertex moved by the rounding of a constructed point (a few ulps)
// is the same cut, by a micrometre it is not; another joint flag, another block or one element
// less is not either.
TEST(MeshDifference, ToleratesRoundingOfConstructedPointsAndNothingMore) {
  const Mesh m = pre::build_mesh(two_bodies(), "m");
  ASSERT_EQ(mesh_difference(m, m), "");
  std::size_t v = 0;  // a vertex the older joint constructed (on its edge, inside the body)
  while (v < m.loop_vertex_count() && m.loop_edge_joint[v] < 0) ++v;
  ASSERT_LT(v, m.loop_vertex_count());
  Mesh ulps = m, micro = m, flag = m;
  for (Mesh* x : {&ulps, &micro, &flag})
    for (std::size_t w = 0; w < m.loop_vertex_count(); ++w)  // every copy of the point moves
      if (m.loop_xy[2 * w] == m.loop_xy[2 * v] && m.loop_xy[2 * w + 1] == m.loop_xy[2 * v + 1]) {
        if (x == &ulps) x->loop_xy[2 * w] = std::nextafter(std::nextafter(m.loop_xy[2 * w], 1e9), 1e9);
        if (x == &micro) x->loop_xy[2 * w] += 1e-6;
      }
  flag.loop_edge_joint[v] = m.loop_edge_joint[v] + 1;
  EXPECT_EQ(mesh_difference(ulps, m), "") << "2 ulps apart";
  EXPECT_NE(mesh_difference(micro, m), "") << "1 µm apart";
  EXPECT_NE(mesh_difference(flag, m), "") << "another joint on an edge";
  Mesh blocks = m;
  for (std::int32_t& b : blocks.element_block) b = 0;
  ASSERT_GT(m.block_count(), 1u);
  EXPECT_NE(mesh_difference(blocks, m), "") << "one block for all";
}

TEST(Recut, ARegionOfEveryTriangleIsTheWholeCut) {
  const SceneDef s = two_bodies();
  const Mesh whole = pre::build_mesh(s, "whole");
  const Lattice lat = make_lattice(s.bodies, s.mesh_size);
  std::vector<std::array<std::int32_t, 3>> all;
  for (std::size_t t = 0; t < whole.triangle_count(); ++t) {
    std::array<std::int32_t, 3> key;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t n = whole.triangle_nodes[3 * t + k];
      const double x = whole.node_xy[2 * n], y = whole.node_xy[2 * n + 1];
      const std::int64_t j = std::llround(y / lat.dy);
      key[k] = lat.index(std::llround(x / lat.h - (((j % 2) + 2) % 2 == 1 ? 0.5 : 0.0)), j);
    }
    all.push_back(key);
  }
  const pre::RegionCut r = pre::cut_region(s, all, "region");
  EXPECT_EQ(r.mesh.element_loop_offset, whole.element_loop_offset);
  EXPECT_EQ(r.mesh.loop_xy, whole.loop_xy);
  EXPECT_EQ(r.mesh.loop_edge_origin, whole.loop_edge_origin);
  EXPECT_EQ(r.mesh.loop_edge_joint, whole.loop_edge_joint);
  EXPECT_EQ(r.mesh.element_covers, whole.element_covers);
  EXPECT_EQ(r.mesh.element_block, whole.element_block);
  EXPECT_EQ(r.mesh.contact_edge_opposite, whole.contact_edge_opposite);
}

TEST(Recut, ACrackInsideABlockIsCutAsTheWholeMeshWouldBe) {
  const pre::RecutMap map = check_recut(two_bodies(), {{3.1, 0.6}, {3.9, 1.45}}, "crack inside the lower body");
  EXPECT_LT(map.cut_triangles.size(), 12u);
}

TEST(Recut, ACrackAcrossABodySplitsItsBlock) {
  // From the upper body's left face to its right face: two blocks where there was one.
  SceneDef s = two_bodies();
  const Mesh old = pre::build_mesh(s, "old");
  check_recut(s, {{1, 3.1}, {5, 3.3}}, "crack across the upper body");
  JointDef crack;
  crack.set = 0;
  crack.points = {{1, 3.1}, {5, 3.3}};
  s.joints.push_back(crack);
  pre::RecutMap map;
  EXPECT_EQ(pre::recut(old, s, s.joints.size() - 1, "recut", map).block_count(), old.block_count() + 1);
}

TEST(Recut, CracksThroughNodesAlongEdgesAndFromATip) {
  // Through a lattice node (0.5, 0) + k·(0.5, 0.433): along a mesh edge direction from a node.
  const double dy = 0.5 * std::sqrt(3.0) / 2;
  check_recut(two_bodies(), {{2.0, 2 * dy}, {3.0, 4 * dy}}, "crack along mesh edges through nodes");
  // On from the older joint's tip (2.6, 1.3), bending.
  check_recut(two_bodies(), {{2.6, 1.3}, {3.4, 1.9}}, "crack continuing a joint from its tip");
  // A short crack wholly inside one triangle.
  check_recut(two_bodies(), {{4.1, 0.3}, {4.2, 0.35}}, "crack inside one triangle");
}

// A point a joint constructs on a mesh edge gets one double in every cut (issue 48). The re-cut
// links blocks across mesh-only edges by their rounded end points, so an old element beside the
// region and a re-cut element in it must round their common vertex alike. CGAL's to_double of a
// lazy number gave the midpoint of whatever interval the construction left, and the region cut
// and the whole cut forced the exact value at different points: here the older joint's crossing
// of a mesh edge came out 1 ulp apart (8 loop vertices with a twin a round-off away, 2 not in the
// whole cut), and on the step-path slope at h 0.5 m such a pair cut a three-sided piece off its
// block (2 blocks against 1 at t 0.02 s). Now every vertex is rounded from its exact value.
TEST(Recut, AConstructedPointRoundsAlikeInTheRegionAndTheWholeCut) {
  SceneDef s = reference::interface_scene(0.5, 30);
  s.bodies = {reference::box(0, 0, 4, 3)};
  JointDef j;  // an older joint, crossing mesh edges at constructed points
  j.set = 0;
  j.points = {{1.2750553671578448, 0.23540875034156006}, {2.1365271935998549, 1.8158726987588176}};
  s.joints.push_back(j);
  const pre::RecutMap map = check_recut(s, {{1.9564727882763981, 0.8660254037844386}, {2.0003418491968414, 1.0917288845608044}},
                                        "crack from a mesh row beside an older joint");
  const Mesh old = pre::build_mesh(s, "old");
  s.joints.push_back({0, {{1.9564727882763981, 0.8660254037844386}, {2.0003418491968414, 1.0917288845608044}}});
  const Mesh whole = pre::build_mesh(s, "whole");
  pre::RecutMap map2;
  const Mesh m = pre::recut(old, s, 1, "recut", map2);
  std::set<std::pair<double, double>> whole_points;
  for (std::size_t v = 0; v < whole.loop_vertex_count(); ++v) whole_points.insert({whole.loop_xy[2 * v], whole.loop_xy[2 * v + 1]});
  std::size_t not_whole = 0, twins = 0;
  for (std::size_t v = 0; v < m.loop_vertex_count(); ++v) {
    const double x = m.loop_xy[2 * v], y = m.loop_xy[2 * v + 1];
    not_whole += whole_points.count({x, y}) == 0;
    for (std::size_t w = 0; w < m.loop_vertex_count(); ++w) {
      const double u = m.loop_xy[2 * w], z = m.loop_xy[2 * w + 1];
      twins += (u != x || z != y) && std::abs(u - x) < 1e-12 && std::abs(z - y) < 1e-12;
    }
  }
  EXPECT_EQ(not_whole, 0u) << "re-cut loop vertices that are not the whole cut's, bit for bit";
  EXPECT_EQ(twins, 0u) << "loop vertices of the re-cut with another double for the same point";
  EXPECT_GT(map.region_triangles, 0u);
}

// A slot narrower than h with its end carried on (mesh.split_gap_ends, cover_cutter.cpp step 5):
// the re-cut gives the whole cut's covers round the slot, for a crack that runs up from the
// slot's end along its extension and for one beside it.
TEST(Recut, ASlotsGapEndIsCutAsTheWholeMeshWouldBe) {
  SceneDef s = reference::interface_scene(0.025, 30);
  BodyDef beam = reference::box(0, 0, 2.2, 0.2);
  beam.outer = {{0, 0}, {1.095, 0}, {1.095, 0.1}, {1.105, 0.1}, {1.105, 0}, {2.2, 0}, {2.2, 0.2}, {0, 0.2}};
  s.bodies = {beam};
  s.split_gap_ends = true;
  check_recut(s, {{1.1, 0.1}, {1.1, 0.14}}, "crack up from the slot's end, along its extension");
  check_recut(s, {{1.112, 0.104}, {1.13, 0.15}}, "crack beside the slot's end");
}

// pre::GrowingCut (cover_cutter.h), the re-cut check's full cut: a scene grown by batches of
// crack segments, each batch inserted into the arrangement kept from the last cut, gives at every
// growth the cut build_mesh gives of the whole scene (mesh_difference: the same elements, covers,
// blocks and contact edges; numbering and loop starts may differ). The batches cross mesh nodes,
// run along mesh edges, end inside elements (an island: a hole bridged in the copy, not in the
// kept arrangement), cross earlier segments and the older joint, and cut a small piece off.
namespace {
void grow_and_compare(pre::GrowingCut& g, SceneDef& s, const std::vector<std::vector<Vec2>>& batch, const char* what,
                      bool expect_growth = true) {
  for (const auto& seg : batch) s.joints.push_back({0, seg});
  const std::size_t grown = g.grown(), fresh = g.fresh();
  const Mesh m = g.cut(s, "grown");
  const Mesh whole = pre::build_mesh(s, "whole");
  EXPECT_EQ(g.grown(), grown + (expect_growth ? 1 : 0)) << what;
  EXPECT_EQ(g.fresh(), fresh + (expect_growth ? 0 : 1)) << what;
  EXPECT_EQ(m.element_count(), whole.element_count()) << what;
  EXPECT_EQ(m.cover_count(), whole.cover_count()) << what;
  EXPECT_EQ(m.block_count(), whole.block_count()) << what;
  EXPECT_EQ(mesh_difference(m, whole), "") << what;
  EXPECT_NEAR(total_area(m), total_area(whole), 1e-12 * total_area(whole)) << what;
  std::printf("%s: %zu joints, elements %zu, covers %zu, blocks %zu\n", what, s.joints.size(), m.element_count(),
              m.cover_count(), m.block_count());
}
}  // namespace

TEST(GrowingCut, EachCutIsTheWholeCutOfTheScene) {
  const double dy = 0.5 * std::sqrt(3.0) / 2;  // m, the lattice's row spacing at h = 0.5 m
  SceneDef s = two_bodies();
  pre::GrowingCut g;
  const Mesh first = g.cut(s, "first");
  EXPECT_EQ(g.fresh(), 1u);
  EXPECT_EQ(mesh_difference(first, pre::build_mesh(s, "whole")), "");
  // x = 1 passes the lattice nodes (1, 0) and (1, 2·dy); the second runs along the row y = 2·dy
  // through nodes (3.5, 4.0) and ends inside the mesh edge (4.0 … 4.5).
  grow_and_compare(g, s, {{{1.0, 0.2}, {1.0, 1.6}}, {{3.3, 2 * dy}, {4.4, 2 * dy}}}, "through nodes, along edges");
  const std::size_t elements_before_island = pre::build_mesh(s, "w").element_count();
  // Wholly inside one triangle (the face gets a hole, bridged), and one ending inside an element.
  grow_and_compare(g, s, {{{4.1, 0.3}, {4.2, 0.35}}, {{2.2, 0.1}, {2.45, 0.45}}}, "inside elements");
  EXPECT_GT(pre::build_mesh(s, "w").element_count(), elements_before_island);
  // Across the first batch's vertical segment and across the older joint, and two crossing each other.
  grow_and_compare(g, s, {{{0.7, 1.2}, {1.4, 1.0}}, {{1.6, 0.5}, {1.9, 1.4}}, {{1.55, 1.3}, {2.0, 0.6}}},
                   "across earlier segments");
  // A corner of the lower body cut off: a block of its own.
  const std::size_t blocks = pre::build_mesh(s, "w").block_count();
  grow_and_compare(g, s, {{{5.75, -0.05}, {6.05, 0.25}}}, "a corner cut off");
  EXPECT_EQ(pre::build_mesh(s, "w").block_count(), blocks + 1);
  // A tiny piece: a segment one micrometre beside the lattice node (2.5, 0) across the row.
  grow_and_compare(g, s, {{{2.45, -0.01}, {2.5 + 1e-6, 0.03}}, {{2.48, 0.02}, {2.56, -0.02}}}, "a small piece");
  // One more batch after all that, from the older joint's tip.
  grow_and_compare(g, s, {{{2.6, 1.3}, {3.4, 1.9}}, {{3.4, 1.9}, {3.5, 2.0}}}, "on from a tip up to the interface");

  // Not a growth: an earlier joint moved, one dropped, the mesh size changed — each cut from
  // nothing, still the whole cut; and the growth resumes from the scene cut last.
  SceneDef moved = s;
  moved.joints[2].points[1].x += 0.01;
  grow_and_compare(g, moved, {}, "an earlier segment moved", false);
  SceneDef dropped = moved;
  dropped.joints.pop_back();
  grow_and_compare(g, dropped, {}, "the last segment dropped (a step taken again)", false);
  grow_and_compare(g, dropped, {{{4.5, 3.1}, {4.9, 3.6}}}, "growing again after it");
  SceneDef finer = dropped;
  finer.mesh_size = 0.4;
  grow_and_compare(g, finer, {}, "another mesh size", false);
  SceneDef moved_body = finer;
  moved_body.bodies[1].outer[0].x += 0.1;
  grow_and_compare(g, moved_body, {}, "a body changed", false);
}

// A growth takes the joints' points as the sweep does: snapped onto a lattice row or node within
// round-off (Lattice::snap). The step-path slope at h 0.5 m (dynamic, fast, Prescott, the narrow
// contact reach; issue 48) grew a crack along the mesh row y = 13·dy from a point on it to one
// 5e-9 m past the node (14.25, 13·dy) and 1 ulp below the row. Snapped, the crack runs along the
// mesh edge and splits nothing there: the whole cut and the re-cut. Taken as typed (the growth,
// before), it dips below the row a round-off short of the node and cuts a three-sided sliver of
// 2.6e-18 m² off the triangle above, with a cover of its own: the re-cut check's full cut had one
// element more than the re-cut (4,091 against 4,090 at t 0.848 s) and stopped the run, although
// the re-cut was the cut of the scene.
TEST(GrowingCut, AGrowthSnapsACracksPointsOntoTheLatticeAsTheSweepDoes) {
  SceneDef s = reference::interface_scene(0.5, 30);
  s.bodies = {reference::box(11.0, 3.5, 17.5, 7.5)};
  const Lattice lat = make_lattice(s.bodies, s.mesh_size);
  const Vec2 node = lat.node(28, 13);  // (14.25, 13·dy): row 13 is shifted by h/2
  ASSERT_EQ(node.x, 14.25);
  const Vec2 a{14.244241029768277, node.y}, b{14.250000005, std::nextafter(node.y, 0.0)};
  ASSERT_NE(lat.snap(b).y, b.y) << "the end lies within round-off of the row";
  pre::GrowingCut g;
  const Mesh before = g.cut(s, "before");
  const std::size_t elements = before.element_count();
  grow_and_compare(g, s, {{a, b}}, "a crack along a mesh row, its end an ulp below it");
  EXPECT_EQ(pre::build_mesh(s, "whole").element_count(), elements) << "along a mesh edge, the crack splits no element";
  // The re-cut gives the same (it cuts its region with the sweep).
  check_recut([&] { SceneDef o = s; o.joints.pop_back(); return o; }(), {a, b}, "the same crack re-cut");
}

// A slot's gap end carried on (split_gap_ends): its extension depends on the bodies and the mesh
// only, so the kept arrangement keeps it; cracks up the extension and beside it grow the cut.
TEST(GrowingCut, ASlotsGapEndGrowsAsTheWholeCut) {
  SceneDef s = reference::interface_scene(0.025, 30);
  BodyDef beam = reference::box(0, 0, 2.2, 0.2);
  beam.outer = {{0, 0}, {1.095, 0}, {1.095, 0.1}, {1.105, 0.1}, {1.105, 0}, {2.2, 0}, {2.2, 0.2}, {0, 0.2}};
  s.bodies = {beam};
  s.split_gap_ends = true;
  pre::GrowingCut g;
  g.cut(s, "first");
  grow_and_compare(g, s, {{{1.1, 0.1}, {1.1, 0.14}}}, "up from the slot's end, along its extension");
  grow_and_compare(g, s, {{{1.112, 0.104}, {1.13, 0.15}}, {{1.1, 0.14}, {1.09, 0.19}}}, "beside the slot's end");
}

}  // namespace nmm
