// Test and bench hooks into a TimeStepper's assembly and update, kept off its public surface
// (time_stepper.h): the patch test imposes cover displacements and reads the next step's
// right-hand side; a bench solves the last step's system with a bare factorisation; tests read
// the last attempt's contact rows.
#pragma once

#include <Eigen/Dense>

#include "solver/stepping/state_update.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::solve {

class TimeStepperProbe {
 public:
  /// Imposes cover displacements d as a step would (stresses and geometry follow), in the
  /// frames of the current configuration.
  static void impose_displacement(TimeStepper& st, const Eigen::VectorXd& d) {
    st.compute_frames();
    update_state(st.b_->model, st.step_context(1.0), d, st.s_);
  }
  /// Assembles a step of dt from the current state and returns its right-hand side
  /// −F_int (+ loads, gravity, inertia), N.
  static const Eigen::VectorXd& assemble_rhs(TimeStepper& st, double dt) {
    st.compute_frames();
    st.b_->form.assemble(st.step_context(dt), st.system_, st.rhs_);
    return st.rhs_;
  }
  /// The right-hand side of the last assembly, N.
  static const Eigen::VectorXd& rhs(const TimeStepper& st) { return st.rhs_; }
  /// The last attempt's contact problem: its rows, working values and what it left outside the
  /// sparse pattern (contact_problem.h).
  static const ContactProblem& contact_problem(const TimeStepper& st) { return st.b_->contact.problem(); }
  /// Keeps the factor in single precision from `from` unknowns (system_matrix.h; a run does so
  /// from kSingleFactorUnknowns, larger than a test's scenes), until the effects are numbered again.
  static void set_single_precision(TimeStepper& st, int from) { st.system_.set_single_precision(from); }
};

}  // namespace nmm::solve
