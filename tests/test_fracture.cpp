// Intact rock that breaks (docs/fracture.md), checked against the strength it was given:
//   - a bar pulled apart cracks once its stress reaches the tensile strength (within 2 %), across
//     the bar, normal to σ1, and unloads;
//   - a specimen in uniaxial compression peaks at UCS = 2c·cosφ/(1 − sinφ) (within 5 %) and its
//     first crack runs on the Mohr–Coulomb plane, 45° + φ/2 from the minor principal stress;
//   - the peak does not depend on the step size (the step is solved again after each break);
//   - cutting a crack into a stressed mesh carries the state over: the displacement field and the
//     strain energy are the same before and after (no jump in energy.csv);
//   - a run restarted from a checkpoint written after cracks formed continues bit for bit;
//   - the Brazilian disc of data/brazilian_disc.json splits along its loaded diameter at a load
//     within 15 % of P = πDtσt/2 (7 % of it corrected for the loading flats);
//   - the step-path slope of data/step_path_slope.json slides once its rock bridges break, and
//     stands when they are ten times stronger;
//   - a scene without a fracture block does not crack, however far past the strength it is loaded;
//   - a run that can crack computes, while nothing cracks, bit for bit what the intact run does
//     (the step's start kept for taking it again and the strength checks touch no figure), with
//     and without crack tips to look ahead of; the strength screen passes every stress at or
//     beyond the strength on to the full check, and settles those a little inside it; a step
//     taken again starts from its start exactly;
//   - energy balances across cracking (energy.h): the tension bar's crack releases the strain
//     energy σt²·A·L/(2E) it held, booked in energy.csv's fracture column (within 2 %), the moving
//     support's load_work is its reaction times its travel (within 0.5 %), and the residual stays
//     under 1 % of the work done at every step, in the bar and in a notched beam in three-point
//     bending whose steps re-cut several times; the energy each cracking step books is what the
//     beam's stiffness lost at fixed grip (Clapeyron: ½ h²·Δk); the cut itself moves no energy
//     between columns;
//   - a crack that cuts a sliver off a single element (a block of one element under
//     kSliverArea·h²) makes it debris; a larger single-element piece, or a small piece of two
//     elements, stays rock.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "common/math_constants.h"
#include "common/scene.h"
#include "common/mesh_file.h"
#include "common/whole_file.h"
#include "preprocess/cover_cutter.h"
#include "preprocess/recut.h"
#include "reference/rock_tests.h"
#include "solver/contact/contact_effect.h"
#include "solver/fracture/crack_parting.h"
#include "solver/fracture/element_geometry.h"
#include "solver/fracture/fracture.h"
#include "solver/fracture/rock_strength.h"
#include "solver/fracture/state_transfer.h"
#include "solver/fracture/step_start.h"
#include "solver/fracture/tip_drive.h"
#include "solver/stepping/restart.h"
#include "solver/stepping/time_stepper.h"
#include "solver/output/solve_run.h"
#include "solver/output/energy.h"
#include "solver/discretisation/model.h"
#include "tests/csv_rows.h"
#include "tests/cut_crack.h"
#include "tests/ended_ok.h"
#include "tests/rock_stress.h"
#include "tests/temp_dir.h"

namespace nmm {
namespace {

using solve::CrackMode;
using solve::ContactHistory;
using solve::CrackSegment;
using solve::RunState;
using solve::TimeStepper;

// A w × h rectangle of rock (E 10 GPa, ν 0.2, plane stress, static) with the given strength,
// mesh size `size`; crack faces: constant springs, φ 30°. `axis` 0: its ends x = 0 and x = w are
// held in x and the end x = w moves at `speed` (m/s, + pulls); axis 1: the same along y.
nlohmann::json specimen(double w, double h, double size, int axis, double speed, const nlohmann::json& strength,
                        bool fracture = true) {
  nlohmann::json d;
  d["plane"] = "stress";
  d["materials"]["rock"] = {{"density", 2500}, {"young", 1e10}, {"poisson", 0.2}, {"strength", strength}};
  d["joint_sets"]["crack"] = {{"friction_deg", 30},
                              {"normal", {{"model", "constant"}, {"kn", 1e11}}},
                              {"shear", {{"model", "constant"}, {"ks", 4e10}}}};
  d["bodies"] = {{{"material", "rock"}, {"outer", {{0, 0}, {w, 0}, {w, h}, {0, h}}}}};
  if (fracture) d["fracture"] = {{"crack_set", "crack"}};
  d["mesh"]["size"] = size;
  const char* fix = axis == 0 ? "x" : "y";
  const nlohmann::json near = axis == 0 ? nlohmann::json{{0, 0}, {0, h}} : nlohmann::json{{0, 0}, {w, 0}};
  const nlohmann::json far = axis == 0 ? nlohmann::json{{w, 0}, {w, h}} : nlohmann::json{{0, h}, {w, h}};
  nlohmann::json v = axis == 0 ? nlohmann::json{speed, 0} : nlohmann::json{0, speed};
  d["supports"] = {{{"points", near}, {"fix", fix}}, {{"points", far}, {"fix", fix}, {"velocity", v}}};
  d["fixed_points"] = {axis == 0 ? nlohmann::json{0, h / 2} : nlohmann::json{w / 2, 0}};
  d["solver"] = {{"time_step", 1e-3}, {"steps", 1}, {"dynamic", false}};
  return d;
}

// Pa, the area-weighted mean of stress component k (0 σxx, 1 σyy) over the elements left in the
// model. In equilibrium without body force it is the end reaction per unit width: ∫σ dA = ∮ t⊗x ds.
double mean_stress(const TimeStepper& st, int k) {
  return test::rock_mean_stress(st.view(), k, &fracture_of(st.view()).debris());
}

struct LoadRun {
  Outcome status;
  double peak = 0;          // Pa, largest |mean stress| along the loading axis
  std::int64_t peak_step = 0;
  double last = 0;          // Pa, |mean stress| at the end
  std::vector<CrackSegment> segments;
};

LoadRun load(TimeStepper& st, int axis, double seconds) {
  LoadRun r;
  r.status = st.run_until(seconds, [&](std::int64_t n) {
    const double s = std::abs(mean_stress(st, axis));
    if (s > r.peak) r.peak = s, r.peak_step = n;
    r.last = s;
  });
  r.segments = fracture_of(st.view()).segments();
  return r;
}

double angle_deg(const CrackSegment& c) {  // of the segment's line, in [0°, 180°) from x
  double a = std::atan2(c.b.y - c.a.y, c.b.x - c.a.x) * 180 / kPi;
  if (a < 0) a += 180;
  if (a >= 180) a -= 180;
  return a;
}

}  // namespace

// σt 1 MPa, E 10 GPa: the bar's stress grows 2.5 kPa a step (1 mm/s over 4 m, Δt 1 ms), so the
// tension cut-off is reached at step 400. The crack forms where the stress first reaches it, runs
// across the bar normal to σ1 = σxx, and the bar unloads.
TEST(Fracture, BarInTensionCracksAcrossAtTheTensileStrength) {
  const double st_ = 1e6;
  const nlohmann::json strength = {{"tensile", st_}, {"cohesion", 4e6}, {"friction_deg", 35}};
  const SceneDef s = scene_from_json(specimen(4, 1, 0.25, 0, 1e-3, strength), "bar");
  const Mesh m = pre::build_mesh(s, "bar");
  TimeStepper st(m, s, "bar");
  const LoadRun r = load(st, 0, 0.6);
  double length = 0, worst = 0;
  for (const CrackSegment& c : r.segments) {
    length += std::hypot(c.b.x - c.a.x, c.b.y - c.a.y);
    worst = std::max(worst, std::abs(angle_deg(c) - 90));
  }
  std::printf("bar: peak %.5g Pa at step %lld (σt %.5g), end %.4g Pa; %zu segments, %.4f m of crack, "
              "furthest %.2f° from normal to σ1; %zu → %zu elements\n",
              r.peak, static_cast<long long>(r.peak_step), st_, r.last, r.segments.size(), length, worst,
              m.element_count(), st.view().mesh.element_count());
  ASSERT_PRED1(test::ended_ok, r.status);
  ASSERT_FALSE(r.segments.empty());
  EXPECT_NEAR(r.peak, st_, 0.02 * st_);
  EXPECT_LT(r.last, 0.02 * st_);  // cracked through: it carries nothing
  for (const CrackSegment& c : r.segments) EXPECT_EQ(c.mode, CrackMode::tensile);
  EXPECT_LT(worst, 5.0);
  EXPECT_NEAR(length, 1.0, 0.02);  // one crack across the 1 m bar
  EXPECT_EQ(fracture_of(st.view()).crack_count(), 1);
  EXPECT_GT(st.view().mesh.element_count(), m.element_count());
}

// The rock-bridge rule (docs/fracture.md rule 8, tip_drive.h) crosses holding rock only between
// joints: a crack is tied to a scene joint when one of its ends lies on the joint, or on a crack
// so tied, however long the chain; a crack whose ends lie in the rock is not. Here joint 0
// runs along y = 0 from x 0 to 4; crack 0 ends on it (within 1e-8 m: a stopping end is cut
// 1e-8·h past its edge), crack 1 ends on crack 0's far end, crack 2 on crack 1's middle, crack 3
// starts 0.3 m beyond crack 2's end, and crack 4 runs from 1 m beyond the joint's end, (5, 0), to
// joint 1, which stands for a crack segment's joint (only the first `scene_joints` are the scene's).
TEST(Fracture, ACrackIsTiedToAJointThroughItsEndsAndTheCracksItEndsOn) {
  std::vector<JointDef> joints(2);
  joints[0].points = {{0, 0}, {4, 0}};
  joints[1].points = {{0, 10}, {1, 10}};  // a crack segment's own joint: not a scene joint
  const std::vector<Vec2> a = {{1, 1e-8}, {1, 0.5}, {0.5, 0.75}, {0.5, 2.3}, {5, 0}};
  const std::vector<Vec2> b = {{1, 0.5}, {0, 1}, {0.5, 2}, {0.5, 2.6}, {0.5, 10}};
  const std::vector<std::int32_t> crack = {0, 1, 2, 3, 4};
  const std::vector<std::uint8_t> tied = solve::jointed_cracks(joints, 1, a, b, crack, 5, 1e-6);
  ASSERT_EQ(tied.size(), 5u);
  EXPECT_EQ(tied[0], 1);  // on the joint
  EXPECT_EQ(tied[1], 1);  // on crack 0's end
  EXPECT_EQ(tied[2], 1);  // on crack 1's face, at its middle (0.5, 0.75)
  EXPECT_EQ(tied[3], 0);  // 0.3 m off
  EXPECT_EQ(tied[4], 0);  // 1 m past the joint's end, and on a crack's joint only
  // A segment grown from a joint's own end (id −1) ties what ends on it.
  const std::vector<std::uint8_t> via =
      solve::jointed_cracks(joints, 1, {{7, 7}, {7, 8}}, {{7, 8}, {8, 8}}, {-1, 0}, 1, 1e-6);
  EXPECT_EQ(via[0], 1);
}

// The tie runs through chains of any length and in any order of the segments: a zigzag of 300
// cracks, numbered from its free end to the joint, ties each through the next (jointed_cracks
// finds the fixed point from each tied segment through a grid of the ends), while a crack beside
// each link, 2·tol off its end, stays free; and on random segments the set is that of the
// all-pairs fixed point, written out here.
TEST(Fracture, ATieRunsThroughAChainOfAnyOrderAsTheAllPairsFixedPoint) {
  std::vector<JointDef> joints(1);
  joints[0].points = {{0, 0}, {10, 0}};
  const double tol = 1e-6;
  const int links = 300;
  std::vector<Vec2> a, b;
  std::vector<std::int32_t> crack;
  for (int k = 0; k < links; ++k) {  // link k from height k·0.1 to (k + 1)·0.1; its id counts down
    const double x0 = (k % 2) ? 1.0 : 1.05, x1 = (k % 2) ? 1.05 : 1.0;
    a.push_back({x0, k * 0.1});
    b.push_back({x1, (k + 1) * 0.1});
    crack.push_back(links - 1 - k);
  }
  for (int k = 1; k < links; ++k) {  // a free crack starting 2·tol beside each link's start
    a.push_back({a[static_cast<std::size_t>(k)].x + 2 * tol, a[static_cast<std::size_t>(k)].y});
    b.push_back({a[static_cast<std::size_t>(k)].x + 0.07, a[static_cast<std::size_t>(k)].y + 0.05});
    crack.push_back(links - 1 + k);
  }
  const int cracks = 2 * links - 1;
  const std::vector<std::uint8_t> tied = solve::jointed_cracks(joints, 1, a, b, crack, cracks, tol);
  ASSERT_EQ(tied.size(), static_cast<std::size_t>(cracks));
  for (int c = 0; c < links; ++c) EXPECT_EQ(tied[static_cast<std::size_t>(c)], 1) << "link " << c;
  for (int c = links; c < cracks; ++c) EXPECT_EQ(tied[static_cast<std::size_t>(c)], 0) << "beside " << c;

  // Random short segments, some sharing ends, several per crack, against the all-pairs passes.
  auto to_segment = [](const Vec2& p, const Vec2& s, const Vec2& e) {
    const double dx = e.x - s.x, dy = e.y - s.y, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((p.x - s.x) * dx + (p.y - s.y) * dy) / l2, 0.0, 1.0) : 0.0;
    return std::hypot(s.x + t * dx - p.x, s.y + t * dy - p.y);
  };
  std::uint64_t seed = 12345;
  auto uniform = [&]() {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) / 9007199254740992.0;
  };
  for (int trial = 0; trial < 5; ++trial) {
    const int n = 400, ids = 120;
    std::vector<Vec2> ra, rb;
    std::vector<std::int32_t> rc;
    for (int i = 0; i < n; ++i) {
      const Vec2 p = i > 0 && uniform() < 0.5 ? rb[static_cast<std::size_t>(uniform() * i)]
                                              : Vec2{10 * uniform(), 10 * uniform() - 0.2};
      ra.push_back(p);
      rb.push_back({p.x + 0.6 * (uniform() - 0.5), p.y + 0.6 * (uniform() - 0.5)});
      rc.push_back(uniform() < 0.05 ? -1 : static_cast<std::int32_t>(uniform() * ids));
    }
    std::vector<std::uint8_t> want(ids, 0);
    auto is_tied = [&](std::int32_t c) { return c < 0 || want[static_cast<std::size_t>(c)] != 0; };
    for (int i = 0; i < n; ++i)
      if (rc[static_cast<std::size_t>(i)] >= 0 && (to_segment(ra[static_cast<std::size_t>(i)], {0, 0}, {10, 0}) <= 0.01 ||
                                                   to_segment(rb[static_cast<std::size_t>(i)], {0, 0}, {10, 0}) <= 0.01))
        want[static_cast<std::size_t>(rc[static_cast<std::size_t>(i)])] = 1;
    for (bool more = true; more;) {
      more = false;
      for (std::size_t i = 0; i < ra.size(); ++i)
        for (std::size_t k = 0; k < ra.size() && !is_tied(rc[i]); ++k)
          if (is_tied(rc[k]) && (to_segment(ra[i], ra[k], rb[k]) <= 0.01 || to_segment(rb[i], ra[k], rb[k]) <= 0.01))
            want[static_cast<std::size_t>(rc[i])] = 1, more = true;
    }
    const std::vector<std::uint8_t> got = solve::jointed_cracks(joints, 1, ra, rb, rc, ids, 0.01);
    int tied_count = 0;
    for (const std::uint8_t w : want) tied_count += w;
    EXPECT_GT(tied_count, 5) << "trial " << trial;  // the chains reach some cracks …
    EXPECT_LT(tied_count, ids) << "trial " << trial;  // … not all
    EXPECT_EQ(got, want) << "trial " << trial;
  }
}

// Rule 4 of fracture.h tells a crack that has not parted its element (crack_parting.h) by the
// covers of the pieces across it: at cover order 0 the jump across a crack is Σ_k λ_k·(u_k⁺ − u_k⁻),
// with no term for a node whose star the crack did not run right across. A crack 0.1 m long in
// the 4 m bar (h 0.25 m: a star reaches h from its node) crosses no star: the pieces either side
// keep all three covers. A crack right across the bar, from boundary to boundary, crosses every
// star it enters: no piece shares a cover with the piece across.
TEST(Fracture, ACrackShorterThanAStarHasNotPartedItsElements) {
  const nlohmann::json strength = {{"tensile", 1e6}, {"cohesion", 4e6}, {"friction_deg", 35}};
  for (const bool across : {false, true}) {
    nlohmann::json doc = specimen(4, 1, 0.25, 0, 1e-3, strength);
    const nlohmann::json points = across ? nlohmann::json{{2.01, -0.1}, {2.01, 1.1}} : nlohmann::json{{2.01, 0.45}, {2.01, 0.55}};
    doc["joints"] = {{{"set", "crack"}, {"points", points}}};
    const SceneDef s = scene_from_json(doc, "bar");
    const Mesh m = pre::build_mesh(s, "bar");
    const solve::TriangleElements pieces(m);
    int cracked = 0, sharing = 0;
    for (std::size_t e = 0; e < m.element_count(); ++e) {
      bool on_crack = false;
      for (std::int32_t v = m.element_loop_offset[e]; v < m.element_loop_offset[e + 1]; ++v)
        on_crack = on_crack || m.loop_edge_joint[static_cast<std::size_t>(v)] == 0;
      if (!on_crack) continue;
      ++cracked;
      sharing += pieces.shares_a_cover(m, e, 0) ? 1 : 0;
    }
    std::printf("%s crack: %d elements on it, %d share a cover with the piece across\n", across ? "across" : "short",
                cracked, sharing);
    EXPECT_GE(cracked, across ? 8 : 2);
    EXPECT_EQ(sharing, across ? 0 : cracked);
  }
}

// c 2 MPa, φ 30°: UCS = 2c·cosφ/(1 − sinφ) = 6.93 MPa, reached at step 1386 (1 mm/s over 2 m).
// The tension cut-off is out of reach (100 MPa), so every segment is shear, and the first runs on
// a Mohr–Coulomb plane: 45° + φ/2 = 60° from the minor principal stress σxx.
TEST(Fracture, UniaxialCompressionPeaksAtTheUcsOnTheCriticalPlane) {
  const double c = 2e6, phi = 30 * kPi / 180;
  const double ucs = 2 * c * std::cos(phi) / (1 - std::sin(phi));
  const nlohmann::json strength = {{"tensile", 1e8}, {"cohesion", c}, {"friction_deg", 30}};
  const SceneDef s = scene_from_json(specimen(1, 2, 0.125, 1, -1e-3, strength), "ucs");
  const Mesh m = pre::build_mesh(s, "ucs");
  TimeStepper st(m, s, "ucs");
  const LoadRun r = load(st, 1, 1.8);
  ASSERT_FALSE(r.segments.empty());
  const CrackSegment& first = r.segments.front();
  const double a = angle_deg(first);
  std::printf("ucs: peak %.5g Pa at step %lld (UCS %.5g, %+.2f %%), end %.4g Pa; %zu segments in %d cracks, "
              "first at step %lld at %.2f° from x (60° or 120° expected)\n",
              r.peak, static_cast<long long>(r.peak_step), ucs, 100 * (r.peak / ucs - 1), r.last,
              r.segments.size(), fracture_of(st.view()).crack_count(), static_cast<long long>(first.step), a);
  ASSERT_PRED1(test::ended_ok, r.status);
  EXPECT_NEAR(r.peak, ucs, 0.05 * ucs);
  for (const CrackSegment& k : r.segments) EXPECT_EQ(k.mode, CrackMode::shear);
  EXPECT_NEAR(std::min(std::abs(a - 60), std::abs(a - 120)), 0.0, 3.0);
  EXPECT_LT(r.last, 0.9 * r.peak);  // it lost strength where it cracked
}

// data/brazilian_disc.json: D = 1 m, σt = 5 MPa, squeezed between two smooth flats (held in y
// only, a fixed point at the bottom) of 2α = 20° of arc, 2R·cosα = 0.985 m apart. The load per
// metre is P = A·mean σyy / H (∫σyy dA = P·H in equilibrium). The standard formula, for a line
// load, splits it at P = πDtσt/2 = 7.85 MN/m; a load spread over 2α (Hondros 1959) lowers the
// centre's tension to 2P/(πDt)·(sin2α − α)/sinα = 0.965 of it, so P = 8.14 MN/m. Measured with
// h = 0.05 m (D/h = 20): 8.57 MN/m, +9.1 % and +5.3 %; the centre's element stress before it
// cracks is 0.916 of the line-load value (0.909 at h = 0.1 m): constant-strain elements.
TEST(Fracture, BrazilianDiscSplitsAtItsTensileStrength) {
  const std::string path = std::string(NMM_SOURCE_DIR) + "/data/brazilian_disc.json";
  const SceneDef s = parse_scene(read_text_file(path), path);
  const Mesh m = pre::build_mesh(s, path);
  TimeStepper st(m, s, path);
  const double D = 1, H = 2 * 0.5 * std::cos(10 * kPi / 180), sigma_t = 5e6;
  const double expected = kPi * D * sigma_t / 2;
  const double area = total_area(m);
  double peak = 0;
  std::int64_t peak_step = 0;
  const Outcome o = st.run_until(1.1, [&](std::int64_t n) {
    const double P = area * std::abs(mean_stress(st, 1)) / H;
    if (P > peak) peak = P, peak_step = n;
  });
  ASSERT_PRED1(test::ended_ok, o);
  const std::vector<CrackSegment>& cracks = fracture_of(st.view()).segments();
  ASSERT_FALSE(cracks.empty());
  const CrackSegment& first = cracks.front();
  const Vec2 mid{0.5 * (first.a.x + first.b.x), 0.5 * (first.a.y + first.b.y)};
  std::printf("Brazilian disc: peak P %.4g N/m at step %lld (πDσt/2 = %.4g, %+.2f %%); first crack at step %lld "
              "at (%.3f, %.3f), %.2f° from x; %zu segments\n",
              peak, static_cast<long long>(peak_step), expected, 100 * (peak / expected - 1),
              static_cast<long long>(first.step), mid.x, mid.y, angle_deg(first), cracks.size());
  const double alpha = 10 * kPi / 180;
  const double hondros = expected * std::sin(alpha) / (std::sin(2 * alpha) - alpha);
  std::printf("with the flats' correction (Hondros): %.4g N/m, %+.2f %%\n", hondros, 100 * (peak / hondros - 1));
  EXPECT_NEAR(peak, expected, 0.15 * expected);
  EXPECT_NEAR(peak, hondros, 0.07 * hondros);
  EXPECT_EQ(first.mode, CrackMode::tensile);
  EXPECT_NEAR(angle_deg(first), 90, 2);
  EXPECT_LT(std::hypot(mid.x - 0.5, mid.y - 0.5), 0.1);  // at the centre
}

// data/step_path_slope.json: friction alone (15° on joints dipping 45°) cannot hold the wedge;
// the rock bridges between the stepped joints do until they break. As given (σt 100 kPa, c
// 300 kPa) they crack in the first steps and the wedge slides; ten times stronger they hold and
// the slope stands: what holds it is the intact rock, and what lets it go is the rock breaking.
TEST(Fracture, RockBridgesBreakIntoAStepPathOnlyWhenWeakEnough) {
  const std::string path = std::string(NMM_SOURCE_DIR) + "/data/step_path_slope.json";
  double moved[2] = {0, 0};
  std::size_t segments[2] = {0, 0};
  for (int strong = 0; strong < 2; ++strong) {
    SceneDef s = parse_scene(read_text_file(path), path);
    if (strong) {
      s.materials[0].strength.tensile *= 10;
      s.materials[0].strength.cohesion *= 10;
    }
    const Mesh m = pre::build_mesh(s, path);
    TimeStepper st(m, s, path);
    ASSERT_PRED1(test::ended_ok, st.run_until(1.0, [](std::int64_t) {}));
    const auto u = st.view().state.measure[0].displacement();
    moved[strong] = std::hypot(u[0], u[1]);
    segments[strong] = fracture_of(st.view()).segments().size();
  }
  std::printf("step-path slope after 1 s: wedge moved %.4g m with %zu crack segments; %.4g m with %zu when the "
              "rock is ten times stronger\n", moved[0], segments[0], moved[1], segments[1]);
  EXPECT_GT(moved[0], 0.015);
  EXPECT_GE(segments[0], 10u);
  EXPECT_LT(moved[1], 1e-3);
}

// The rule "solve the step again until its solution breaks nothing more" makes the peak a
// function of the load, not of how it is cut into steps: the compression specimen (h 0.25 m)
// loaded in steps of 0.5, 1, 2 and 4 µm of platen travel peaks at the same stress (measured
// within 0.2 %). After the peak every run has lost strength, but how much differs (1.6 to 3.3 MPa
// at 1.6 mm): without cohesive softening a brittle crack pattern is not unique.
TEST(Fracture, TheLoadDisplacementCurveDoesNotDependOnTheStepSize) {
  const nlohmann::json strength = {{"tensile", 1e8}, {"cohesion", 2e6}, {"friction_deg", 30}};
  std::vector<double> peak, after;
  const double dts[] = {0.5e-3, 1e-3, 2e-3, 4e-3};
  for (const double dt : dts) {
    nlohmann::json doc = specimen(1, 2, 0.25, 1, -1e-3, strength);
    doc["solver"]["time_step"] = dt;
    const SceneDef s = scene_from_json(doc, "ucs");
    const Mesh m = pre::build_mesh(s, "ucs");
    TimeStepper st(m, s, "ucs");
    const LoadRun r = load(st, 1, 1.6);  // 1.6 mm of travel: 0.2 mm past the peak
    ASSERT_PRED1(test::ended_ok, r.status);
    peak.push_back(r.peak);
    after.push_back(r.last);
  }
  for (std::size_t i = 0; i < peak.size(); ++i)
    std::printf("step %.1f µm of travel: peak %.5g Pa, at 1.6 mm %.5g Pa\n", dts[i] * 1e3 * 1e3 / 1e3, peak[i],
                after[i]);
  for (std::size_t i = 0; i < peak.size(); ++i) {
    EXPECT_NEAR(peak[i], peak[0], 0.01 * peak[0]);
    EXPECT_LT(after[i], 0.6 * peak[i]);
  }
}

// Without a fracture block the same specimen is elastic to the end: 9 MPa, 30 % past its UCS.
TEST(Fracture, NothingBreaksWithoutAFractureBlock) {
  const nlohmann::json strength = {{"tensile", 1e8}, {"cohesion", 2e6}, {"friction_deg", 30}};
  const SceneDef s = scene_from_json(specimen(1, 2, 0.25, 1, -1e-3, strength, false), "ucs");
  const Mesh m = pre::build_mesh(s, "ucs");
  TimeStepper st(m, s, "ucs");
  const LoadRun r = load(st, 1, 1.8);
  ASSERT_PRED1(test::ended_ok, r.status);
  EXPECT_FALSE(fracture_of(st.view()).active());
  EXPECT_TRUE(r.segments.empty());
  EXPECT_NEAR(r.last, 1e10 * 1.8e-3 / 2, 0.01 * 9e6);
  EXPECT_EQ(st.view().mesh.element_count(), m.element_count());
}

// While nothing cracks, a run that can crack is the intact run: the same state bit for bit after
// every step (state hashes equal), in a bar without joints (no tips, no contacts) and in one with
// an edge notch (a joint whose tip the rule looks ahead of after every step, contacts on its
// faces: the contact history is kept with the state). σt 1 MPa; the bar's nominal stress reaches
// 0.2 MPa by the end, the notch tip's elements stay below σt (checked: no segment).
TEST(Fracture, AQuietStepIsTheIntactStepBitForBit) {
  const nlohmann::json strength = {{"tensile", 1e6}, {"cohesion", 4e6}, {"friction_deg", 35}};
  for (const bool notch : {false, true}) {
    nlohmann::json can = specimen(4, 1, 0.125, 0, 1e-3, strength), intact = specimen(4, 1, 0.125, 0, 1e-3, strength, false);
    if (notch)
      for (nlohmann::json* d : {&can, &intact}) (*d)["joints"] = {{{"set", "crack"}, {"points", {{2, 1}, {2, 0.8}}}}};
    const SceneDef sc = scene_from_json(can, "bar"), si = scene_from_json(intact, "bar");
    const Mesh mc = pre::build_mesh(sc, "bar"), mi = pre::build_mesh(si, "bar");
    TimeStepper a(mc, sc, "bar"), b(mi, si, "bar");
    ASSERT_TRUE(fracture_of(a.view()).active());
    ASSERT_FALSE(fracture_of(b.view()).active());
    for (int k = 0; k < 80; ++k) {
      ASSERT_PRED1(test::ended_ok, a.attempt(1e-3));
      ASSERT_PRED1(test::ended_ok, b.attempt(1e-3));
      ASSERT_EQ(solve::state_hash(a.view()), solve::state_hash(b.view())) << "notch " << notch << ", step " << k + 1;
    }
    EXPECT_TRUE(fracture_of(a.view()).segments().empty()) << "notch " << notch << ": not a quiet run";
    EXPECT_NEAR(mean_stress(a, 0), 1e10 * 80e-6 / 4, 0.05 * 2e5) << "notch " << notch;
    EXPECT_EQ(b.view().contacts.active(), notch);
  }
}

// The screen before the full strength check (rock_strength.h) may only settle stresses whose
// ratio is below 1: on stresses scaled onto the strength surface (bisected to the last double
// inside and the first at or beyond), in tension, compression and shear, for strong and weak
// friction, every stress at or beyond 1 goes on to rock_failure, and every stress 1e-6 inside is
// settled by the screen (a screen settling nothing would be safe and useless; one with a wrong
// Nφ or UCS settles stresses beyond the surface and fails here).
TEST(Fracture, TheStrengthScreenPassesOnEveryStressAtOrBeyondTheStrength) {
  std::mt19937_64 rng(49);
  std::uniform_real_distribution<double> unit(-1, 1);
  int beyond = 0, inside = 0;
  for (const double phi : {0.0, 30.0, 55.0})
    for (const double tensile : {1e4, 5e6, 1e9}) {
      StrengthDef st;
      st.present = true;
      st.tensile = tensile;
      st.cohesion = 12e6;
      st.friction_deg = phi;
      const solve::StrengthScreen screen(st);
      for (int i = 0; i < 2000; ++i) {
        const double sxx = unit(rng), syy = unit(rng), sxy = unit(rng);
        auto ratio = [&](double l) { return solve::rock_failure(st, l * sxx, l * syy, l * sxy).ratio; };
        // The ratio is homogeneous of degree 1 in the stress: a direction whose ratio is not
        // positive never reaches the strength (compression that Mohr–Coulomb holds at any size).
        if (!(ratio(1) > 0)) continue;
        double lo = 0, hi = 2 / ratio(1);
        for (int k = 0; k < 200 && std::nextafter(lo, hi) < hi; ++k) {
          const double mid = 0.5 * (lo + hi);
          (ratio(mid) < 1 ? lo : hi) = mid;
        }
        ASSERT_GE(ratio(hi), 1);
        ASSERT_LT(ratio(lo), 1);
        for (const double l : {hi, hi * (1 + 1e-15), 2 * hi}) {
          ASSERT_FALSE(screen.surely_holds(l * sxx, l * syy, l * sxy))
              << "φ " << phi << ", σt " << tensile << ": ratio " << ratio(l) << " settled by the screen";
          ++beyond;
        }
        EXPECT_TRUE(screen.surely_holds(lo * (1 - 1e-6) * sxx, lo * (1 - 1e-6) * syy, lo * (1 - 1e-6) * sxy))
            << "φ " << phi << ", σt " << tensile << ": ratio " << ratio(lo * (1 - 1e-6)) << " not settled";
        ++inside;
      }
    }
  EXPECT_FALSE(solve::StrengthScreen(StrengthDef{}).surely_holds(0, 0, 0));  // no strength: never settled
  StrengthDef st{};
  st.present = true;
  st.tensile = 5e6;
  st.cohesion = 12e6;
  st.friction_deg = 35;
  EXPECT_FALSE(solve::StrengthScreen(st).surely_holds(std::nan(""), 0, 0));
  EXPECT_FALSE(solve::StrengthScreen(st).surely_holds(1e308, -1e308, 1e308));
  std::printf("%d stresses at or beyond the strength passed on, %d just inside settled\n", beyond, inside);
}

// A step taken again starts from its start exactly: the state and contact history kept before
// the step come back bit for bit (state hash), with the diagnostics of the solve that broke the
// rock; and a second step keeps its own start in the same buffers.
TEST(Fracture, TakingAStepAgainRestoresItsStartExactly) {
  const nlohmann::json strength = {{"tensile", 1e6}, {"cohesion", 4e6}, {"friction_deg", 35}};
  const SceneDef s = scene_from_json(specimen(4, 1, 0.25, 0, 1e-3, strength), "bar");
  const Mesh m = pre::build_mesh(s, "bar");
  TimeStepper st(m, s, "bar");
  for (int k = 0; k < 3; ++k) ASSERT_PRED1(test::ended_ok, st.attempt(1e-3));
  solve::StepStart start;
  for (int round = 0; round < 2; ++round) {
    RunState s0 = st.view().state;
    std::vector<ContactHistory> h0(2);
    h0[1].vertex = 7 + round, h0[1].shear_el = 1e-5 * (round + 1);
    const std::string hash0 = solve::state_hash(s0, "", m);
    start.keep(s0, h0);
    // The step's solution: moved on, with more of everything, and its diagnostics.
    RunState s1 = s0;
    for (double& u : s1.cover_u) u += 1e-4;
    s1.stress.push_back(1);
    s1.time += 1e-3;
    ++s1.step;
    s1.iterations = s0.iterations + 5;
    s1.cuts = s0.cuts + 2;
    s1.max_penetration = 3e-4;
    ASSERT_NE(solve::state_hash(RunState(s1), "", m), hash0);
    start.restore(s1);
    EXPECT_EQ(solve::state_hash(s1, "", m), hash0) << "round " << round;
    EXPECT_EQ(s1.iterations, s0.iterations + 5);
    EXPECT_EQ(s1.cuts, s0.cuts + 2);
    EXPECT_EQ(s1.max_penetration, 3e-4);
    const std::vector<ContactHistory>& h1 = start.history();
    ASSERT_EQ(h1.size(), 2u);
    EXPECT_EQ(h1[1].vertex, 7 + round);
    EXPECT_EQ(h1[1].shear_el, 1e-5 * (round + 1));
  }
}

namespace {
// m, the displacement field of element e of `m` (cover order 0: Σ_k λ_k(p)·u_k over its
// triangle's nodes) at p, as cut.
std::array<double, 2> field(const Mesh& m, const std::vector<double>& cover_u, std::size_t e, Vec2 p) {
  const std::int32_t t = m.element_triangle[e];
  Vec2 n[3];
  for (int k = 0; k < 3; ++k) {
    const std::size_t i = static_cast<std::size_t>(m.triangle_nodes[3 * static_cast<std::size_t>(t) + k]);
    n[k] = {m.node_xy[2 * i], m.node_xy[2 * i + 1]};
  }
  const double area2 = (n[1].x - n[0].x) * (n[2].y - n[0].y) - (n[2].x - n[0].x) * (n[1].y - n[0].y);
  std::array<double, 2> u{0, 0};
  for (int k = 0; k < 3; ++k) {
    const Vec2 b = n[(k + 1) % 3], c = n[(k + 2) % 3];
    const double l = ((b.x - p.x) * (c.y - p.y) - (c.x - p.x) * (b.y - p.y)) / area2;
    const std::size_t pc = static_cast<std::size_t>(m.element_covers[3 * e + static_cast<std::size_t>(k)]);
    u[0] += l * cover_u[2 * pc];
    u[1] += l * cover_u[2 * pc + 1];
  }
  return u;
}

// J/m, ½ Σ_e A_e σ_eᵀ D⁻¹ σ_e in plane stress (E, ν).
double strain_energy(const Mesh& m, const std::vector<double>& stress, double E, double nu) {
  double U = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    const double sx = stress[3 * e], sy = stress[3 * e + 1], txy = stress[3 * e + 2];
    const double w = (sx * sx + sy * sy - 2 * nu * sx * sy + 2 * (1 + nu) * txy * txy) / E;
    U += 0.5 * element_area(m, e) * w;
  }
  return U;
}
// The bar of BarInTensionCracksAcross… loaded to 75 % of its strength (0.3 s), and the same state
// carried onto the mesh with a crack cut across it, through elements and nodes' stars.
// The bar at 75 % of its strength, cut across through elements and nodes' stars.
test::CutCrack cut_stressed_bar() {
  const nlohmann::json strength = {{"tensile", 1e6}, {"cohesion", 4e6}, {"friction_deg", 35}};
  test::CutCrack c = test::cut_crack(scene_from_json(specimen(4, 1, 0.25, 0, 1e-3, strength), "bar"), "bar", 0.3,
                                     {Vec2{2.03, -0.01}, Vec2{2.11, 1.01}}, 2);
  EXPECT_PRED1(test::ended_ok, c.outcome);
  return c;
}
}  // namespace

// A crack cut across the bar at 75 % of its strength, through elements and nodes' stars: every
// loop vertex of the new mesh moves as the field of the element it came from moved it (the crack's
// own vertices included), and the strain energy is the same to round-off.
TEST(Fracture, CuttingACrackCarriesTheStateOver) {
  const test::CutCrack c = cut_stressed_bar();
  ASSERT_FALSE(c.cracked_in_run);
  const Mesh &m = c.before_mesh, &now = c.now;
  const pre::RecutMap& map = c.map;
  const RunState &before = c.before, &after = c.after;
  ASSERT_GT(now.element_count(), m.element_count());

  double worst = 0, scale = 0;
  for (std::size_t e = 0; e < now.element_count(); ++e) {
    const std::size_t parent = static_cast<std::size_t>(map.element_parent[e]);
    for (std::int32_t v = now.element_loop_offset[e]; v < now.element_loop_offset[e + 1]; ++v) {
      const Vec2 p{now.loop_xy[2 * v], now.loop_xy[2 * v + 1]};
      const auto was = field(m, before.cover_u, parent, p);   // the old element's field there
      const auto is = field(now, after.cover_u, e, p);        // the new element's
      const std::size_t i = static_cast<std::size_t>(v);
      for (int k = 0; k < 2; ++k) {
        worst = std::max({worst, std::abs(is[k] - was[k]), std::abs(after.loop_u[2 * i + k] - was[k])});
        scale = std::max(scale, std::abs(was[k]));
      }
    }
  }
  const double U0 = strain_energy(m, before.stress, 1e10, 0.2), U1 = strain_energy(now, after.stress, 1e10, 0.2);
  std::printf("insertion: %zu → %zu elements; displacement differs by at most %.3g m (of %.3g m); strain "
              "energy %.10g → %.10g J/m\n", m.element_count(), now.element_count(), worst, scale, U0, U1);
  EXPECT_GT(scale, 1e-4);
  EXPECT_LT(worst, 1e-12 * scale * 1e3);
  EXPECT_NEAR(U1, U0, 1e-12 * U0);
  EXPECT_GT(U0, 0.5 * 0.75e6 * 0.75e6 / 1e10 * 4 * 0.9);  // the bar is loaded: ½σ²/E·V
}

// A run restarted from a checkpoint written after its first cracks (MESH and FRACTURE sections)
// continues bit for bit as the run that went straight on — cracks, mesh and state.
TEST(Fracture, RestartMidCrackingContinuesBitForBit) {
  const nlohmann::json strength = {{"tensile", 1e8}, {"cohesion", 2e6}, {"friction_deg", 30}};
  const nlohmann::json doc = specimen(1, 2, 0.25, 1, -1e-3, strength);
  const SceneDef s = scene_from_json(doc, "ucs");
  Mesh m = pre::build_mesh(s, "ucs");
  m.scene_text = doc.dump();  // as nmm-preprocess records it: the checkpoint's MESH section checks it
  m.scene_sha256 = sha256(m.scene_text);
  TimeStepper straight(m, s, "ucs"), first(m, s, "ucs"), second(m, s, "ucs");
  ASSERT_PRED1(test::ended_ok, straight.run_until(1.5, [](std::int64_t) {}));
  ASSERT_PRED1(test::ended_ok, first.run_until(1.42, [](std::int64_t) {}));
  const std::size_t at_checkpoint = fracture_of(first.view()).segments().size();
  ASSERT_GT(at_checkpoint, 0u) << "the checkpoint must hold cracks";
  const std::string path = ::testing::TempDir() + "/cracked.nmmstate";
  solve::write_checkpoint(first.view(), path);
  second.restart_from(path);
  EXPECT_EQ(solve::state_hash(second.view()), solve::state_hash(first.view()));
  ASSERT_PRED1(test::ended_ok, second.run_until(1.5, [](std::int64_t) {}));
  std::printf("restart with %zu segments at the checkpoint, %zu at the end\n", at_checkpoint,
              fracture_of(straight.view()).segments().size());
  EXPECT_GT(fracture_of(straight.view()).segments().size(), at_checkpoint) << "cracks must grow after the restart";
  EXPECT_EQ(fracture_of(second.view()).segments().size(), fracture_of(straight.view()).segments().size());
  EXPECT_EQ(second.view().mesh.element_count(), straight.view().mesh.element_count());
  EXPECT_EQ(solve::state_hash(second.view()), solve::state_hash(straight.view()));
}


namespace {
// A run of `doc` as nmm-solve makes it (solve_run.h), into `dir`: its summary, its energy.csv
// rows, and, per accepted step, `reaction` (N/m, the loaded support's force, from the state) for
// the trapezoid of the support's work: Σ ½(F_n−1 + F_n)·travel_n.
struct EnergyRun {
  Outcome outcome;
  nlohmann::json summary;
  std::vector<std::map<std::string, double>> rows;
  double trapezoid_work = 0;  // J/m
  double peak = 0;            // N/m, the largest reaction
};

EnergyRun energy_run(const nlohmann::json& doc, const std::string& name, const test::TempDir& dir,
                     double travel_per_step, const std::function<double(const solve::RunView&)>& reaction) {
  const SceneDef s = scene_from_json(doc, name);
  Mesh m = pre::build_mesh(s, name);
  m.scene_text = doc.dump();
  m.scene_sha256 = sha256(m.scene_text);
  solve::SolveOptions o;
  o.out_dir = dir.path("run");
  solve::SolveRun run(m, name, o);
  EnergyRun r;
  double last = 0;
  solve::StepFunction watch([&](const solve::RunView& v, std::int64_t, bool) {
    const double f = reaction(v);
    r.trapezoid_work += 0.5 * (last + f) * travel_per_step;
    r.peak = std::max(r.peak, f);
    last = f;
  });
  run.add(watch);
  r.summary = run.run();
  r.outcome = run.outcome();
  r.rows = test::csv_rows(dir.path("run/energy.csv"));
  return r;
}

// %, the largest |residual| of the rows against the work done so far (load_work − gravity).
double worst_residual(const EnergyRun& r) {
  double worst = 0, work = 0;
  for (const auto& row : r.rows) {
    work = std::max(work, std::abs(row.at("load_work") - row.at("gravity")));
    if (work > 0) worst = std::max(worst, 100 * std::abs(row.at("residual")) / work);
  }
  return worst;
}
}  // namespace

// The bar of BarInTensionCracksAcrossAtTheTensileStrength (4 m × 1 m, E 10 GPa, σt 1 MPa, its end
// pulled 1 µm a step) cracks across in one step and unloads to nothing: the strain energy it held,
// σt²·A·L/(2E) = 200 J/m at σt (plane stress, uniaxial), and the support springs' share, are
// released. The static steps take that energy out; energy.csv books it in `fracture` (½ r·d,
// energy.h), so the residual stays the balance's error. The support's work against its travel:
// the reaction is the bar's mean σxx times its 1 m width (in equilibrium, no body force).
TEST(Fracture, TensionBarReleasesItsStrainEnergyIntoTheFractureColumn) {
  const double st_ = 1e6, E = 1e10, L = 4, A = 1;
  const nlohmann::json strength = {{"tensile", st_}, {"cohesion", 4e6}, {"friction_deg", 35}};
  nlohmann::json doc = specimen(L, A, 0.25, 0, 1e-3, strength);
  doc["solver"]["steps"] = 600;
  doc["solver"]["output_every"] = 1;
  const test::TempDir dir;
  const EnergyRun r = energy_run(doc, "bar", dir, 1e-6, [](const solve::RunView& v) {
    return test::rock_mean_stress(v, 0) * 1.0;  // N/m: mean σxx times the 1 m width
  });
  ASSERT_PRED1(test::ended_ok, r.outcome);
  ASSERT_GT(r.summary["fracture"]["segments"].get<int>(), 0);
  // The stored energy the crack released: U + S of the row before the first crack's step.
  // The crack is found on the solution of step first + 1 (cracks.csv names the state it broke).
  const std::int64_t first = r.summary["fracture"]["first_crack_step"].get<std::int64_t>();
  double stored = 0, held = 0, damped_before = 0;
  for (const auto& row : r.rows)
    if (row.at("step") == static_cast<double>(first - 1))
      stored = row.at("strain") + row.at("springs"), held = row.at("strain"), damped_before = row.at("damped");
  const double sigma = r.peak / A;  // Pa, the bar's stress at the peak
  const double closed = sigma * sigma * A * L / (2 * E);
  const auto& end = r.rows.back();
  const double relaxed = end.at("damped") - damped_before;  // the relaxation DDA's inertia term spread over steps
  std::printf("bar: first crack at step %lld at %.5g Pa; U %.5g J/m (closed form σ²AL/2E %.5g), U + S %.5g; "
              "fracture %.5g J/m (summary %.5g) + damped since %.5g = %.5g; load_work %.6g J/m, reaction × travel "
              "%.6g; residual %.4g J/m, worst %.3g %% of the work done\n",
              static_cast<long long>(first), sigma, held, closed, stored, end.at("fracture"),
              r.summary["fracture"]["dissipated_j"].get<double>(), relaxed, end.at("fracture") + relaxed,
              end.at("load_work"), r.trapezoid_work, end.at("residual"), worst_residual(r));
  EXPECT_NEAR(held, closed, 0.01 * closed);  // the bar held what the closed form says
  // What the bar held leaves through the cracking step's crack closure (fracture) and the motion
  // the static steps throw away as the bar relaxes over the next steps (damped: its mass term
  // 2M/Δt² is stiffer than the 4 m bar, so it springs back ~43 % of the rest a step).
  EXPECT_NEAR(end.at("fracture") + relaxed, closed, 0.02 * closed);
  EXPECT_NEAR(end.at("fracture") + relaxed, stored, 0.01 * stored);
  EXPECT_GT(end.at("fracture"), 0.2 * closed);
  EXPECT_DOUBLE_EQ(r.summary["fracture"]["dissipated_j"].get<double>(), end.at("fracture"));
  EXPECT_NEAR(end.at("load_work"), r.trapezoid_work, 0.005 * r.trapezoid_work);
  EXPECT_LT(worst_residual(r), 1.0);
}

// A notched beam in three-point bending (2 m span, 0.2 m deep, a notch 0.1 m deep and 20 mm wide
// under the load; σt 1 MPa, the top pushed down 1 µm a step over 0.1 m): the crack starts at the
// notch and runs up the ligament, its steps re-cut several times. The support's work is its
// reaction times its travel (before the re-cut maps were composed over a step's re-cuts,
// load_work jumped in the cracking step and the residual with it).
TEST(Fracture, NotchedBeamBalancesItsEnergyThroughCracking) {
  const nlohmann::json strength = {{"tensile", 1e6}, {"cohesion", 4e6}, {"friction_deg", 35}};
  nlohmann::json doc = specimen(2.2, 0.2, 0.025, 0, 0, strength);
  doc["bodies"][0]["outer"] = {{0, 0}, {1.09, 0}, {1.09, 0.1}, {1.11, 0.1}, {1.11, 0}, {2.2, 0}, {2.2, 0.2}, {0, 0.2}};
  doc["supports"] = {{{"points", {{0.05, 0}, {0.15, 0}}}, {"fix", "y"}},
                     {{"points", {{2.05, 0}, {2.15, 0}}}, {"fix", "y"}},
                     {{"points", {{1.05, 0.2}, {1.15, 0.2}}}, {"fix", "y"}, {"velocity", {0, -1e-3}}}};
  doc["fixed_points"] = {{0.1, 0.01}};
  doc["solver"]["steps"] = 300;
  doc["solver"]["output_every"] = 1;
  const test::TempDir dir;
  // The load: the vertical force the beam's supports carry, half the sum of both rollers' — read
  // as the load support's spring force, k_s ∫ (h − u_y) ds over its edges (energy.h S).
  const EnergyRun r = energy_run(doc, "beam", dir, 1e-6, [](const solve::RunView& v) {
    const double k = v.model.support_stiffness(), h = -1e-3 * v.state.time;
    double f = 0;
    for (const solve::BoundaryEdge& be : v.model.support_edges()[2]) {
      const double len = std::hypot(v.state.loop_xy[2 * be.next] - v.state.loop_xy[2 * be.vertex],
                                    v.state.loop_xy[2 * be.next + 1] - v.state.loop_xy[2 * be.vertex + 1]);
      f += k * len * 0.5 * ((v.state.loop_u[2 * be.vertex + 1] - h) + (v.state.loop_u[2 * be.next + 1] - h));
    }
    return f;
  });
  const auto& end = r.rows.back();
  std::printf("beam: %s after %zu rows; first crack at step %s, %d segments, %lld steps solved again; peak load "
              "%.5g N/m; load_work %.6g J/m, reaction × travel %.6g; fracture %.5g J/m, damped %.5g J/m; residual "
              "%.4g J/m, worst %.3g %% of the work done\n",
              r.summary["stop_code"].get<std::string>().c_str(), r.rows.size(),
              r.summary["fracture"]["first_crack_step"].dump().c_str(), r.summary["fracture"]["segments"].get<int>(),
              r.summary["fracture"]["steps_resolved"].get<long long>(), r.peak, end.at("load_work"),
              r.trapezoid_work, end.at("fracture"), end.at("damped"), end.at("residual"), worst_residual(r));
  for (std::size_t i = 1; i < r.rows.size(); ++i)  // the steps that moved the residual (diagnostics)
    if (std::abs(r.rows[i].at("residual") - r.rows[i - 1].at("residual")) > 1e-3 * end.at("load_work"))
      std::printf("  step %g: residual %+.4g J/m (W %.4g, U %.4g, S %.4g, Q %.4g, F %.4g)\n", r.rows[i].at("step"),
                  r.rows[i].at("residual") - r.rows[i - 1].at("residual"), r.rows[i].at("load_work"),
                  r.rows[i].at("strain"), r.rows[i].at("springs"), r.rows[i].at("damped"), r.rows[i].at("fracture"));
  ASSERT_PRED1(test::ended_ok, r.outcome);
  ASSERT_GT(r.summary["fracture"]["segments"].get<int>(), 1);
  EXPECT_GT(end.at("fracture"), 0);
  EXPECT_NEAR(end.at("load_work"), r.trapezoid_work, 0.005 * r.trapezoid_work);
  // Within 1 % since the release is read from the force the cut start is out of balance by
  // (crack_release.h; measured 2026-11-29: 0.0115 % at worst in the matrix's beam, 13.8 % with
  // the faces' traction σ0·n alone). A jump like the 180 J/m of the uncomposed maps fails it too.
  EXPECT_LT(worst_residual(r), 1.0);
}

// The energy a crack releases against Clapeyron's theorem. The notched beam of
// NotchedBeamBalancesItsEnergyThroughCracking in static_mode "equilibrium" (no inertia term) is a
// linear system driven by one prescribed displacement, the load support's travel h = v·t: in
// every accepted state its stored energy is E = U + S = ½ P·h = ½ k·h² (P the support's force,
// k = 2E/h² the secant stiffness of the beam with the cracks it has). A step that cracks at fixed
// grip releases what the stiffness lost, ½ h²·(k_before − k_after) (= ½ P²·ΔC at fixed load);
// the step also moves the support by Δh, so the closed form is bracketed by h at the step's start
// and at its end: E_b − E_a·(h_b/h_a)² … E_b·(h_a/h_b)² − E_a, their mean taken. energy.csv's
// fracture column must book it in each cracking step (measured 2026-11-29: 0.38565 J/m in all
// against 0.38569; the faces' traction σ0·n alone booked 0.1637, 42 %).
TEST(Fracture, ACrackReleasesWhatTheBeamsStiffnessLost) {
  const nlohmann::json strength = {{"tensile", 1e6}, {"cohesion", 4e6}, {"friction_deg", 35}};
  nlohmann::json doc = specimen(2.2, 0.2, 0.025, 0, 0, strength);
  doc["bodies"][0]["outer"] = {{0, 0}, {1.09, 0}, {1.09, 0.1}, {1.11, 0.1}, {1.11, 0}, {2.2, 0}, {2.2, 0.2}, {0, 0.2}};
  const double speed = 1e-3;  // m/s, the load support's
  doc["supports"] = {{{"points", {{0.05, 0}, {0.15, 0}}}, {"fix", "y"}},
                     {{"points", {{2.05, 0}, {2.15, 0}}}, {"fix", "y"}},
                     {{"points", {{1.05, 0.2}, {1.15, 0.2}}}, {"fix", "y"}, {"velocity", {0, -speed}}}};
  doc["fixed_points"] = {{0.1, 0.01}};
  doc["solver"]["steps"] = 300;
  doc["solver"]["output_every"] = 1;
  doc["solver"]["static_mode"] = "equilibrium";
  const test::TempDir dir;
  const EnergyRun r = energy_run(doc, "beam", dir, 1e-6, [](const solve::RunView&) { return 0.0; });
  ASSERT_PRED1(test::ended_ok, r.outcome);
  int cracking = 0;
  double booked = 0, closed = 0;
  for (std::size_t i = 1; i < r.rows.size(); ++i) {
    const auto &b = r.rows[i - 1], &a = r.rows[i];
    const double f = a.at("fracture") - b.at("fracture");
    if (f == 0) continue;
    const double hb = speed * b.at("time"), ha = speed * a.at("time");
    const double eb = b.at("strain") + b.at("springs"), ea = a.at("strain") + a.at("springs");
    const double low = eb - ea * (hb / ha) * (hb / ha), high = eb * (ha / hb) * (ha / hb) - ea;
    std::printf("  step %g: fracture %+.6g J/m, ½h²Δk %.6g … %.6g\n", a.at("step"), f, low, high);
    EXPECT_GE(f, low - 1e-3 * std::abs(low)) << "step " << a.at("step");
    EXPECT_LE(f, high + 1e-3 * std::abs(high)) << "step " << a.at("step");
    ++cracking;
    booked += f;
    closed += 0.5 * (low + high);
  }
  std::printf("beam (equilibrium steps): %d cracking steps; fracture %.6g J/m, Clapeyron %.6g J/m; residual %.4g "
              "J/m, worst %.3g %% of the work done\n",
              cracking, booked, closed, r.rows.back().at("residual"), worst_residual(r));
  ASSERT_GE(cracking, 3);
  EXPECT_NEAR(booked, closed, 0.005 * closed);
  EXPECT_LT(worst_residual(r), 0.1);
}

// A re-cut moves no energy between columns: the bar loaded to 75 % of its strength, and the same
// state carried onto the mesh with a crack cut across it, have the same strain and spring
// energies (energy.h's state terms: what the meter reads on either side of a re-cut).
TEST(Fracture, TheCutItselfMovesNoEnergy) {
  const test::CutCrack c = cut_stressed_bar();
  const solve::Model before_model(c.before_mesh, c.scene, "bar"), after_model(c.now, c.cracked, "bar");
  const solve::EnergyRow a = solve::EnergyMeter(before_model).state_terms(c.before, {});
  const solve::EnergyRow b = solve::EnergyMeter(after_model).state_terms(c.after, {});
  std::printf("cut: K %.10g → %.10g, U %.10g → %.10g, V %.10g → %.10g, S %.10g → %.10g J/m\n", a.kinetic,
              b.kinetic, a.strain, b.strain, a.gravity, b.gravity, a.springs, b.springs);
  EXPECT_GT(a.strain, 100.0);
  EXPECT_NEAR(b.strain, a.strain, 1e-12 * a.strain);
  EXPECT_NEAR(b.springs, a.springs, 1e-12 * a.springs);
  EXPECT_EQ(b.kinetic, 0.0);
  EXPECT_EQ(b.gravity, 0.0);
}

// A step that cracks re-cuts the mesh and is solved again from its start on the cut mesh. The
// closed contacts the accepted step before it ended with, each with its end force c_end on its
// rows, are carried onto the cut mesh (contact_effect.h carry_ended): the vertex by the re-cut's
// map, the edge's point to the piece of its element that holds it, the row's values to the same
// local unknowns of the piece (a piece keeps its triangle's nodes and cover functions). Closed
// form: a contact the cut mesh's detection finds closed again starts the step with its history's
// forces on rows at the step's start — the same force at the same point — so over the step's
// solution d, Σ c_end·d of those equals Σ c_start·d of the contacts closed at the step's start,
// within the rows' update between the two starts (the end rows are linearised on the geometry
// of the step before, and the cracks open under them) and what re-paired contacts start with:
// measured 2026-11-30 within 2.4e-3 of Σ|c_start·d| over the ten cut steps, 3.9e-2 in one of
// them; with each contact's depth carried across the re-cut too (contact_set.cpp restore) and
// crack ends moved onto their edges at order 0 the path cuts 18 steps, within 2.6e-3 over all and
// 0.14 in one of them (step 92: re-found contacts start from their carried depth on the cut
// edge). A re-cut that carried nothing would be off by all of it. The others, released, start
// with none, and ½ (0 − c_end)·d of them is what `damped` books (docs/energy.md: 1038 J/m here,
// which went to the residual before; the cell's residual 4.05 → 1.32 % of the work at worst).
TEST(Fracture, ARecutCarriesTheContactsEndForcesOntoThePiecesTheyActOn) {
  reference::RockTestCase c;
  ASSERT_TRUE(reference::rock_test_case_from_name("uniaxial.h1.static.fast", c));
  const reference::RockTestSpecimen sp = reference::rock_test(c);
  const SceneDef scene = scene_from_json(sp.scene, "uniaxial");
  const Mesh mesh = pre::build_mesh(scene, "uniaxial");
  TimeStepper st(mesh, scene, "uniaxial");
  std::size_t topology = 0;
  int cut_steps = 0, released_steps = 0;
  double released = 0, worst = 0;  // J/m, Σ ½ (0 − c_end)·d over the cut steps; –
  double differ = 0, total = 0;    // J/m, Σ |c_end·d − c_start·d| and Σ Σ|c_start·d| over them
  std::vector<solve::ContactEffect::EndedShear> last;  // the last accepted step's closed contacts at its end
  std::size_t carried = 0, sheared = 0;  // of them, carried across a re-cut; with a shear force
  std::size_t dropped = 0;               // of them, not carried
  const Outcome o = st.run_until(sp.end_time * (1 - 1e-9), [&](std::int64_t) {
    const solve::RunView v = st.view();
    const auto* contact = solve::find_effect<solve::ContactEffect>(v);
    ASSERT_NE(contact, nullptr);
    const std::vector<solve::ContactEffect::EndedShear> ended = contact->ended_shear(false);
    if (v.topology == topology) {
      last = ended;
      return;
    }
    topology = v.topology;
    // Every one is carried: a re-cut keeps each loop vertex at its point, on its own face where a
    // crack ends inside its element (the loop passes that point twice: contact_effect.cpp
    // old_vertex_on_its_side). The map's first vertex at the point alone dropped the other face's:
    // 12 of 945 here (2026-12-01; within 0.0039 over all before, 0.0036 now; released 1213.16 →
    // 1215.16 J/m).
    const std::vector<solve::ContactEffect::EndedShear> started = contact->ended_shear(true);
    EXPECT_EQ(started.size(), last.size()) << "step " << v.state.step << ": closed contacts dropped by the re-cut";
    dropped += last.size() - std::min(last.size(), started.size());
    // Each contact carried keeps its end shear force and springs' energy, bit for bit: T0 of a
    // contact found open on its edge (energy_step's friction) and the trace's start energy.
    for (const solve::ContactEffect::EndedShear& e : started) {
      const auto was = std::find_if(last.begin(), last.end(), [&](const solve::ContactEffect::EndedShear& l) {
        return l.bx == e.bx && l.by == e.by && l.shear_force == e.shear_force && l.stored == e.stored;
      });
      EXPECT_NE(was, last.end()) << "step " << v.state.step << ": a carried contact at (" << e.bx << ", " << e.by
                                 << ") has T " << e.shear_force << " N, " << e.stored << " J/m";
      ++carried;
      if (e.shear_force != 0) ++sheared;
    }
    last = ended;
    // m, the step's solution on the cut mesh: the state now less its start carried onto it.
    const Eigen::Index n = v.space.unknowns();
    const int dpc = v.space.dofs_per_cover();
    Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
    for (std::size_t k = 0; k < v.mesh.cover_count(); ++k)
      for (int j = 0; j < dpc; ++j) {
        const std::size_t i = k * static_cast<std::size_t>(dpc) + static_cast<std::size_t>(j);
        d[v.space.first_unknown(k) + j] = v.state.cover_u[i] - v.recut_start.cover_u[i];
      }
    // J/m, c_start·d of the contacts closed at the step's start (their rows, the start forces).
    const solve::ContactProblem& p = contact->problem();
    // The scale: Σ |c_start·d| contact by contact (the sum cancels between the faces of a crack).
    double start = 0, scale = 0;
    for (std::size_t k = 0; k < p.contacts().size(); ++k) {
      const solve::Contact& q = p.contacts()[k];
      if (q.start_state == solve::ContactState::open) continue;
      const solve::ContactProblem::Row r = p.row(k);
      double w = 0;
      for (int i = 0; i < r.size; ++i)
        if (r.dofs[i] >= 0 && r.dofs[i] < n)
          w += (p.work(k).start_normal_force * r.cn(i) - q.start_shear_force * r.cs(i)) * d[r.dofs[i]];
      start += w;
      scale += std::abs(w);
    }
    const double kept = contact->started_end_forces(n, false).dot(d);
    const double gone = -0.5 * contact->started_end_forces(n, true).dot(d);
    std::printf("  step %lld re-cut: c_end·d %.6g J/m carried, c_start·d %.6g J/m (Σ|c_start·d| %.6g); released "
                "½(0 − c_end)·d %.6g J/m\n",
                static_cast<long long>(v.state.step), kept, start, scale, gone);
    ++cut_steps;
    if (scale > 0) worst = std::max(worst, std::abs(kept - start) / scale);
    EXPECT_NEAR(kept, start, 0.2 * scale + 1e-9) << "step " << v.state.step;
    differ += std::abs(kept - start);
    total += scale;
    if (gone != 0) ++released_steps, released += gone;
  });
  ASSERT_PRED1(test::ended_ok, o);
  std::printf("uniaxial h 0.1 m, static, fast: %d steps re-cut, the carried end forces within %.2g of Σ|c_start·d| "
              "at worst, %.2g over all; %d of them released contacts, ½ (0 − c_end)·d = %.6g J/m\n",
              cut_steps, worst, differ / total, released_steps, released);
  EXPECT_LT(differ, 0.005 * total);
  EXPECT_GE(cut_steps, 3);
  EXPECT_GE(released_steps, 1);
  EXPECT_GT(released, 100.0);  // J/m: what a re-cut lost to the residual before
  std::printf("%zu contacts carried across the re-cuts, %zu of them with a shear force; %zu dropped\n", carried, sheared,
              dropped);
  EXPECT_GT(sheared, 10u);
}

// Sliver pieces (issue 48): a block a crack cuts off a single element has no stiffness path to the
// rock beside it, and below kSliverArea·h² its own contacts were all that held it (one of
// 1.5e-2·h² under a biaxial specimen's platen moved 2 mm a step at every Δt). A crack is cut by
// hand across a corner of a square at rest (h 0.25 m, a lattice of near-equilateral triangles),
// as the fracture rule cuts one, from a along one side to b along the other: the corner piece is
// the triangle a·b/2; Fracture::cut sees the re-cut mesh.
namespace {
struct CornerPiece {
  int elements = 0;        // of the re-cut mesh, inside the corner triangle
  double area = 0;         // m², theirs
  int debris = 0;          // of them, debris
  int debris_blocks = 0;
  double debris_area = 0;  // m², Fracture's count
};
CornerPiece cut_corner(const Vec2& corner, double a, double b) {
  const nlohmann::json strength = {{"tensile", 1e6}, {"cohesion", 4e6}, {"friction_deg", 35}};
  const SceneDef s = scene_from_json(specimen(1, 1, 0.25, 0, 0, strength), "corner");
  const Mesh m = pre::build_mesh(s, "corner");
  TimeStepper st(m, s, "corner");
  solve::Fracture f(s);
  EXPECT_TRUE(f.active());
  EXPECT_TRUE(f.find(m, s, st.view().state, {}).empty());  // at rest nothing breaks
  // From (a, 0) to (0, b) in the corner's axes (pointing into the square), 10 % past both sides.
  const double sx = corner.x == 0 ? 1 : -1, sy = corner.y == 0 ? 1 : -1;
  CrackSegment seg;
  seg.a = {corner.x + sx * 1.1 * a, corner.y - sy * 0.1 * b};
  seg.b = {corner.x - sx * 0.1 * a, corner.y + sy * 1.1 * b};
  SceneDef cracked = s;
  cracked.joints.push_back({s.fracture.crack_set, {seg.a, seg.b}});
  pre::RecutMap map;
  const Mesh now = pre::recut(m, cracked, s.joints.size(), "corner", map);
  f.cut({seg}, now, map);
  CornerPiece p;
  for (std::size_t e = 0; e < now.element_count(); ++e) {
    const Vec2 q = solve::inside_point(now, e);
    if (sx * (q.x - corner.x) / a + sy * (q.y - corner.y) / b >= 1) continue;
    ++p.elements;
    p.area += element_area(now, e);
    p.debris += f.debris()[e];
  }
  p.debris_blocks = f.debris_blocks();
  p.debris_area = f.debris_area();
  std::printf("corner (%g, %g), a %g m, b %g m: %d elements, %.4g m2 = %.4g h2, %d debris (%d blocks, %.4g m2)\n",
              corner.x, corner.y, a, b, p.elements, p.area, p.area / 0.0625, p.debris, p.debris_blocks, p.debris_area);
  return p;
}
}  // namespace

TEST(Fracture, ASliverACrackCutsOffOneElementIsDebris) {
  const double h2 = 0.25 * 0.25;
  ASSERT_LT(solve::Fracture::kDebrisArea, 0.015);
  ASSERT_GT(solve::Fracture::kSliverArea, 0.015);
  ASSERT_LT(solve::Fracture::kSliverArea, 0.078);
  // 1.5e-2·h², the biaxial sliver's share, of one element (the corner triangle (0, 1),
  // (0.0774, 1), (0, 0.866) m): above kDebrisArea, debris.
  const double c15 = std::sqrt(2 * 0.015 * h2), c3 = std::sqrt(2 * 0.03 * h2);
  const CornerPiece one = cut_corner({0, 1}, c15, c15);
  ASSERT_EQ(one.elements, 1);
  EXPECT_NEAR(one.area, c15 * c15 / 2, 1e-12);
  EXPECT_EQ(one.debris, 1);
  EXPECT_EQ(one.debris_blocks, 1);
  EXPECT_NEAR(one.debris_area, c15 * c15 / 2, 1e-12);
  // 7.8e-2·h² of one element (the corner triangle at (1, 1)): a piece of rock, kept.
  const CornerPiece big = cut_corner({1, 1}, 0.075, 0.13);
  ASSERT_EQ(big.elements, 1);
  EXPECT_NEAR(big.area, 0.075 * 0.13 / 2, 1e-12);
  EXPECT_EQ(big.debris, 0);
  EXPECT_EQ(big.debris_blocks, 0);
  // 3e-2·h² over the two elements that meet at the corner (0, 0): a stiffness path across
  // their shared edge; kept.
  const CornerPiece two = cut_corner({0, 0}, c3, c3);
  ASSERT_EQ(two.elements, 2);
  EXPECT_NEAR(two.area, c3 * c3 / 2, 1e-12);
  EXPECT_EQ(two.debris, 0);
  EXPECT_EQ(two.debris_blocks, 0);
}

// A piece is a block that contacts, supports or inertia hold, or debris (issue 48; docs/fracture.md
// "Free pieces in static equilibrium"). In static_mode "equilibrium" (K d = F, no inertia) a block
// a crack cuts off a held body has no support and its faces may open: K is singular on its
// covers and the run stopped "unconstrained". Such a piece takes DDA's static inertia 2M/Δt²
// from rest, so under a resultant F it moves d = F·Δt²/(2m) a step (m its mass per metre).
// Here the piece is cut off by a scene joint right across a bar whose left end is on rollers and
// a fixed point; the right block (2 m × 1 m, ρ 2500: m = 5000 kg/m) is pulled by a traction of
// 1e5 Pa on its end (F = 1e5 N/m) away from the joint, which holds no tension: d = 1e-5 m a step
// of 1 ms. The rock is strong (nothing cracks), so only the rule is tested.
TEST(Fracture, AFreePieceInStaticEquilibriumTakesInertiaAndMovesByFDt2Over2m) {
  const nlohmann::json strength = {{"tensile", 1e9}, {"cohesion", 4e9}, {"friction_deg", 35}};
  nlohmann::json doc = specimen(4, 1, 0.25, 0, 0, strength);
  doc["supports"] = {{{"points", {{0, 0}, {0, 1}}}, {"fix", "x"}}};
  doc["joint_sets"]["bedding"] = doc["joint_sets"]["crack"];
  doc["joints"] = {{{"set", "bedding"}, {"points", {{2.01, -0.1}, {2.01, 1.1}}}}};
  doc["tractions"] = {{{"points", {{4, 0}, {4, 1}}}, {"normal", 1e5}, {"shear", 0}}};
  doc["measure_points"] = {{3.0, 0.5}, {1.0, 0.5}};
  doc["solver"] = {{"time_step", 1e-3}, {"steps", 6}, {"dynamic", false}, {"static_mode", "equilibrium"}};
  const SceneDef s = scene_from_json(doc, "piece");
  const Mesh m = pre::build_mesh(s, "piece");
  ASSERT_EQ(m.block_count(), 2u);
  TimeStepper st(m, s, "piece");
  std::vector<double> ux_piece, ux_held;
  const Outcome o = st.run_until(6e-3, [&](std::int64_t) {
    ux_piece.push_back(st.view().state.measure[0].displacement()[0]);
    ux_held.push_back(st.view().state.measure[1].displacement()[0]);
  });
  ASSERT_PRED1(test::ended_ok, o);
  ASSERT_EQ(ux_piece.size(), 6u);
  const double mass = 2500 * (4 - 2.01) * 1, expected = 1e5 * 1e-3 * 1e-3 / (2 * mass);  // m a step
  for (std::size_t k = 1; k < ux_piece.size(); ++k) {
    const double step = ux_piece[k] - ux_piece[k - 1];
    std::printf("step %zu: piece moved %.6g m (F·Δt²/(2m) = %.6g m), held block at %.3g m\n", k + 1, step, expected,
                ux_held[k]);
    EXPECT_NEAR(step, expected, 0.01 * expected);
    EXPECT_LT(std::abs(ux_held[k]), 1e-9);  // the held block carries nothing
  }
}

}  // namespace nmm
