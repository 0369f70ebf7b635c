// NMM time stepping (Shi's implicit scheme) on a loaded mesh: see time_stepper.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "solver/element_integration.h"
#include "solver/contact.h"
#include "solver/configuration.h"
#include "solver/contact_solve.h"
#include "solver/cover_space.h"
#include "solver/cover_unknowns.h"
#include "solver/elasticity.h"
#include "solver/equilibrium_indicator.h"
#include "solver/joint_water.h"
#include "common/mesh.h"
#include "solver/model.h"
#include "solver/boundary_conditions.h"
#include "solver/run_effects.h"
#include "solver/run_state.h"
#include "common/scene.h"
#include "solver/step_control.h"
#include "solver/stress_field.h"
#include "solver/system_matrix.h"

namespace nmm::solve {


/// Seconds spent per part of the run.
struct StepTimings {
  double contact_detection = 0;
  double assembly = 0;
  double factorisation = 0;
  double solves = 0;
  double geometry_update = 0;  ///< stresses, loop vertices, covers and points moved after a solve
  double output = 0;
  long factorisations = 0;     ///< numeric factorisations of the system matrix
  long solves_count = 0;       ///< triangular solve pairs (direct solves and preconditioner applications)
};

class TimeStepper {
 public:
  /// Prepares a run: locates the scene's points in the elements (InputError naming the scene
  /// path, e.g. /fixed_points/2, for a point outside every body), builds the sparsity pattern.
  /// `scene_name` names the scene in such errors.
  TimeStepper(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name);
  // The contacts hold the model and the space by reference: a stepper stays where it was built.
  TimeStepper(const TimeStepper&) = delete;
  TimeStepper& operator=(const TimeStepper&) = delete;

  /// Asked before every step: true stops the run with status "interrupted" (interrupt.h).
  void set_stop_check(std::function<bool()> f) { stop_check_ = std::move(f); }
  /// Threads of the factorisation's dense kernels (solver_threads.h); 0: the default for the
  /// problem size (one thread below 150k unknowns).
  void set_threads(int threads);
  /// Threads the factorisation uses (summary.json "threads").
  int threads() const { return threads_; }

  // ---- state, for tests ------------------------------------------------------------------
  /// One step of length dt. Throws RunError when it cannot be taken.
  void step(double dt);
  /// Steps until simulated time t_end (s) with step control, calling on_step(n) after the n-th
  /// accepted step. Returns "ok" or the reason the run cannot go on.
  std::string run_until(double t_end, const std::function<void(std::int64_t)>& on_step);
  /// Tries one step of length dt; on success the state moves on and "" is returned, otherwise
  /// the state is left as it was and the reason is returned (the caller cuts dt and retries).
  /// Throws RunError for what no smaller step can cure.
  std::string attempt(double dt);
  /// [m·pc] m, m = space().dofs_per_cover(): cover-function coefficients (n = 0: u, v)
  const std::vector<double>& cover_displacement() const { return s_.cover_u; }
  const std::vector<double>& velocity() const { return s_.velocity; }  ///< [m·pc] m/s, likewise
  /// [3·T·me] Pa σxx σyy τxy: per element, T = (n+1)(n+2)/2 polynomial coefficients of the
  /// stress in the element's scaled frame coordinates (n = 0: the element's constant stress)
  const std::vector<double>& stress() const { return s_.stress; }
  /// [3·me] Pa, the mean stress of each element (∫σ dA / A; n = 0: stress() itself)
  std::vector<double> mean_stress() const { return solve::mean_stress(mesh_, space_, s_); }
  /// Stress (Pa, σxx σyy τxy) of element e at the point (x, y) of its current configuration.
  std::array<double, 3> stress_at(std::size_t e, double x, double y) const {
    return solve::stress_at(mesh_, space_, s_, e, x, y);
  }
  const std::vector<double>& loop_xy() const { return s_.loop_xy; }              ///< [2·v] m
  const std::vector<TrackedPoint>& measure_points() const { return s_.measure; }
  /// Displacement of a point (x, y) of element e in its current configuration, m.
  std::array<double, 2> displacement_at(const TrackedPoint& p) const;
  double time() const { return s_.time; }
  /// Test hooks for the patch test: impose cover displacements d (as a step would, stresses and
  /// geometry follow), and the right-hand side −F_int (+ loads, gravity) of the next step.
  void impose_displacement(const Eigen::VectorXd& d);
  const Eigen::VectorXd& assemble_rhs(double dt);
  const StepTimings& timings() const { return timings_; }
  /// The physical effects this run computes (summary.json "effects").
  std::vector<std::string> effects() const { return run_effects(model_, s_, contacts_); }
  /// dofs_per_cover per independent cover: sliver covers share a neighbour's (cover_unknowns.cpp).
  int unknowns() const { return space_.unknowns(); }
  const CoverUnknowns& cover_unknowns() const { return space_.ties(); }
  /// The approximation space: order, unknowns per cover, shape functions (cover_space.h).
  const CoverSpace& space() const { return space_; }
  /// The space placed on the cover positions at the start of the last step (configuration.h).
  const Configuration& configuration() const { return config_; }
  /// The mesh the run steps on.
  const Mesh& mesh() const { return mesh_; }
  std::size_t symbolic_analyses() const { return system_.analyses(); }
  const ContactSet& contacts() const { return contacts_; }
  std::size_t open_close_iterations() const { return static_cast<std::size_t>(s_.iterations); }
  /// What the contact solves of the run have cost so far (summary.json "contact_solve").
  const ContactSolveStats& contact_solve_stats() const { return solve_stats_; }
  std::size_t time_step_cuts() const { return static_cast<std::size_t>(s_.cuts); }
  double max_penetration() const { return s_.max_penetration; }
  /// What the run derived once from the mesh and the scene (model.h: penalty stiffnesses, w0,
  /// water...): shared with the energy meter (energy.h) and the contacts.
  const Model& model() const { return model_; }
  /// The system of the last step (for benchmarks comparing against a bare factorisation).
  const SystemMatrix& system() const { return system_; }
  const Eigen::VectorXd& rhs() const { return rhs_; }

  // ---- run state, checkpoints and stages (run_state.h) -----------------------------------
  /// The whole state a next step starts from (the contact history aside: contact_history()).
  const RunState& state() const { return s_; }
  /// Bytes of the contact history (contact_history.h).
  std::string contact_history() const;
  /// SHA-256 (hex) of the physical state and contact history: equal hashes, equal states.
  std::string state_hash() const;
  /// Writes the state to `path` atomically (checkpoint.nmmstate); safe to call between steps,
  /// e.g. from an interrupt handler's deferred path.
  void write_checkpoint(const std::string& path) const;
  /// Continues from a checkpoint (InputError naming `path` if it is damaged or of another mesh),
  /// then applies the scene's `excavate`. Call before run().
  void restart_from(const std::string& path);
  /// Continues from a state in memory (tests).
  void restore(const RunState& state, const std::string& contact_history, const std::string& name);
  /// Removes bodies (excavation) at the current step: excavation.h.
  void excavate(const std::vector<int>& bodies);
  /// Steps the run has completed since step 0 of its first stage.
  std::int64_t step_count() const { return s_.step; }
  /// The equilibrium indicators of the last accepted step (equilibrium_indicator.h).
  const EquilibriumSample& equilibrium() const { return balance_; }
  /// The last run_until stopped because solver.stop_at_ratio was met.
  bool stopped_at_ratio() const { return stopped_at_ratio_; }

 private:
  void compute_frames();
  void assemble(double dt);
  void update_pattern();
  void update(const Eigen::VectorXd& d, double dt);
  /// The equilibrium indicators of the step just solved (increment d of length dt), before
  /// update() moves the state on.
  void measure_balance(const Eigen::VectorXd& d, double dt, bool contact);
  /// The step's matrix has the inertia term: dynamic runs and DDA static ones.
  bool step_inertia() const { return model_.step_inertia(); }
  void build_pattern_with_pairs();
  /// Polynomial stress coefficients per element: (n+1)(n+2)/2.
  std::size_t stress_terms() const { return static_cast<std::size_t>(space_.terms()); }
  /// ε of the regularised factorisation (system_matrix.h), relative to each diagonal entry.
  static constexpr double kRegularisation = 1e-10;
  void apply_removed();

  const Mesh& mesh_;
  const SceneDef& scene_;
  std::string scene_name_;
  Model model_;                         // derived once from mesh and scene (model.h)
  StepControl control_;                 // Shi's step control (step_control.h)
  CoverSpace space_;                    // order, unknowns of each cover and element, shapes
  Configuration config_;                // the space on the step's cover positions: frames, bases
  RunState s_;                          // everything a step carries to the next
  std::vector<std::uint8_t> removed_elem_;      // [me] 1: its body is excavated

  Eigen::VectorXd rhs_;
  SystemMatrix system_;
  StepTimings timings_;
  // Contact and step control.
  ContactSet contacts_;
  Eigen::VectorXd rhs_base_;     // right-hand side without contacts
  std::function<bool()> stop_check_;                     // interrupt.h
  ContactSolveStats solve_stats_;
  int threads_ = 1;  // what the contact solves cost (contact_solve.h)
  EquilibriumIndicator indicator_;  // lumped cover masses (derived from the mesh: no run state)
  EquilibriumSample balance_;       // of the last accepted step (diagnostics, not state)
  bool stopped_at_ratio_ = false;
};

}  // namespace nmm::solve
