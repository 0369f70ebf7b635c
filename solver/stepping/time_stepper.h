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
#include "preprocess/recut.h"
#include "solver/discretisation/effect.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/step_timings.h"
#include "solver/discretisation/system_matrix.h"
#include "solver/fracture/step_start.h"
#include "solver/stepping/equilibrium_indicator.h"
#include "solver/stepping/mesh_bound.h"
#include "solver/stepping/run_view.h"
#include "solver/stepping/step_control.h"

namespace nmm::solve {

class TimeStepper : private StepHost {
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
    return {*mesh_,  b_->model, b_->space, b_->config, s_, b_->contact.set(), system_, timings_, b_->contact.stats(),
            balance_, stopped_at_ratio_, threads_, topology_, recut_, recut_from_, recut_start_, recut_start_work_,
            b_->effects, changes_.list, b_->checkpointed, b_->metered};
  }

 private:
  friend class TimeStepperProbe;  // test and bench hooks (time_stepper_probe.h)

  Outcome compute_frames();
  /// A stop of this attempt: the code and reason at the current state's time.
  Outcome stop(StopCode code, std::string reason) const;
  /// The context of a step of dt from the current state (step_context.h).
  StepContext step_context(double dt) const;
  /// What the effects see of a stage of the attempt in `context` (effect.h).
  EffectStep effect_step(const StepContext& context);
  /// Solves the assembled step (rhs_, system_): one factorisation, or `solver`'s own way (the
  /// contacts' problem); `again`: the same step solved again from x.d (an effect judged its
  /// solution). Sets x.
  Outcome solve_step(EffectStep& step, Effect* solver, bool again, StepSolution& x);
  /// StepHost: the force at rest of s_ (effect.h).
  const Eigen::VectorXd& force_at_rest() override;
  /// N/m per cover unknown: force_at_rest of the state, but for the effect that solves the step
  /// (the contacts), whose state it leaves as it is (recut_start_work_).
  Eigen::VectorXd force_at_rest_of_loads();
  /// force_at_rest (with_solver) or force_at_rest_of_loads (without the solving effect), in rhs_.
  const Eigen::VectorXd& assemble_at_rest(bool with_solver);
  /// The effects installed or carried on from s_ (a start, a restart), numbered, and the pattern
  /// built with their groups (`name`: the scene's or checkpoint's, for errors); false: an effect's
  /// unknowns no longer fit a checkpoint's factorisation.
  bool place_effects(const std::string& name);
  /// Numbers the effects on s_ and builds the pattern with their groups.
  void number_effects();
  /// The step's matrix has the inertia term: dynamic runs and DDA static ones.
  bool step_inertia() const { return b_->model.step_inertia(); }
  /// –, the share of a step's momentum the next step keeps: solver.dynamic_factor in a dynamic
  /// run, 0 in a static one (block_momentum.h hands on that share of the residual).
  double handed_on_share() const { return scene().solver.dynamic ? scene().solver.dynamic_factor : 0.0; }
  /// The sparse pattern of the elements' and the effects' coupling groups on s_.
  void build_pattern();
  /// Polynomial stress coefficients per element: (n+1)(n+2)/2.
  std::size_t stress_terms() const { return static_cast<std::size_t>(b_->space.terms()); }
  /// ε of the regularised factorisation (system_matrix.h), relative to each diagonal entry.
  static constexpr double kRegularisation = 1e-10;
  /// Removes bodies (excavation) at the current step: excavation.h.
  void excavate(const std::vector<int>& bodies);
  void apply_removed();
  /// One attempt of a step of dt (attempt() repeats it while an effect changes the mesh).
  Outcome attempt_once(double dt);
  /// One attempt looking `reach` (m) far for open contacts; `redo` > 0 (m): the attempt moved a
  /// loop vertex more than half that, and is to be taken again from its start looking `redo` far
  /// (step_control.h, the reach).
  Outcome attempt_reaching(double dt, double reach, double& redo);
  /// The run goes on on the new mesh `m` an effect made at a step's solution (mesh_change.h), s_
  /// already carried onto it (the step's start): what is derived from the mesh is built again and
  /// the observers' map of the step's re-cuts composed.
  void change_mesh(NewMesh m);
  /// mesh_ and scene_ become `mesh` and `scene` (owned), and what is derived from them is built
  /// again, with the contact history `history`. The caller carries the state s_ onto the new
  /// mesh (or restores it) and then applies the removed elements; with `map` (a re-cut: s_ is
  /// the step's start already carried by it) the effects carry their own parts of s_ over
  /// (Effect::carry_over: a bolt's ties, the absorbing boundaries' reaction).
  void replace_mesh(std::unique_ptr<Mesh> mesh, std::unique_ptr<SceneDef> scene,
                    std::vector<ContactHistory> history, const pre::RecutMap* map = nullptr);

  const Mesh& mesh() const { return *mesh_; }
  const SceneDef& scene() const { return *scene_; }

  const Mesh* mesh_;                    // the run's mesh: the file's, or own_mesh_ once changed
  const SceneDef* scene_;               // the run's scene: the given one, or own_scene_ once changed
  std::string scene_name_;
  std::unique_ptr<Mesh> own_mesh_;      // the changed mesh (null: mesh_ is the file's)
  std::unique_ptr<SceneDef> own_scene_; // the scene with the joints a change added (null: none yet)
  std::unique_ptr<MeshBound> b_;        // derived from mesh_ and scene_
  MeshChanges changes_;                 // the effects that change the mesh (mesh_bound.h)
  StepStart step_start_;                // the step's start, to take it again on a new mesh (step_start.h)
  std::size_t topology_ = 0;            // re-cuts so far (RunView::topology)
  // The re-cuts of the step being taken (RunView::recut): the map from the mesh now back to the
  // mesh at the last accepted step, composed over every re-cut since (a step may re-cut several
  // times, and a step cut shorter keeps the changes its longer attempt made); recut_from_ is that
  // mesh's topology_, recut_step_ the accepted steps (s_.step) the composition started at, and
  // recut_start_ the state the step starts from, carried onto the mesh now.
  pre::RecutMap recut_;
  std::size_t recut_from_ = 0;
  std::int64_t recut_step_ = -1;
  RunState recut_start_;
  // J/m, r·d of the last attempt on a mesh re-cut within its step (RunView::recut_start_work):
  // r what the cut opened of the force its start, carried onto the cut mesh, is out of balance
  // by (crack_release.h cut_release_force), d the attempt's solution; 0 before any re-cut.
  double recut_start_work_ = 0;
  StepControl control_;                 // Shi's step control (step_control.h)
  RunState s_;                          // everything a step carries to the next
  bool factor_fits_ = true;             // false: a restart installed effects' unknowns, its FACTOR is of another size
  std::vector<std::uint8_t> removed_elem_;      // [me] 1: its body is excavated

  Eigen::VectorXd rhs_;
  // The start guess of the next attempt, by cover of the mesh now (dofs_per_cover each): the
  // solution of the same step on the mesh before a re-cut, each new cover its parent's
  // increment (as transfer_state carries the state); empty: none (attempt_once starts from 0).
  std::vector<double> carried_;
  Eigen::VectorXd solved_d_;     // the last attempt's solution, in unknown order (a re-cut carries it)
  Eigen::VectorXd start_force_;  // N/m, r of the attempt on a re-cut mesh (recut_start_work_)
  SystemMatrix system_;
  StepTimings timings_;
  std::function<bool()> stop_check_;                     // interrupt.h
  int threads_ = 1;                 // of the factorisation (solver_threads.h)
  EquilibriumSample balance_;       // of the last accepted step (diagnostics, not state)
  bool stopped_at_ratio_ = false;
};

}  // namespace nmm::solve
