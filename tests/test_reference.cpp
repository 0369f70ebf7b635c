// The reference problems' closed forms (reference/) against known numbers, and the data/
// examples' promises against the same closed forms: the number a scene header promises
// ("// expect: history ... within V +- T", checked after the run by tests/check_expect.py) must be
// the library's closed form for that scene, so the example, the tests and nmm-study agree on one
// value.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "reference/cantilever.h"
#include "reference/kirsch.h"
#include "common/math_constants.h"
#include "reference/slides.h"
#include "reference/sliding_block.h"
#include "reference/wave_bar.h"

namespace nmm::reference {
namespace {

// The value V of the scene header's first "// expect: history ... within V +- T" line whose
// text contains `what`.
double promised(const std::string& scene, const std::string& what) {
  std::ifstream in(std::string(NMM_SOURCE_DIR) + "/data/" + scene);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("// expect: history", 0) != 0 || line.find(what) == std::string::npos) continue;
    const std::size_t at = line.find(" within ");
    if (at != std::string::npos) return std::stod(line.substr(at + 8));
  }
  ADD_FAILURE() << scene << ": no expect line with '" << what << "'";
  return std::nan("");
}

TEST(Reference, SlidingBlockClosedForm) {
  // ½·9.81·(sin 30° − cos 30° tan 20°) = 0.90641 m in 1 s; φ ≥ α holds the block.
  EXPECT_NEAR(sliding_distance(30, 20, 1), 0.906407, 1e-6);
  EXPECT_NEAR(sliding_distance(30, 20, 2), 4 * sliding_distance(30, 20, 1), 1e-12);
  EXPECT_EQ(sliding_distance(30, 35, 1), 0);
  // data/block_on_incline.json promises the same travel (to its 3 digits).
  EXPECT_NEAR(promised("block_on_incline.json", "travel 0"), sliding_distance(30, 20, 1), 5e-4);
}

TEST(Reference, SlidingBlockScenes) {
  const SceneDef s = sliding_block_tilted(30, 20, 0.5, 0, 2e-3, 5);
  EXPECT_EQ(s.bodies.size(), 2u);
  EXPECT_DOUBLE_EQ(s.joint_sets[0].normal.kn, 5e10);  // kn = 5·E per contact point
  EXPECT_DOUBLE_EQ(s.joint_sets[0].shear.ks, 2e10);   // ks = kn/2.5
  EXPECT_DOUBLE_EQ(s.solver.time_step, 2e-3);
  EXPECT_NEAR(std::atan2(s.gravity.x, -s.gravity.y) * 180 / nmm::kPi, 30, 1e-12);
  // The incline: the block's bottom edge lies on the 30° line through (0, 0.144338).
  const SceneDef in = sliding_block_incline(30, 20);
  for (int i = 0; i < 2; ++i) {
    const Vec2 p = in.bodies[1].outer[i];
    EXPECT_NEAR(p.y - 0.144338, p.x * std::tan(30 * nmm::kPi / 180), 1e-12);
  }
}

TEST(Reference, CantileverTimoshenko) {
  // P L³/(3 E I) = 1e5·1000/(3·1e10/12) = 0.04 m, shear P L/(κ G H) = 1e6/(5/6·4e9) = 3e-4 m.
  EXPECT_NEAR(timoshenko_tip_deflection(), 0.0403, 1e-12);
  const SceneDef s = cantilever(0.5);
  EXPECT_EQ(s.fixed_points.size(), 5u);  // every h/2 along the 1 m clamped end
  EXPECT_EQ(s.loads.size(), 1u);
  EXPECT_DOUBLE_EQ(s.loads[0].force.y, -1e5);
}

TEST(Reference, KirschWall) {
  // σθ(a, θ) = 2P − 4Q cos 2θ: 3p_y − p_x = 25 MPa at the side wall, 3p_x − p_y = 5 MPa at the
  // crown for K0 = 0.5; far away the field stress.
  const double py = kKirschPressure, px = 0.5 * py;
  EXPECT_NEAR(kirsch_hoop(px, py, kKirschRadius, 0), 25e6, 1e-6);
  EXPECT_NEAR(kirsch_hoop(px, py, kKirschRadius, nmm::kPi / 2), 5e6, 1e-6);
  EXPECT_NEAR(kirsch_hoop(px, py, 1e4, 0), py, 1);  // a²/r² = 1e-8: 0.075 Pa off
  // Hydrostatic: u_r = p a²/(2 G r), whatever ν.
  const double G = kKirschYoung / (2 * (1 + kKirschPoisson));
  EXPECT_NEAR(kirsch_radial_displacement(py, py, G, kKirschPoisson, 2, 0.3), py / (2 * G * 2), 1e-15);
}

TEST(Reference, PlanarSlideHoekBray) {
  // data/planar_slide.json: H = 5 m, ψf = 60°, ψp = 30°, crack 5 m behind the toe, φ = 25°,
  // c = 10 kPa; its header and data.planar_slide.fos check nmm-fos against F = 1.2533.
  const ReferenceSlide r = planar_slide(5, 60, 30, 5, 25, 1e4);
  EXPECT_NEAR(r.fos, 1.2533, 5e-5);
  EXPECT_NEAR(r.plane_length, 5.774, 5e-4);
  EXPECT_NEAR(r.weight, 259.1e3, 50);
  // Block on a plane: F = tan φ / tan α.
  EXPECT_NEAR(block_on_plane(30, 35).fos, std::tan(35 * nmm::kPi / 180) /
                                              std::tan(30 * nmm::kPi / 180), 1e-12);
}

TEST(Reference, WaveBarFinalDisplacement) {
  // Once the pulse has passed, every point has moved 2p/(ωZ); data/joint_wave.json promises the
  // displacement after the joint at its end, which the pulse has passed by then.
  const JointWaveSetup w;
  const JointWaveClosedForm cf(w);
  EXPECT_NEAR(cf.final_displacement(), 2 * w.pressure * w.duration / (nmm::kPi * cf.impedance()), 1e-15);
  const double t_end = joint_wave_scene(w).solver.steps * w.dt;
  EXPECT_NEAR(promised("joint_wave.json", "ux 1"), cf.displacement(w.after_x, t_end),
              0.03 * cf.final_displacement());
}

}  // namespace
}  // namespace nmm::reference
