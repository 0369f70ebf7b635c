// NMM time stepping (Shi's implicit scheme) on a loaded mesh: see time_stepper.cpp.
//
// The interface is the run's phases: build (the constructor), start from a checkpoint
// (restart_from, restore), take steps (attempt, step, run_until), and read (view(): what the
// outputs read, run_view.h). Test and bench hooks into assembly and update are
// TimeStepperProbe's (time_stepper_probe.h).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
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
#include "solver/fracture/fracture.h"
#include "solver/fracture/step_start.h"
#include "preprocess/recut.h"
#include "solver/discretisation/system_matrix.h"
#include "solver/reinforcement/bolt_system.h"

namespace nmm::solve {

class TimeStepper {
 public:
  /// Prepares a run: locates the scene's points in the elements (InputError naming the scene
  /// path, e.g. /fixed_points/2, for a point outside every body), builds the sparsity pattern,
  /// applies the scene's excavate. `scene_name` names the scene in such errors.
  TimeStepper(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name);
  // Derived objects hold references into the stepper's mesh and scene: it stays where it was built.
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
  /// accepted step, and after `max_steps` accepted steps at the most (< 0: no limit). Returns ok
  /// (also when solver.stop_at_ratio is met or max_steps are taken), interrupted (the stop
  /// check said so), or why the run cannot go on: what no shorter step cures, or what step
  /// control cut to its floor (the reason says so).
  Outcome run_until(double t_end, const std::function<void(std::int64_t)>& on_step,
                    std::int64_t max_steps = -1);

  // ---- read -------------------------------------------------------------------------------
  /// What the outputs read: state, model, space, contacts, system, costs (run_view.h).
  RunView view() const {
    return {*mesh_,      b_->model,  b_->space,    b_->config,   s_,
            b_->contacts, system_,   timings_,     solve_stats_, balance_,
            stopped_at_ratio_, threads_, fracture_, topology_, recut_, recut_from_, recut_start_};
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
  int first_pair_group() const { return static_cast<int>(mesh().element_count() + b_->bolts.groups()); }
  /// Unknowns of the system: the covers', then the bolts' own (bolt_system.h).
  int system_unknowns() const { return b_->space.unknowns() + b_->bolts.unknowns(); }
  /// The step's matrix has the inertia term: dynamic runs and DDA static ones.
  bool step_inertia() const { return b_->model.step_inertia(); }
  /// –, the share of a step's momentum the next step keeps: solver.dynamic_factor in a dynamic
  /// run, 0 in a static one (block_momentum.h hands on that share of the residual).
  double handed_on_share() const { return scene().solver.dynamic ? scene().solver.dynamic_factor : 0.0; }
  void build_pattern_with_pairs();
  /// Polynomial stress coefficients per element: (n+1)(n+2)/2.
  std::size_t stress_terms() const { return static_cast<std::size_t>(b_->space.terms()); }
  /// ε of the regularised factorisation (system_matrix.h), relative to each diagonal entry.
  static constexpr double kRegularisation = 1e-10;
  /// Removes bodies (excavation) at the current step: excavation.h.
  void excavate(const std::vector<int>& bodies);
  void apply_removed();
  /// One attempt of a step of dt (attempt() repeats it while the rock breaks).
  Outcome attempt_once(double dt);
  /// The segments a step's solution breaks (fracture.h) are cut into the mesh
  /// (preprocess/recut.h), the state s_ (the step's start) and the contact history `history` (of
  /// the step's start) are carried over (state_transfer.h) and what is derived from the mesh is
  /// built again.
  void break_rock(const std::vector<CrackSegment>& segments, std::vector<ContactHistory> history);
  /// mesh_ and scene_ become `mesh` and `scene` (owned), and what is derived from them is built
  /// again, with the contact history `history`. The state s_ is not touched: the caller carries
  /// it onto the new mesh (or restores it) and then applies the removed elements.
  void replace_mesh(std::unique_ptr<Mesh> mesh, std::unique_ptr<SceneDef> scene,
                    std::vector<ContactHistory> history);

  /// What is derived from the mesh and the scene: built with the stepper, and again when cracks
  /// change the mesh (the members hold references to each other and to mesh and scene, so the
  /// whole is replaced at once).
  struct MeshBound {
    /// `cracks`: how many of the scene's joints (its last ones) are cracks grown in the run.
    MeshBound(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name, std::size_t cracks = 0);
    Model model;                      // derived once from mesh and scene (model.h)
    Form form;                        // the integrators the scene calls for (form.h)
    CoverSpace space;                 // order, unknowns of each cover and element, shapes
    Configuration config;             // the space on the step's cover positions: frames, bases
    EquilibriumIndicator indicator;   // lumped cover masses (derived from the mesh: no run state)
    BlockMomentum momentum;           // each block's covers and mass shares (block_momentum.h)
    ContactSet contacts;              // detection and the history carried between steps
    ContactProblem problem;           // the step's rows and Newton kernels (contact_problem.h)
    BoltSystem bolts;                 // the bolts' unknowns, groups and each step's springs
  };
  const Mesh& mesh() const { return *mesh_; }
  const SceneDef& scene() const { return *scene_; }

  const Mesh* mesh_;                    // the run's mesh: the file's, or own_mesh_ once cracked
  const SceneDef* scene_;               // the run's scene: the given one, or own_scene_ once cracked
  std::string scene_name_;
  std::unique_ptr<Mesh> own_mesh_;      // the cracked mesh (null: mesh_ is the file's)
  std::unique_ptr<SceneDef> own_scene_; // the scene with the crack joints (null: none yet)
  std::unique_ptr<MeshBound> b_;        // derived from mesh_ and scene_
  Fracture fracture_;                   // cracks so far and their tips (fracture.h)
  StepStart step_start_;                // a cracking run's step start, to take the step again (step_start.h)
  /// Re-cuts one attempt of a step may make before it is cut (attempt): a shorter step breaks
  /// fewer elements at once. The uniaxial specimen of docs/fracture.md's matrix took up to 54 at
  /// its peak; a bound far above that only stops a cascade that a shorter step would spread.
  static constexpr int kMaxRecutsPerStep = 200;
  /// With NMM_TRACE_PEN set: what a rejected step moved most and its deepest contacts, on stderr.
  void trace_rejected_step(const Eigen::VectorXd& covers_d, double max_penetration) const;
  std::size_t topology_ = 0;            // re-cuts so far (RunView::topology)
  // The re-cuts of the step being taken (RunView::recut): the map from the mesh now back to the
  // mesh at the last accepted step, composed over every re-cut since (a step may re-cut several
  // times, and a step cut shorter keeps the cracks its longer attempt cut); recut_from_ is that
  // mesh's topology_, recut_step_ the accepted steps (s_.step) the composition started at, and
  // recut_start_ the state the step starts from, carried onto the mesh now.
  pre::RecutMap recut_;
  std::size_t recut_from_ = 0;
  std::int64_t recut_step_ = -1;
  RunState recut_start_;
  StepControl control_;                 // Shi's step control (step_control.h)
  RunState s_;                          // everything a step carries to the next
  bool bolts_renumbered_ = false;       // a restart installed bolts: its FACTOR is of another size
  std::vector<std::uint8_t> removed_elem_;      // [me] 1: its body is excavated

  Eigen::VectorXd rhs_;
  SystemMatrix system_;
  StepTimings timings_;
  Eigen::VectorXd rhs_base_;     // right-hand side without contacts
  std::function<bool()> stop_check_;                     // interrupt.h
  ContactSolveStats solve_stats_;   // what the contact solves cost (contact_solve.h)
  int threads_ = 1;                 // of the factorisation (solver_threads.h)
  EquilibriumSample balance_;       // of the last accepted step (diagnostics, not state)
  bool stopped_at_ratio_ = false;
};

}  // namespace nmm::solve
