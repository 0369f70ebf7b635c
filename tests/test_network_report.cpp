// nmm-inspect --network statistics and pictures (preprocess/network_report.h) against networks
// with known answers: hand-built parallel joints (spacing, P10, P21, lengths exact), a generated
// Poisson set (P21 within 5 %, P10 against the stereological expectation), generation clipped to
// a non-convex (L-shaped) region, block areas of a hand-built mesh, and the SVGs' contents.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <string>

#include "preprocess/joint_network.h"
#include "common/math_constants.h"
#include "preprocess/network_report.h"

namespace nmm::pre {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A 100 m × 50 m body; set "a": 9 persistent horizontal joints at y = 5, 10, ..., 45 (spacing
// 5 m); set "b": 5 joints at 35° of lengths 2, 4, 6, 8, 10 m.
SceneDef parallel_scene() {
  SceneDef s;
  s.name = "parallel";
  BodyDef b;
  b.material = 0;
  b.outer = {{0, 0}, {100, 0}, {100, 50}, {0, 50}};
  s.bodies.push_back(b);
  s.joint_sets.resize(2);
  s.joint_sets[0].name = "a";
  s.joint_sets[1].name = "b";
  for (int k = 1; k <= 9; ++k) s.joints.push_back({0, {{0, 5.0 * k}, {100, 5.0 * k}}});
  const double c = std::cos(35 * nmm::kPi / 180), sn = std::sin(35 * nmm::kPi / 180);
  for (int k = 1; k <= 5; ++k) {
    const Vec2 o{10.0 + 15 * k, 20};
    s.joints.push_back({1, {o, {o.x + 2.0 * k * c, o.y + 2.0 * k * sn}}});
  }
  return s;
}

TEST(NetworkReport, ParallelJointsHaveTheirKnownSpacingIntensityAndLengths) {
  const auto sets = joint_set_reports(parallel_scene());
  ASSERT_EQ(sets.size(), 2u);
  const auto& a = sets[0];
  EXPECT_FALSE(a.generated);
  EXPECT_DOUBLE_EQ(a.region_area, 5000.0);
  EXPECT_NEAR(a.measured_p21, 900.0 / 5000, 1e-12);
  EXPECT_NEAR(a.mean_angle_deg, 0.0, 1e-9);
  EXPECT_NEAR(a.resultant_length, 1.0, 1e-12);
  EXPECT_NEAR(a.scanline_angle_deg, 90.0, 1e-9);
  // 50 vertical scanlines of 50 m, each crossing the 9 joints: P10 = 9/50 = 1/spacing·(9/10).
  EXPECT_EQ(a.scanlines, 50);
  EXPECT_NEAR(a.scanline_length, 2500.0, 1e-9);
  EXPECT_EQ(a.crossings, 450u);
  EXPECT_NEAR(a.p10, 0.18, 1e-12);
  EXPECT_NEAR(a.p10_expected, 0.18, 1e-12);
  EXPECT_EQ(a.spacings, 400u);
  EXPECT_NEAR(a.mean_spacing, 5.0, 1e-9);
  EXPECT_EQ(a.trace_lengths.count, 9u);
  EXPECT_NEAR(a.trace_lengths.mean, 100.0, 1e-12);
  EXPECT_NEAR(a.trace_lengths.std_dev, 0.0, 1e-12);

  const auto& b = sets[1];
  EXPECT_NEAR(b.mean_angle_deg, 35.0, 1e-9);
  EXPECT_NEAR(b.trace_lengths.mean, 6.0, 1e-12);
  EXPECT_NEAR(b.trace_lengths.median, 6.0, 1e-12);
  EXPECT_NEAR(b.trace_lengths.min, 2.0, 1e-12);
  EXPECT_NEAR(b.trace_lengths.max, 10.0, 1e-12);
  EXPECT_NEAR(b.trace_lengths.std_dev, std::sqrt(10.0), 1e-12);
  EXPECT_NEAR(b.trace_lengths.total, 30.0, 1e-12);
  EXPECT_NEAR(b.measured_p21, 30.0 / 5000, 1e-12);
}

// A set typed by hand is measured in the rock itself: a 100 m × 50 m body with a 20 m × 10 m
// hole; one joint along y = 25 crosses the hole, so 80 m of it lie in 4800 m² of rock.
TEST(NetworkReport, HandTypedSetIsMeasuredInTheRockWithoutHoles) {
  SceneDef s;
  BodyDef b;
  b.material = 0;
  b.outer = {{0, 0}, {100, 0}, {100, 50}, {0, 50}};
  b.holes = {{{40, 20}, {60, 20}, {60, 30}, {40, 30}}};
  s.bodies.push_back(b);
  s.joint_sets.resize(1);
  s.joint_sets[0].name = "h";
  s.joints.push_back({0, {{0, 25}, {100, 25}}});
  const auto r = joint_set_reports(s).at(0);
  EXPECT_NEAR(r.region_area, 4800.0, 1e-9);
  EXPECT_NEAR(r.measured_p21, 80.0 / 4800, 1e-12);
  EXPECT_NEAR(r.trace_lengths.total, 100.0, 1e-12);  // the joint as typed
  // 50 vertical scanlines 2 m apart: the 10 with x in (40, 60) meet the hole, not the joint.
  EXPECT_EQ(r.crossings, 40u);
  EXPECT_NEAR(r.scanline_length, 50 * 50.0 - 10 * 10.0, 1e-9);
}

TEST(NetworkReport, GeneratedPoissonSetMeetsItsRequestedP21AndStereologicalP10) {
  GeneratedSetInput in;
  in.set = 0;
  in.def.mean_angle_deg = 35;
  in.def.dispersion = DispersionKind::von_mises;
  in.def.kappa = 10;
  in.def.p21 = 0.4;
  in.def.length = {LengthDistribution::exponential, 8.0, 0, 0, 0, 0};
  in.def.seed = 5;
  const Ring box = {{0, 0}, {200, 0}, {200, 200}, {0, 200}};
  const JointNetwork net = generate_joint_network({in}, box);
  SceneDef s;
  s.bodies.push_back({0, box, {}});
  s.joint_sets.resize(1);
  s.joint_sets[0].name = "j";
  s.joint_sets[0].expanded = true;
  s.joint_sets[0].generate = in.def;
  s.joints = net.joints;
  const auto r = joint_set_reports(s).at(0);
  EXPECT_TRUE(r.generated);
  EXPECT_DOUBLE_EQ(r.requested_p21, 0.4);
  EXPECT_NEAR(r.measured_p21 / 0.4, 1.0, 0.05);
  EXPECT_NEAR(r.mean_angle_deg, 35.0, 2.0);
  // P10 on scanlines normal to the set against P21·E|cos δ| (each of ~2 scanlines a joint meets
  // is a correlated count: sampling error ~3 %; a wrong definition is off by far more).
  EXPECT_NEAR(r.p10 / r.p10_expected, 1.0, 0.08);
  // Von Mises κ = 10 on 2θ: E|cos δ| ≈ 0.97, so P10 is close to P21 and not, e.g., P21·2/π.
  EXPECT_GT(r.p10_expected / r.measured_p21, 0.93);
  // Poisson traces: exponential lengths (mean 8 m) clipped by the box edges (shorter on average).
  EXPECT_NEAR(r.trace_lengths.mean, 8.0, 0.8);
  EXPECT_LT(r.trace_lengths.median, r.trace_lengths.mean);  // exponential: median = mean·ln 2
}

TEST(NetworkReport, NonConvexRegionClipsEveryJointAndKeepsItsP21) {
  // L-shaped region in a 200 m box: the square [100, 200]² is outside it.
  const Ring box = {{0, 0}, {200, 0}, {200, 200}, {0, 200}};
  GeneratedSetInput in;
  in.set = 0;
  in.def.region = {{0, 0}, {200, 0}, {200, 100}, {100, 100}, {100, 200}, {0, 200}};
  in.def.mean_angle_deg = 60;
  in.def.dispersion = DispersionKind::uniform;
  in.def.spread_deg = 30;
  in.def.p21 = 0.5;
  in.def.length = {LengthDistribution::lognormal, 10.0, 6.0, 0, 0, 0};
  in.def.seed = 9;
  const JointNetwork net = generate_joint_network({in}, box);
  ASSERT_GT(net.joints.size(), 1000u);
  for (const JointDef& j : net.joints)
    for (int k = 0; k <= 20; ++k) {  // no part of any joint in the notch or outside the box
      const double t = k / 20.0;
      const Vec2 p{j.points[0].x + t * (j.points[1].x - j.points[0].x),
                   j.points[0].y + t * (j.points[1].y - j.points[0].y)};
      ASSERT_FALSE(p.x > 100 + 1e-9 && p.y > 100 + 1e-9) << p.x << ", " << p.y;
      ASSERT_TRUE(p.x >= -1e-9 && p.x <= 200 + 1e-9 && p.y >= -1e-9 && p.y <= 200 + 1e-9);
    }
  EXPECT_NEAR(net.stats[0].region_area, 30000.0, 1e-6);
  EXPECT_NEAR(net.stats[0].clipped_length / 30000.0 / 0.5, 1.0, 0.05);
  // The inspector measures the same thing inside the same region.
  SceneDef s;
  s.bodies.push_back({0, box, {}});
  s.joint_sets.resize(1);
  s.joint_sets[0].name = "l";
  s.joint_sets[0].expanded = true;
  s.joint_sets[0].generate = in.def;
  s.joints = net.joints;
  const auto r = joint_set_reports(s).at(0);
  EXPECT_NEAR(r.region_area, 30000.0, 1e-6);
  EXPECT_NEAR(r.measured_p21, net.stats[0].clipped_length / 30000.0, 1e-9);
  // The re-entrant corner cuts joints into separate pieces, none bridging the notch.
  EXPECT_GT(net.stats[0].joints, 0);
}

// Termination through the uniform grid (joint_network.cpp, SegmentGrid): with probability 1 a
// later-set joint stops at its first crossing on each side, so no earlier-set joint may cross the
// inside of any later-set joint. Checked here against all pairs: a grid that missed a candidate
// joint would leave crossings.
TEST(NetworkReport, TerminationGridMissesNoCrossing) {
  const Ring box = {{0, 0}, {200, 0}, {200, 200}, {0, 200}};
  GeneratedSetInput a;
  a.set = 0;
  a.def.mean_angle_deg = 20;
  a.def.dispersion = DispersionKind::von_mises;
  a.def.kappa = 4;
  a.def.p21 = 0.3;
  a.def.length = {LengthDistribution::power_law, 0, 0, 2.5, 1.0, 60.0};  // a few long joints
  a.def.seed = 3;
  GeneratedSetInput b = a;
  b.set = 1;
  b.def.mean_angle_deg = 100;
  b.def.length = {LengthDistribution::exponential, 12.0, 0, 0, 0, 0};
  b.def.termination = 1;
  b.def.seed = 4;
  const JointNetwork net = generate_joint_network({a, b}, box);
  ASSERT_GT(net.stats[1].sides_with_intersection, 500);
  EXPECT_EQ(net.stats[1].sides_terminated, net.stats[1].sides_with_intersection);
  std::size_t checked = 0;
  for (const JointDef& jb : net.joints) {
    if (jb.set != 1) continue;
    const Vec2 p = jb.points[0], q = jb.points[1];
    const double len = std::hypot(q.x - p.x, q.y - p.y);
    for (const JointDef& ja : net.joints) {
      if (ja.set != 0) continue;
      const Vec2 c = ja.points[0], d = ja.points[1];
      const Vec2 r{q.x - p.x, q.y - p.y}, sv{d.x - c.x, d.y - c.y}, ca{c.x - p.x, c.y - p.y};
      const double den = r.x * sv.y - r.y * sv.x;
      if (den == 0) continue;
      const double t = (ca.x * sv.y - ca.y * sv.x) / den, u = (ca.x * r.y - ca.y * r.x) / den;
      if (u < 0 || u > 1) continue;
      const double margin = 1e-7 / std::max(len, 1e-9);
      ASSERT_FALSE(t > margin && t < 1 - margin)
          << "set-0 joint crosses a terminated set-1 joint at t = " << t;
      ++checked;
    }
  }
  EXPECT_GT(checked, 500u);  // the endpoints on earlier joints were seen
}

// Four elements in three blocks: areas 1 + 1 (block 0), 2 (block 1), 0.5 (block 2).
Mesh block_mesh() {
  Mesh m;
  auto add = [&](std::vector<Vec2> loop, int block) {
    m.element_triangle.push_back(0);
    m.element_body.push_back(0);
    m.element_block.push_back(block);
    if (m.element_loop_offset.empty()) m.element_loop_offset.push_back(0);
    for (const Vec2& p : loop) {
      m.loop_xy.push_back(p.x);
      m.loop_xy.push_back(p.y);
    }
    m.element_loop_offset.push_back(static_cast<std::int32_t>(m.loop_xy.size() / 2));
  };
  add({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 0);
  add({{1, 0}, {2, 0}, {2, 1}, {1, 1}}, 0);
  add({{0, 2}, {2, 2}, {2, 3}, {0, 3}}, 1);
  add({{5, 5}, {6, 5}, {5, 6}}, 2);
  m.block_body = {0, 0, 0};
  return m;
}

TEST(NetworkReport, BlockAreaDistributionOfAKnownMesh) {
  const NetworkReport rep = network_report(block_mesh(), parallel_scene());
  EXPECT_EQ(rep.blocks, 3u);
  ASSERT_EQ(rep.block_areas.size(), 3u);
  EXPECT_NEAR(rep.block_areas[0], 0.5, 1e-12);
  EXPECT_NEAR(rep.block_areas[1], 2.0, 1e-12);
  EXPECT_NEAR(rep.block_areas[2], 2.0, 1e-12);
  EXPECT_NEAR(rep.block_area_total, 4.5, 1e-12);
  EXPECT_NEAR(rep.block_area_mean, 1.5, 1e-12);
  EXPECT_NEAR(percentile(rep.block_areas, 0.25), 1.25, 1e-12);  // rank 0.5: halfway 0.5 → 2
  const auto j = network_report_json(rep);
  EXPECT_NEAR(j["blocks"]["area_percentiles"]["p50"].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(j["blocks"]["area_percentiles"]["p0"].get<double>(), 0.5, 1e-12);
  EXPECT_TRUE(j["joint_sets"][0]["requested_p21"].is_null());
  EXPECT_NEAR(j["joint_sets"][0]["mean_spacing"].get<double>(), 5.0, 1e-9);
  const std::string text = network_report_text(rep);
  EXPECT_NE(text.find("blocks: 3"), std::string::npos);
  EXPECT_NE(text.find("mean spacing 5 m"), std::string::npos);
}

TEST(NetworkReport, PicturesAreWellFormedAndShowWhatTheyClaim) {
  const SceneDef scene = parallel_scene();
  const NetworkReport rep = network_report(block_mesh(), scene);
  // Rose: per set a rim polygon and two wedges (one 10° bin, drawn at θ and θ + 180°).
  const std::string rose = rose_svg(rep);
  EXPECT_EQ(count(rose, "<polygon"), 6u);
  EXPECT_NE(rose.find("set a (9 segments, max bin 9)"), std::string::npos);
  EXPECT_NE(rose.find("set b (5 segments, max bin 5)"), std::string::npos);
  EXPECT_EQ(count(rose, "fill=\"" + set_colour(0) + "\""), 2u);
  EXPECT_EQ(count(rose, "fill=\"" + set_colour(1) + "\""), 2u);
  const std::string hist = trace_length_histogram_svg(rep);
  EXPECT_NE(hist.find("set a (9 joints)"), std::string::npos);
  EXPECT_NE(hist.find("set b (5 joints)"), std::string::npos);
  const std::string cdf = block_area_cdf_svg(rep);
  EXPECT_NE(cdf.find("3 blocks"), std::string::npos);
  const std::string net = network_svg(scene);
  EXPECT_NE(net.find("set a: 9 joints"), std::string::npos);
  EXPECT_NE(net.find("set b: 5 joints"), std::string::npos);
  EXPECT_EQ(count(net, "stroke=\"" + set_colour(0) + "\""), 1u);  // one <path> per set
  for (const std::string* svg : {&rose, &hist, &cdf, &net}) {
    EXPECT_EQ(svg->rfind("<svg", 0) == 0 || svg->find("<svg") != std::string::npos, true);
    EXPECT_NE(svg->find("</svg>"), std::string::npos);
    // Every opened element is closed (self-closing or with its end tag).
    const std::regex open("<([a-z]+)[ >]"), close("</([a-z]+)>");
    std::size_t opens = 0, closes = 0;
    for (std::sregex_iterator it(svg->begin(), svg->end(), open), e; it != e; ++it) ++opens;
    for (std::sregex_iterator it(svg->begin(), svg->end(), close), e; it != e; ++it) ++closes;
    EXPECT_EQ(opens, closes + count(*svg, "/>"));
  }
}

}  // namespace
}  // namespace nmm::pre
