// NMM time stepping (Shi's implicit scheme) on a loaded mesh: see time_stepper.cpp.
//
// The interface is the run's phases: build (the constructor), start from a checkpoint
// (restart_from, restore), take steps (attempt, step, run_until), and read (view(): what the
// outputs read, run_view.h). Test and bench hooks into assembly and update are
// TimeStepperProbe's (time_stepper_probe.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/mesh.h"
#include "common/outcome.h"
#include "common/scene.h"
#include "solver/stepping/block_momentum.h"
#include "solver/discretisation/configuration.h"
#include "solver/contact/contact_problem.h"
#include "solver/contact/contact_set.h"
#include "solver/contact/contact_solve.h"
#include "solver/discretisation/cover_space.h"
#include "solver/stepping/equilibrium_indicator.h"
#include "solver/discretisation/form.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"
#include "solver/stepping/run_view.h"
#include "solver/stepping/step_control.h"
#include "solver/stepping/step_timings.h"
#include "solver/discretisation/system_matrix.h"
#include "solver/reinforcement/bolt_system.h"

namespace nmm::solve {

class TimeStepper {
 public:
  /// Prepares a run: locates the scene's points in the elements (InputError naming the scene
  /// path, e.g. /fixed_points/2, for a point outside every body), builds the sparsity pattern,
  /// applies the scene's excavate. `scene_name` names the scene in such errors.
  TimeStepper(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name);
  // The contacts hold the model and the space by reference: a stepper stays where it was built.
  TimeStepper(const TimeStepper&) = delete;
  TimeStepper& operator=(const TimeStepper&) = delete;

  /// Asked before every step: true stops the run, interrupted (interrupt.h).
  void set_stop_check(std::function<bool()> f) { stop_check_ = std::move(f); }
  /// Threads of the factorisation's dense kernels (solver_threads.h); 0: the default for the
  /// problem size (one thread below 150k unknowns).
  void set_threads(int threads);

  // ---- start ------------------------------------------------------------------------------
  /// Continues from a checkpoint (InputError naming `path` if it is damaged or of another mesh),
  /// then applies the scene's `excavate` (restart.h). Call before stepping.
  void restart_from(const std::string& path);
  /// Continues from a state and contact history in memory; `name` names them in errors.
  void restore(const RunState& state, const std::string& contact_history, const std::string& name);

  // ---- steps ------------------------------------------------------------------------------
  /// Tries one step of length dt; on success the state moves on and ok is returned, otherwise
  /// the state is left as it was and the outcome says why (common/outcome.h: the caller cuts dt
  /// and retries where cured_by_shorter_step(), and stops otherwise).
  Outcome attempt(double dt);
  /// One step of length dt. Throws RunError when it cannot be taken.
  void step(double dt);
  /// Steps until simulated time t_end (s) with step control, calling on_step(n) after the n-th
  /// accepted step. Returns ok (also when solver.stop_at_ratio is met), interrupted (the stop
  /// check said so), or why the run cannot go on: what no shorter step cures, or what step
  /// control cut to its floor (the reason says so).
  Outcome run_until(double t_end, const std::function<void(std::int64_t)>& on_step);

  // ---- read -------------------------------------------------------------------------------
  /// What the outputs read: state, model, space, contacts, system, costs (run_view.h).
  RunView view() const {
    return {mesh_,    model_,       space_,       config_,  s_,
            contacts_, system_,     timings_,     solve_stats_, balance_,
            stopped_at_ratio_, threads_};
  }

 private:
  friend class TimeStepperProbe;  // test and bench hooks (time_stepper_probe.h)

  Outcome compute_frames();
  /// A stop of this attempt: the code and reason at the current state's time.
  Outcome stop(StopCode code, std::string reason) const;
  /// The context of a step of dt from the current state (step_context.h).
  StepContext step_context(double dt) const;
  void update_pattern();
  /// The equilibrium indicators of the step just solved (increment d of length dt), before
  /// update() moves the state on.
  void measure_balance(const Eigen::VectorXd& d, const StepContext& step, bool contact);
  /// Solves the assembled step (rhs_, system_): one factorisation, or the step's contact
  /// problem with its breaks; `again`: the same step solved again from d (the bolts' modes
  /// changed at its solution). Sets d, the residual handed on and whether Newton iterated.
  Outcome solve_step(bool contact, bool again, Eigen::VectorXd& d, Eigen::VectorXd& residual, bool& iterated);
  /// Takes the absorbing boundaries' carried reaction from the state the step starts from
  /// (absorbing_boundary.h): its out-of-balance force with d = 0, without inertia.
  void take_absorbing_reaction(bool contact);
  /// The bolts of the run's scene on state s_ (installed now or carried on), their unknowns
  /// numbered and the pattern built with their groups.
  void place_bolts(const std::vector<BoltState>& previous);
  /// The system's first contact-pair group: after the elements' and the bolts' groups.
  int first_pair_group() const { return static_cast<int>(mesh_.element_count() + bolts_.groups()); }
  /// Unknowns of the system: the covers', then the bolts' own (bolt_system.h).
  int system_unknowns() const { return space_.unknowns() + bolts_.unknowns(); }
  /// The step's matrix has the inertia term: dynamic runs and DDA static ones.
  bool step_inertia() const { return model_.step_inertia(); }
  /// –, the share of a step's momentum the next step keeps: solver.dynamic_factor in a dynamic
  /// run, 0 in a static one (block_momentum.h hands on that share of the residual).
  double handed_on_share() const { return scene_.solver.dynamic ? scene_.solver.dynamic_factor : 0.0; }
  void build_pattern_with_pairs();
  /// Polynomial stress coefficients per element: (n+1)(n+2)/2.
  std::size_t stress_terms() const { return static_cast<std::size_t>(space_.terms()); }
  /// ε of the regularised factorisation (system_matrix.h), relative to each diagonal entry.
  static constexpr double kRegularisation = 1e-10;
  /// Removes bodies (excavation) at the current step: excavation.h.
  void excavate(const std::vector<int>& bodies);
  void apply_removed();

  const Mesh& mesh_;
  const SceneDef& scene_;
  std::string scene_name_;
  Model model_;                         // derived once from mesh and scene (model.h)
  Form form_;                           // the integrators the scene calls for (form.h)
  StepControl control_;                 // Shi's step control (step_control.h)
  CoverSpace space_;                    // order, unknowns of each cover and element, shapes
  Configuration config_;                // the space on the step's cover positions: frames, bases
  RunState s_;                          // everything a step carries to the next
  BoltSystem bolts_;                    // the bolts' unknowns, groups and each step's springs
  bool bolts_renumbered_ = false;       // a restart installed bolts: its FACTOR is of another size
  std::vector<std::uint8_t> removed_elem_;      // [me] 1: its body is excavated

  Eigen::VectorXd rhs_;
  SystemMatrix system_;
  StepTimings timings_;
  // Contact and step control.
  ContactSet contacts_;             // detection and the history carried between steps
  ContactProblem problem_;          // the step's rows and Newton kernels (contact_problem.h)
  Eigen::VectorXd rhs_base_;     // right-hand side without contacts
  std::function<bool()> stop_check_;                     // interrupt.h
  ContactSolveStats solve_stats_;   // what the contact solves cost (contact_solve.h)
  int threads_ = 1;                 // of the factorisation (solver_threads.h)
  EquilibriumIndicator indicator_;  // lumped cover masses (derived from the mesh: no run state)
  BlockMomentum momentum_;          // each block's covers and mass shares (block_momentum.h)
  EquilibriumSample balance_;       // of the last accepted step (diagnostics, not state)
  bool stopped_at_ratio_ = false;
};

}  // namespace nmm::solve
