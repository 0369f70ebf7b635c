// Equilibrium indicators of a run as UDEC users read them: the unbalanced force ratio (static
// analysis) and the largest velocity (dynamic), per step, and the verdict at the end
// (summary.json "equilibrium"). Definitions and thresholds: equilibrium_indicator.cpp.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "solver/discretisation/boundary_conditions.h"
#include "solver/discretisation/cover_space.h"
#include "common/mesh.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/step_context.h"
#include "common/scene.h"

namespace nmm::solve {

/// The indicators after one step.
struct EquilibriumSample {
  bool measured = false;       ///< a step has been measured
  double max_ratio = 0;        ///< –, max_c |R_c| / F_ref
  double mean_ratio = 0;       ///< –, mean_c |R_c| / F_ref
  double max_velocity = 0;     ///< m/s, largest cover velocity at the step's end
  double max_unbalanced = 0;   ///< N/m, max_c |R_c|
  double applied_force = 0;    ///< N/m, F_ref: the representative applied force per cover
};

/// What a step hands to the indicator, taken after its solve and before the state moves on.
struct StepBalance {
  const Eigen::VectorXd* d = nullptr;      ///< [unknowns] m, the step's increment
  const std::vector<double>* v0 = nullptr; ///< [m·pc] m/s, velocity at the step's start
  const std::vector<double>* a0 = nullptr; ///< [m·pc] m/s², acceleration at the step's start
  double dt = 0;                           ///< s, the step's length
  double beta = 0.5;                       ///< –, the step's Newmark β
  /// [unknowns] N/m, static_mode "equilibrium" only (no mass): the out-of-balance force the
  /// step's solve removed, F_ext − F_int of the starting state with the step's contact forces
  const Eigen::VectorXd* balance = nullptr;
  /// N/m, Σ of the magnitudes of the applied forces at the step's end (applied_force_sum)
  double applied_sum = 0;
  /// [3·T·me] Pa, stresses: the force scale when nothing is applied (F_ref fallback)
  const std::vector<double>* stress = nullptr;
  std::size_t stress_terms = 1;
};

/// What the verdict compares against (why these: the .cpp).
struct RestCriterion {
  /// –, a static run is at rest below this maximum unbalanced force ratio: UDEC's default for
  /// `solve ratio`
  static constexpr double kRatio = 1e-5;
  /// m/s, a dynamic run is at rest with no cover faster than this
  static constexpr double kVelocity = 1e-4;
};

class EquilibriumIndicator {
 public:
  EquilibriumIndicator() = default;
  /// Lumped cover masses from the mesh as cut (mass is conserved: they never change).
  EquilibriumIndicator(const Mesh& mesh, const SceneDef& scene, const CoverSpace& space);

  /// The indicators of one step (covers of excavated bodies left out).
  EquilibriumSample measure(const StepBalance& step, const std::vector<std::uint8_t>& body_removed) const;
  /// The indicators of a step of `model` just solved (d: its increment) in the context it was
  /// assembled in — the same body force, β and loads, at the step's end, before the state moves
  /// on; `balance`: without inertia, the force the solve balanced, K·d (StepBalance).
  EquilibriumSample measure_step(const Model& model, const StepContext& step, const Eigen::VectorXd& d,
                                 const Eigen::VectorXd* balance) const;

  /// kg/m, the mass of the bodies not excavated.
  double active_mass(const std::vector<std::uint8_t>& body_removed) const;
  /// [unknown group] kg/m, the lumped mass of each independent cover (its unknowns are
  /// g·dpc … g·dpc + dpc − 1).
  const std::vector<double>& group_mass() const { return mass_; }

 private:
  const Mesh* mesh_ = nullptr;        // the stepper's: outlives it
  const SceneDef* scene_ = nullptr;   // likewise
  std::size_t dpc_ = 2;               // unknowns per cover
  std::vector<double> mass_;          // [unknown group] kg/m, lumped mass of each independent cover
  std::vector<std::int32_t> body_;    // [unknown group] body of its covers
  std::vector<std::size_t> cover_;    // [unknown group] a cover of it (its velocity slot)
};

/// N/m: Σ of the magnitudes of the applied forces at time t — the body force on the active
/// mass (|b|·m), point loads (|f|·table), boundary tractions (|t|·edge length, in-situ ones
/// with |σ·n|) and the in-situ traction still acting on faces freed by excavation.
double applied_force_sum(const SceneDef& scene, const RunState& s, double t, double body_force,
                         double active_mass,
                         const std::vector<std::vector<BoundaryEdge>>& traction_edges,
                         const std::vector<InterfaceEdge>& interface_edges,
                         const std::vector<std::uint8_t>& removed_element);

/// summary.json "equilibrium": verdict "at_rest" / "moving" ("unknown" before any step) with the
/// figures behind it and the criterion.
nlohmann::json equilibrium_verdict(const EquilibriumSample& last, bool dynamic);

/// "at_rest (max unbalanced ratio 3.1e-07, largest velocity 2e-06 m/s)": the verdict of an
/// equilibrium_verdict() object in a few words, for the tool's last line.
std::string equilibrium_line(const nlohmann::json& verdict);

/// The verdict alone: true when `last` meets RestCriterion (static: the ratio; dynamic: the
/// velocity).
bool at_rest(const EquilibriumSample& last, bool dynamic);

}  // namespace nmm::solve
