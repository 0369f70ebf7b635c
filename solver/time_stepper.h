// NMM time stepping (Shi's implicit scheme) on a loaded mesh: see time_stepper.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "element_integration.h"
#include "contact.h"
#include "cover_unknowns.h"
#include "elasticity.h"
#include "mesh.h"
#include "output_writer.h"
#include "scene.h"
#include "system_matrix.h"

namespace nmm::solve {

/// A point carried by the deforming body (fixed point, load point, measure point).
struct TrackedPoint {
  std::int32_t element = -1;  ///< element it lies in
  double x0 = 0, y0 = 0;      ///< m, where it started
  double x = 0, y = 0;        ///< m, where it is now
};

/// Seconds spent per part of the run.
struct StepTimings {
  double contact_detection = 0;
  double assembly = 0;
  double factorisation = 0;
  double solves = 0;
  double geometry_update = 0;  ///< stresses, loop vertices, covers and points moved after a solve
  double output = 0;
};

class TimeStepper {
 public:
  /// Prepares a run: locates the scene's points in the elements (InputError naming the scene
  /// path, e.g. /fixed_points/2, for a point outside every body), builds the sparsity pattern.
  /// `scene_name` names the scene in such errors.
  TimeStepper(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name);

  /// Runs all steps, writing history, frames and the summary into `out`. Returns the summary
  /// (also written). `progress`: a progress line on stderr.
  nlohmann::json run(OutputWriter& out, bool progress);

  /// Asked before every step: true stops the run with status "interrupted" (interrupt.h).
  void set_stop_check(std::function<bool()> f) { stop_check_ = std::move(f); }
  /// Called after every accepted step with (step, simulated time in s) (progress.h).
  void set_progress(std::function<void(std::int64_t, double)> f) { progress_ = std::move(f); }

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
  const std::vector<double>& cover_displacement() const { return cover_u_; }  ///< [2·pc] m
  const std::vector<double>& velocity() const { return velocity_; }           ///< [2·pc] m/s
  const std::vector<double>& stress() const { return stress_; }  ///< [3·me] Pa σxx σyy τxy
  const std::vector<double>& loop_xy() const { return loop_xy_; }              ///< [2·v] m
  const std::vector<TrackedPoint>& measure_points() const { return measure_; }
  /// Displacement of a point (x, y) of element e in its current configuration, m.
  std::array<double, 2> displacement_at(const TrackedPoint& p) const;
  double time() const { return time_; }
  /// Test hooks for the patch test: impose cover displacements d (as a step would, stresses and
  /// geometry follow), and the right-hand side −F_int (+ loads, gravity) of the next step.
  void impose_displacement(const Eigen::VectorXd& d);
  const Eigen::VectorXd& assemble_rhs(double dt);
  const StepTimings& timings() const { return timings_; }
  /// The physical effects this run computes (summary.json "effects").
  std::vector<std::string> effects() const;
  /// Two per independent cover: sliver covers share a neighbour's (cover_unknowns.cpp).
  int unknowns() const { return covers_.unknowns(); }
  const CoverUnknowns& cover_unknowns() const { return covers_; }
  std::size_t symbolic_analyses() const { return system_.analyses(); }
  const ContactSet& contacts() const { return contacts_; }
  std::size_t open_close_iterations() const { return iterations_; }
  std::size_t time_step_cuts() const { return cuts_; }
  double max_penetration() const { return max_penetration_; }
  double model_half_size() const { return w0_; }
  /// The system of the last step (for benchmarks comparing against a bare factorisation).
  const SystemMatrix& system() const { return system_; }
  const Eigen::VectorXd& rhs() const { return rhs_; }

 private:
  void compute_frames();
  void assemble(double dt);
  void update_pattern();
  void update(const Eigen::VectorXd& d, double dt);
  std::vector<MeasureSample> sample_measure_points() const;
  void check_static_support() const;

  const Mesh& mesh_;
  const SceneDef& scene_;
  std::string scene_name_;
  std::vector<Mat3> material_d_;        // [material] elasticity matrix, Pa
  std::vector<std::int32_t> elem_mat_;  // [me] material index
  CoverUnknowns covers_;                // which unknowns each cover moves with
  std::vector<std::array<int, 6>> groups_;  // [me] unknowns of the element's covers
  double fixed_k_ = 0;                  // N/m, penalty stiffness of a fixed point

  std::vector<double> cover_xy_;   // [2·pc] m, current position of each cover's node
  std::vector<double> cover_u_;    // [2·pc] m, displacement since the start
  std::vector<double> velocity_;   // [2·pc] m/s, v0 of the next step (a tied cover: its master's)
  std::vector<double> accel_;      // [2·pc] m/s², a0 of the next step
  bool accel_known_ = false;       // a0 comes from a step (else the next step takes β = ½)
  std::vector<double> stress_;     // [3·me] Pa
  std::vector<double> loop_xy_;    // [2·v] m, current loop vertices
  std::vector<double> loop_u_;     // [2·v] m, displacement since the start
  std::vector<TrackedPoint> fixed_, loads_, measure_;
  std::vector<ElementFrame> frame_;  // [me]
  Eigen::VectorXd rhs_;
  SystemMatrix system_;
  StepTimings timings_;
  double time_ = 0;
  double max_step_displacement_ = 0;  // m, largest cover displacement in one step
  // Contact and step control.
  ContactSet contacts_;
  std::vector<std::pair<std::int32_t, std::int32_t>> pattern_pairs_;  // element pairs in pattern
  Eigen::VectorXd rhs_base_;     // right-hand side without contacts
  double w0_ = 0;                // m, half the model size
  std::size_t iterations_ = 0;   // open–close iterations (solves), all steps
  std::size_t cuts_ = 0;         // time-step cuts
  std::size_t friction_unsettled_ = 0;  // steps taken with friction forces still moving
  double dt_ = 1e300;            // s, the step length step control has arrived at
  double max_penetration_ = 0;   // m, largest penetration after any accepted step
  std::size_t max_capped_ = 0;   // most contacts held below Vm after one step
  std::function<bool()> stop_check_;                     // interrupt.h
  std::function<void(std::int64_t, double)> progress_;  // progress.h
  static constexpr int kMaxIterations = 16;  // factorisations per step's open–close iteration
};

}  // namespace nmm::solve
