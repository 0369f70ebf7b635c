// Contact detection's Verlet list (solver/contact/contact_detection.cpp, "Broad phase") is a cache: a
// call that reuses a list must find exactly the contacts a fresh search finds, on
// configurations that drift away from the one the list was built on until it no longer holds
// and is built anew. What it catches, measured: a list kept without ever being built anew
// (the upper bricks' vertices slide past the edges it holds) differs from the fresh search from
// the 88th configuration on.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <vector>

#include "tests/ended_ok.h"
#include "preprocess/cover_cutter.h"
#include "reference/brick_wall.h"
#include "solver/contact/contact_detection.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {
namespace {

// Each call's contacts from a fresh search and from the reused list, over `drifts`
// configurations of a 6 × 6 wall: between two, the bricks above the middle bed joint slide
// along it by `slip`·d0 (so their vertices pass the ends of the edges below and come to face
// edges they were far from when the list was built), and every loop vertex moves its own way by
// up to 0.02·d0 per coordinate (edges stretch and turn; faces open and sink into each other).
// Returns the list's builds.
std::size_t compare_along_a_drift(double mesh_size, double slip, int drifts) {
  const SceneDef s = reference::peer_wall(6, 6, false, mesh_size);
  const Mesh m = pre::build_mesh(s, "wall");
  TimeStepper st(m, s, "wall");
  EXPECT_PRED1(test::ended_ok, st.run_until(5e-3, [](std::int64_t) {}));
  const ContactTopology topo = build_contact_topology(m);
  const ClosedContacts closed = st.view().contacts.closed_contacts();
  EXPECT_FALSE(closed.pairs.empty()) << "the wall rests on closed contacts";
  // As time_stepper.cpp: search distance 2.5·g2·w0, new contacts at most 1e-3·h deep.
  const double d0 = 2.5 * s.solver.max_displacement_ratio * st.view().model.w0();
  const double shallow = 1e-3 * s.mesh_size;
  std::vector<double> xy = st.view().state.loop_xy;
  // Above the middle bed joint (y = 1.5 m): by the centre of the vertex's element.
  std::vector<double> cy(m.element_count(), 0.0), count(m.element_count(), 0.0);
  for (std::size_t v = 0; v < topo.element_of.size(); ++v) {
    cy[static_cast<std::size_t>(topo.element_of[v])] += xy[2 * v + 1];
    count[static_cast<std::size_t>(topo.element_of[v])] += 1;
  }
  std::vector<char> above(topo.element_of.size());
  for (std::size_t v = 0; v < above.size(); ++v) {
    const auto e = static_cast<std::size_t>(topo.element_of[v]);
    above[v] = cy[e] / count[e] > 1.5 ? 1 : 0;
  }
  std::mt19937 rng(20261125);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  CandidateList list;
  DetectionStats stats;
  std::size_t compared = 0;
  for (int k = 0; k < drifts; ++k) {
    const std::vector<ContactCandidate> fresh = detect_contacts(topo, xy, d0, shallow, closed);
    const std::vector<ContactCandidate> reused = detect_contacts(topo, xy, d0, shallow, closed, &stats, nullptr, &list);
    EXPECT_GT(fresh.size(), 0u);
    EXPECT_EQ(reused.size(), fresh.size()) << "configuration " << k;
    for (std::size_t c = 0; c < std::min(fresh.size(), reused.size()); ++c) {
      EXPECT_EQ(reused[c].vertex, fresh[c].vertex) << "configuration " << k << ", contact " << c;
      EXPECT_EQ(reused[c].edge, fresh[c].edge) << "configuration " << k << ", contact " << c;
      EXPECT_EQ(reused[c].gap, fresh[c].gap) << "configuration " << k << ", contact " << c;
      ++compared;
    }
    for (std::size_t v = 0; v < above.size(); ++v) {
      xy[2 * v] += (above[v] ? slip * d0 : 0.0) + 0.02 * d0 * u(rng);
      xy[2 * v + 1] += 0.02 * d0 * u(rng);
    }
  }
  std::printf("h = %.1f m: %zu contacts compared over %d configurations, list built %zu times\n", mesh_size,
              compared, drifts, stats.list_builds);
  return stats.list_builds;
}

TEST(ContactDetection, AReusedVerletListFindsWhatAFreshSearchFinds) {
  for (const double h : {0.5, 2.0}) {
    const std::size_t builds = compare_along_a_drift(h, 0.15, 150);
    EXPECT_GT(builds, 2u) << "the drift outgrew the list";
    EXPECT_LT(builds, 75u) << "the list was reused";
  }
}

// The closed pairs' per-vertex index answers as the binary search over the sorted pairs does.
TEST(ContactDetection, ClosedPairsIndexedByVertexAnswerAsTheirSearch) {
  const SceneDef s = reference::peer_wall(6, 6, false, 0.5);
  const Mesh m = pre::build_mesh(s, "wall");
  TimeStepper st(m, s, "wall");
  ASSERT_PRED1(test::ended_ok, st.run_until(5e-3, [](std::int64_t) {}));
  const ClosedContacts indexed = st.view().contacts.closed_contacts();
  ASSERT_FALSE(indexed.first.empty());
  ClosedContacts searched = indexed;
  searched.first.clear();
  const auto vertices = static_cast<std::int32_t>(indexed.first.size() - 1);
  std::size_t with_pairs = 0;
  for (std::int32_t v = 0; v < vertices; ++v) {
    ASSERT_EQ(indexed.range(v), searched.range(v)) << "vertex " << v;
    with_pairs += indexed.range(v).second > indexed.range(v).first;
    for (std::int32_t block = -1; block <= static_cast<std::int32_t>(m.block_count()); ++block)
      ASSERT_EQ(indexed.with(v, block), searched.with(v, block)) << "vertex " << v << ", block " << block;
  }
  EXPECT_GT(with_pairs, 100u) << "the wall rests on many closed vertices";
}

}  // namespace
}  // namespace nmm::solve
