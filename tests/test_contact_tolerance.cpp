// The contact solve's force tolerance (solver.contact_tolerance, docs/contact.md "Tolerance and
// error"): a looser tolerance costs fewer Newton iterations and leaves the sliding block on
// Coulomb's answer; what the tolerance allowed is reported in forces and in gap.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "preprocess/cover_cutter.h"
#include "common/math_constants.h"
#include "reference/joint_specimen.h"
#include "reference/scene_pieces.h"
#include "reference/sliding_block.h"
#include "solver/contact_solve.h"
#include "solver/time_stepper.h"

namespace nmm::solve {
namespace {

struct Slide {
  double along = 0;         ///< m, slide of the block's centre after 1 s
  long newton = 0;          ///< Newton iterations of the run
  double force_tol = 0;     ///< N, largest F_tol used
  double gap_error = 0;     ///< m, largest F_tol/kn
  double max_force = 0;     ///< N, largest contact force at the end
  double u_error = 0;       ///< m, largest estimated displacement error of an accepted step
  long checks = 0;          ///< displacement estimates made
};

Slide slide(double tau) {
  // The sliding block of the contact tests: gravity tilted 30°, φ = 20°, kn = 2e11 N/m.
  SceneDef s = reference::sliding_block_tilted(30, 20);
  s.solver.contact_tolerance = tau;
  const Mesh m = pre::build_mesh(s, "tilted");
  TimeStepper st(m, s, "tilted");
  EXPECT_EQ(st.run_until(1.0, [](std::int64_t) {}), "ok");
  Slide r;
  r.along = st.view().state.measure[0].displacement()[0];
  r.newton = st.view().contact_solve.newton;
  r.force_tol = st.view().contact_solve.max_force_tolerance;
  r.gap_error = st.view().contact_solve.max_gap_error;
  r.u_error = st.view().contact_solve.max_displacement_error;
  r.checks = st.view().contact_solve.displacement_checks;
  for (const Contact& c : st.view().contacts.contacts())
    r.max_force = std::max({r.max_force, std::abs(c.normal_force), std::abs(c.shear_force)});
  return r;
}

TEST(ContactTolerance, LooserIsCheaperAndStaysOnCoulomb) {
  const double want = reference::sliding_distance(30, 20, 1.0);
  const Slide tight = slide(1e-8), loose = slide(1e-3);
  std::printf("tau 1e-8: slid %.6f m (%+.4f %%), %ld Newton; tau 1e-3: slid %.6f m (%+.4f %%), %ld Newton\n",
              tight.along, 100 * (tight.along - want) / want, tight.newton, loose.along,
              100 * (loose.along - want) / want, loose.newton);
  // Both on Coulomb's answer within the contact tests' 0.1 %, and on each other within 0.01 %.
  EXPECT_NEAR(tight.along, want, 1e-3 * want);
  EXPECT_NEAR(loose.along, want, 1e-3 * want);
  EXPECT_NEAR(loose.along, tight.along, 1e-4 * want);
  // The tolerance is what the loop stops on: the loose run needs clearly fewer iterations.
  EXPECT_LT(loose.newton, 0.8 * tight.newton);
  // Reported: F_tol = τ × the largest contact force (the block's weight share on a corner, a few
  // 10 kN), and F_tol/kn with kn = 2e11 N/m.
  EXPECT_GT(loose.force_tol, 0.5e-3 * loose.max_force);
  EXPECT_LT(loose.force_tol, 2e-3 * loose.max_force);
  EXPECT_NEAR(loose.gap_error, loose.force_tol / 2e11, 1e-3 * loose.force_tol / 2e11);
  // A constant spring's error is bounded by F_tol/kn (above): no displacement test is made.
  EXPECT_EQ(loose.checks, 0);
  EXPECT_EQ(loose.u_error, 0);
  // τ = 1e-8 is 1e-5 of the loose one, but the tolerance has a round-off floor (1e-12 of the
  // largest load, here the inertia term): still far below.
  EXPECT_LT(tight.force_tol, 1e-4 * loose.force_tol);
}

TEST(ContactTolerance, ASofteningJointIsCheckedInDisplacement) {
  // The joint of the seed paper's direct shear (hyperbolic shear, Rf = 0.9) loaded to 90 % of
  // its strength: its tangent is (1 − 0.9·0.9)² = 3.6 % of Ksi, so F_tol moves it 28 times as far
  // as on its initial stiffness. The solve must check the displacement, refuse iterates over
  // 3e-4·τ·w0, and accept none over it.
  SceneDef s = reference::joint_specimen_scene(reference::seed_shear_joint(), 5e11, 0.25);
  reference::load_joint_specimen(s, 5e6, 0.9 * 5e6 * std::tan(30 * kPi / 180));
  s.solver.contact_tolerance = 1e-3;
  const Mesh m = pre::build_mesh(s, "joint");
  TimeStepper st(m, s, "joint");
  ASSERT_EQ(st.run_until(0.1, [](std::int64_t) {}), "ok");
  const ContactSolveStats& cs = st.view().contact_solve;
  const double u_tol = displacement_tolerance(1e-3, st.view().model.w0());
  std::printf("checks %ld, refused %ld, largest accepted %.3e m, tolerance %.3e m\n", cs.displacement_checks,
              cs.displacement_refusals, cs.max_displacement_error, u_tol);
  EXPECT_GT(cs.displacement_checks, 0);
  EXPECT_GT(cs.displacement_refusals, 0) << "the force test alone would have stopped short here";
  EXPECT_GT(cs.max_displacement_error, 0);
  EXPECT_LE(cs.max_displacement_error, u_tol);
}

}  // namespace
}  // namespace nmm::solve
