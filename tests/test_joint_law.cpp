// The seed paper's contact model against its closed forms (issue 5): the Bandis–Barton closure
// and the hyperbolic shear law, first as curves, then through the whole solver for one joint in
// normal compression and in direct shear.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "tests/ended_ok.h"
#include "preprocess/cover_cutter.h"
#include "reference/joint_specimen.h"
#include "solver/contact/joint_law.h"
#include "studies/joint_specimen_run.h"
#include "common/math_constants.h"
#include "common/scene.h"
#include "solver/stepping/time_stepper.h"
#include "common/whole_file.h"

namespace nmm::solve {
namespace {

ContactLaw bb_law() {
  ContactLaw law;
  law.normal = NormalModel::bandis_barton;
  law.kni = 15.35e9;  // JRC 10, JCS 100 MPa, σc 150 MPa (docs/physics.md §4)
  law.vm = 0.227e-3;
  law.shear = ShearModel::hyperbolic;
  law.ksi = 1e10;
  law.rf = 0.9;
  law.tan_phi = std::tan(30 * kPi / 180);
  return law;
}

double closure_of(double sigma, const ContactLaw& l) { return sigma * l.vm / (l.kni * l.vm + sigma); }

// Mohr–Coulomb strength tanφ·N + c·L; a broken contact (it slid or opened) keeps the residual
// cohesion c_r instead of c: 0 by default (brittle), c for a perfectly plastic joint.
TEST(JointLaw, ShearStrengthKeepsTheResidualCohesionOnceBroken) {
  ContactLaw law;
  law.tan_phi = 0.5;
  law.cohesion = 1e4;
  EXPECT_DOUBLE_EQ(shear_strength(law, 2000, 0.25, false), 0.5 * 2000 + 1e4 * 0.25);
  EXPECT_DOUBLE_EQ(shear_strength(law, 2000, 0.25, true), 0.5 * 2000);
  EXPECT_DOUBLE_EQ(shear_strength(law, -2000, 0.25, false), 1e4 * 0.25);  // tension: c only
  law.residual_cohesion = 4e3;
  EXPECT_DOUBLE_EQ(shear_strength(law, 2000, 0.25, true), 0.5 * 2000 + 4e3 * 0.25);
}

TEST(JointLaw, BandisBartonCurveAndTangent) {
  const ContactLaw law = bb_law();
  const double L = 0.25;
  for (double sigma : {1e6, 5e6, 10e6}) {
    const double d = closure_of(sigma, law);
    const SpringState s = normal_spring(law, d, L);
    EXPECT_NEAR(s.force / L, sigma, 1e-9 * sigma);
    const double h = 1e-9 * law.vm;
    const double fd = (normal_spring(law, d + h, L).force - normal_spring(law, d - h, L).force) / (2 * h);
    EXPECT_NEAR(s.stiffness, fd, 1e-5 * fd);
    EXPECT_FALSE(s.capped);
  }
  // Stiffness rises with closure; the closure is capped below Vm with a finite, growing force.
  EXPECT_LT(normal_spring(law, 0.1e-3, L).stiffness, normal_spring(law, 0.2e-3, L).stiffness);
  const SpringState beyond = normal_spring(law, 2 * law.vm, L);
  EXPECT_TRUE(beyond.capped);
  EXPECT_TRUE(std::isfinite(beyond.force));
  EXPECT_GT(beyond.force, normal_spring(law, 0.99 * law.vm, L).force);
}

TEST(JointLaw, HyperbolicShearCurveTangentAndGuards) {
  const ContactLaw law = bb_law();
  const double L = 0.25, strength = 5e6 * law.tan_phi * L;  // N, at σn = 5 MPa
  const double tf = strength / L;
  double prev_k = std::numeric_limits<double>::infinity();
  for (double frac : {0.3, 0.6, 0.9}) {
    const double tau = frac * tf;
    const double us = tau / (law.ksi * (1 - law.rf * tau / tf));
    const SpringState s = shear_spring(law, us, strength, L);
    EXPECT_NEAR(s.force / L, tau, 1e-9 * tau);
    EXPECT_NEAR(shear_spring(law, -us, strength, L).force, -s.force, 1e-9 * s.force);
    const double h = 1e-9 * us;
    const double fd = (shear_spring(law, us + h, strength, L).force - shear_spring(law, us - h, strength, L).force) / (2 * h);
    EXPECT_NEAR(s.stiffness, fd, 1e-5 * fd);
    EXPECT_LT(s.stiffness, prev_k) << "shear stiffness falls as the shear grows";
    prev_k = s.stiffness;
    EXPECT_NEAR(shear_at_force(law, s.force, strength, L), us, 1e-9 * us);
  }
  const SpringState none = shear_spring(law, 1e-3, 0.0, L);  // no strength: no force, no NaN
  EXPECT_EQ(none.force, 0.0);
  EXPECT_GT(none.stiffness, 0.0);
  EXPECT_GE(shear_spring(law, 1.0, strength, L).stiffness, 1e-3 * law.ksi * L) << "stiffness floor";
}

TEST(JointLaw, BartonBandisEmpiricalRelationsFromJrcJcsUcs) {
  const std::string text = R"({
    "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 } },
    "joint_sets": { "j": { "friction_deg": 30,
        "normal": { "model": "bandis_barton", "jrc": 10, "jcs": 100e6, "ucs": 150e6 },
        "shear": { "model": "hyperbolic", "ksi": 1e10, "rf": 0.9 } } },
    "bodies": [ { "material": "rock", "outer": [[0,0],[1,0],[1,1],[0,1]] } ],
    "mesh": { "size": 0.5 } })";
  const SceneDef s = parse_scene(text, "jrc.json");
  const NormalLawDef& n = s.joint_sets[0].normal;
  EXPECT_EQ(n.model, NormalModel::bandis_barton);
  EXPECT_NEAR(n.aperture, 0.40e-3, 1e-6);
  EXPECT_NEAR(n.kni, 15.35e9, 0.01e9);  // GPa/m in docs/physics.md's worked example
  EXPECT_NEAR(n.vm, 0.2277e-3, 0.0005e-3);
}

// Two 2 m × 1 m bodies, one on the other; the base held along its bottom, the joint between
// them y = 1. Normal load: point loads along the top face; shear load: point loads along the
// joint 2 cm above it (as a shear box loads the whole face, with no overturning moment). Quasi-static (dynamic factor
// 0) until it settles. Returns the joint's closure and slip measured through the solver: the
// displacement jump between points 0.1 mm above and below the joint at its middle.
struct JointResult {
  double closure, slip;
  Outcome status;
};

SceneDef joint_scene(double sigma_n, double tau, double h) {
  // Rock far stiffer than the joint (500 GPa): the closed forms are about the joint alone, and
  // the point loads' own local deformation must not reach the measuring points.
  SceneDef s = reference::joint_specimen_scene(reference::seed_shear_joint(), 5e11, h);
  reference::load_joint_specimen(s, sigma_n, tau);
  return s;
}

JointResult load_joint(double sigma_n, double tau, double seconds) {
  const SceneDef s = joint_scene(sigma_n, tau, 0.25);
  const Mesh m = pre::build_mesh(s, "joint");
  const studies::JointSpecimenResult sr = studies::run_joint_specimen(m, s, seconds);
  JointResult r;
  r.status = sr.outcome;
  r.closure = sr.closure;
  r.slip = sr.slip;
  return r;
}

TEST(JointLaw, SingleJointNormalClosureThroughTheSolver) {
  const ContactLaw law = bb_law();
  for (double sigma : {1e6, 5e6, 10e6}) {
    const JointResult r = load_joint(sigma, 0, 0.3);
    ASSERT_PRED1(test::ended_ok, r.status);
    const double want = closure_of(sigma, law);
    std::printf("normal %4.0f MPa: closure %.4e m, Bandis-Barton %.4e m (%+.2f %%)\n", sigma / 1e6,
                r.closure, want, 100 * (r.closure - want) / want);
    EXPECT_NEAR(r.closure, want, 0.02 * want);
  }
}

TEST(JointLaw, SingleJointDirectShearThroughTheSolver) {
  const ContactLaw law = bb_law();
  const double sigma = 5e6, tf = sigma * law.tan_phi;
  for (double frac : {0.3, 0.6, 0.9}) {
    const double tau = frac * tf;
    const JointResult r = load_joint(sigma, tau, 0.4);
    ASSERT_PRED1(test::ended_ok, r.status);
    const double want = tau / (law.ksi * (1 - law.rf * tau / tf));
    std::printf("shear %2.0f %% of strength: slip %.4e m, hyperbola %.4e m (%+.2f %%)\n", 100 * frac,
                r.slip, want, 100 * (r.slip - want) / want);
    // Measured +0.23 / +0.17 / -0.03 % at the default contact_tolerance 1e-3 (+0.43 / +0.26 /
    // +0.12 % at 1e-4). Without the displacement tolerance (contact_solve.h) 1e-3 gave
    // -0.06 / -0.46 / -1.24 %: near its strength the joint is soft, and the force tolerance
    // alone let it stop short.
    // 1 %: a joint point whose contact passes to the other face's vertex must keep its elastic
    // shear (contact_set.cpp begin_step); when it started over with none, the slip came out
    // +1.7 / +1.3 / +0.6 %.
    EXPECT_NEAR(r.slip, want, 0.01 * want);
  }
  // Beyond the strength the joint slides: far more than the elastic slip at 90 %, and growing.
  const JointResult a = load_joint(sigma, 1.1 * tf, 0.2), b = load_joint(sigma, 1.1 * tf, 0.3);
  const double elastic90 = 0.9 * tf / (law.ksi * (1 - law.rf * 0.9));
  std::printf("shear 110 %%: slip %.3e m at 0.2 s, %.3e m at 0.3 s\n", a.slip, b.slip);
  EXPECT_GT(a.slip, 3 * elastic90);
  EXPECT_GT(b.slip, a.slip + 2 * elastic90) << "and it keeps sliding";
}

TEST(JointLaw, TheWholeJointCarriesTheLoadOnFineMeshes) {
  // The closed contacts' tributary lengths must add up to the joint's 2 m, so that σn·2 m is
  // carried at σn. At h = 0.0625 both corners of the joint (x = 0, 2) lost their contact in the
  // second step (sum 1.985 m, the joint's stress 0.75 % too high, the closure 0.35 % too large):
  // the pair of coincident corner vertices keeps one contact, the lower block's corner; Poisson
  // expansion moved it 0.16 µm outside the upper block, and the upper corner, sunk 0.13 mm, was
  // too deep to count as a new contact. Its mirror's history now counts as its own.
  const std::string path = std::string(NMM_SOURCE_DIR) + "/data/single_joint.json";
  for (double h : {0.25, 0.125, 0.0625}) {
    SceneDef s = parse_scene(read_text_file(path), path);  // Kni, Vm from JRC, JCS, σc
    s.mesh_size = h;
    const Mesh m = pre::build_mesh(s, "joint");
    TimeStepper st(m, s, "joint");
    ASSERT_PRED1(test::ended_ok, st.run_until(0.01, [](std::int64_t) {}));
    double length = 0, force = 0;
    for (const Contact& c : st.view().contacts.contacts())
      if (c.state != ContactState::open) {
        length += c.length;
        force += c.normal_force;
      }
    std::printf("h = %g m: closed contacts cover %.6f m of the joint, carry %.6g N (load 1e7 N)\n",
                h, length, force);
    EXPECT_NEAR(length, 2.0, 1e-4) << "h = " << h;
    EXPECT_NEAR(force, 5e6 * 2.0, 0.01 * 5e6 * 2.0) << "h = " << h;
  }
}

}  // namespace
}  // namespace nmm::solve
