// Water in the joints (solver/discretisation/joint_water.h) against hydrostatics: the face forces of the water,
// summed over a body or a block, are Archimedes' buoyancy under a level water table, −∫∇p dA
// under a sloping one, ½·γw·d² on a joint filled to a depth d, and ∫p ds for a pressure table.
// The forces are read off the first step's right-hand side (with and without the water).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "preprocess/cover_cutter.h"
#include "solver/stepping/time_stepper_probe.h"
#include "common/scene.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {
namespace {

constexpr double kGammaW = 1000 * 9.81;  // N/m³

// A 2 m × 2 m body (optionally cut by the vertical joint x = 1 into two blocks), gravity down,
// with the scene's "water" given as JSON.
SceneDef square(const std::string& water, bool joint) {
  std::string text = R"({
    "gravity": [0, -9.81],
    "materials": {"rock": {"density": 2500, "young": 1e10, "poisson": 0.25}},
    "joint_sets": {"j": {"friction_deg": 30, "normal": {"model": "constant", "kn": 1e11},
                         "shear": {"model": "constant", "ks": 4e10}}},
    "bodies": [{"material": "rock", "outer": [[0, 0], [2, 0], [2, 2], [0, 2]]}],
    "mesh": {"size": 0.5})";
  if (joint) text += R"(, "joints": [{"set": "j", "points": [[1, 0], [1, 2]]}])";
  if (!water.empty()) text += ", \"water\": " + water;
  text += "}";
  return parse_scene(text, "water.json");
}

// Σ of the first step's nodal forces (x, y) over the unknowns of `block` (−1: all), N.
std::array<double, 2> force_on(const SceneDef& s, const Mesh& m, int block) {
  TimeStepper st(m, s, "water");
  const Eigen::VectorXd& f = TimeStepperProbe::assemble_rhs(st, 1e-3);
  std::set<int> unknowns;
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    if (block >= 0 && m.element_block[e] != block) continue;
    const int* u = st.view().space.element_unknowns(e);
    for (int i = 0; i < st.view().space.element_dofs(); ++i) unknowns.insert(u[i]);
  }
  std::array<double, 2> sum{0, 0};
  for (int u : unknowns) sum[static_cast<std::size_t>(u % 2)] += f[u];
  return sum;
}

// The water's share: the forces with water minus those without.
std::array<double, 2> water_force(const std::string& water, bool joint, int block) {
  const SceneDef wet = square(water, joint), dry = square("", joint);
  const Mesh m = pre::build_mesh(dry, "water");
  const auto a = force_on(wet, m, block), b = force_on(dry, m, block);
  return {a[0] - b[0], a[1] - b[1]};
}

TEST(JointWater, LevelWaterTableGivesArchimedesBuoyancy) {
  // Water to y = 1.2 (between the mesh's node rows): 2.4 m² of rock under water.
  const auto f = water_force(R"({"phreatic": [[-1, 1.2], [3, 1.2]]})", false, -1);
  EXPECT_NEAR(f[0], 0, 1e-9 * kGammaW);
  EXPECT_NEAR(f[1], kGammaW * 2.4, 1e-9 * kGammaW * 2.4);
  // Fully under water: γw·4 m²; above it: nothing.
  EXPECT_NEAR(water_force(R"({"phreatic": [[0, 7], [2, 7]]})", false, -1)[1], kGammaW * 4, 1e-6);
  EXPECT_EQ(water_force(R"({"phreatic": [[0, -1], [2, -1]]})", false, -1)[1], 0.0);
}

TEST(JointWater, SlopingWaterTableGivesMinusTheIntegralOfThePressureGradient) {
  // z_w = 0.5 + x/2: p = γw·(z_w − y), ∇p = γw·(½, −1) over the wet 2 m², so the water pushes
  // with −∫∇p dA = γw·(−1, 2) m². The polyline's second point past the body: held beyond its end.
  const auto f = water_force(R"({"phreatic": [[0, 0.5], [1, 1.0], [2, 1.5], [2.5, 1.75]]})", false, -1);
  EXPECT_NEAR(f[0], -kGammaW * 1.0, 1e-9 * kGammaW);
  EXPECT_NEAR(f[1], kGammaW * 2.0, 1e-9 * kGammaW);
}

TEST(JointWater, JointFilledToADepthPushesBothFacesApart) {
  // The joint x = 1 filled from its foot (y = 0) to 0.8 m: ½·γw·0.8² on each face, outwards.
  const std::string water = R"({"joints": [{"joint": 0, "fill_depth": 0.8}]})";
  const double thrust = 0.5 * kGammaW * 0.8 * 0.8;
  const Mesh m = pre::build_mesh(square("", true), "water");
  int left_block = -1;  // the block of the element at the lower-left corner
  for (std::size_t e = 0; e < m.element_count() && left_block < 0; ++e)
    if (m.loop_xy[2 * m.element_loop_offset[e]] < 0.3) left_block = m.element_block[e];
  const auto left = water_force(water, true, left_block), right = water_force(water, true, 1 - left_block);
  EXPECT_NEAR(left[0], -thrust, 1e-9 * thrust);
  EXPECT_NEAR(left[0] + right[0], 0, 1e-9 * thrust);
  EXPECT_NEAR(left[1], 0, 1e-9 * thrust);
  EXPECT_NEAR(right[1], 0, 1e-9 * thrust);
}

TEST(JointWater, PressureTableAlongTheJoint) {
  // 100 kPa at the joint's first point (1, 0), 300 kPa at its end (1, 2): ∫p ds = 400 kN per face.
  const auto f = water_force(R"({"joints": [{"joint": 0, "pressure": [[0, 1e5], [2, 3e5]]}]})", true, 0);
  EXPECT_NEAR(std::abs(f[0]), 4e5, 1e-6);
  // One row: uniform.
  const auto g = water_force(R"({"joints": [{"joint": 0, "pressure": 2e5}]})", true, 1);
  EXPECT_NEAR(std::abs(g[0]), 4e5, 1e-6);
}

}  // namespace
}  // namespace nmm::solve
