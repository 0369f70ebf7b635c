// Strength reduction (SRM, as in UDEC/3DEC): the factor of safety F is the factor by which the
// joints' strength must be divided to bring the model to failure.
//
// For a trial factor F the chosen joint sets get
//   tan φ_F = tan φ / F,   c_F = c / F,   T_F = T / F,   c_r,F = c_r / F
// (friction angle, cohesion, tensile strength, residual cohesion; docs/fos-and-sweeps.md), so the Mohr–Coulomb strength
// τf = c + σn·tan φ becomes τf / F at every σn. The seed's joint laws use the same strength: the
// Barton–Bandis shear law has τ = σn·tan(φr + JRC_mob·log10(JCS/σn)), where dividing tan φr would
// leave the roughness whole: its shear.strength_factor = F divides the whole τ instead (with its
// friction_deg, φr, kept; the dilation is kinematic and kept too). The
// hyperbolic shear law τ = us / (1/Ksi + Rf·us/τf) takes the reduced τf, so its tangent stiffness
// ks = Ksi·(1 − Rf·τ/τf)² follows it — the initial stiffness Ksi is unchanged, the curve bends
// over sooner and reaches the lower asymptote τf/(F·Rf). Bandis–Barton normal closure has no
// strength and is not changed. Constant springs keep kn, ks.
//
// The search: bracket, then k-section. A round runs k trials in parallel (k = workers). While no
// failing trial is known, a round tries lo·2, lo·4, …, lo·2^k above the largest stable factor lo
// (and likewise down by halves while no stable one is known); then each round puts its k trials
// at lo + j·(hi − lo)/(k+1), j = 1..k, which narrows the bracket [lo, hi] (largest stable, smallest
// failing) (k+1)-fold. It stops when hi − lo ≤ tol·lo and reports F = (lo + hi)/2: within tol/2
// of the factor where the verdict changes. A stable trial above a failing one (the verdict not
// monotone in F) is reported; the bracket then uses the smallest failing factor.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace nmm::studies {

/// Strength of one joint set before reduction.
struct SetStrength {
  std::string name;
  double tan_phi = 0;           ///< –
  double cohesion = 0;          ///< Pa
  double tensile_strength = 0;  ///< Pa
  double residual_cohesion = 0;  ///< Pa, cohesion kept after failure (0: brittle)
  std::string shear_model;      ///< "constant", "hyperbolic", "penalty" or "barton_bandis"
  double strength_factor = 1;   ///< –, a Barton–Bandis set's own shear.strength_factor
};

/// The strengths of `sets` (empty = every joint set) in a scene document (after the user's
/// variants). InputError (naming `source` and --sets) for an unknown set or no joint sets.
std::vector<SetStrength> set_strengths(const nlohmann::json& scene, const std::vector<std::string>& sets,
                                       const std::string& source);

/// The nmm-solve --set arguments ("joint_sets.NAME.friction_deg=…" etc.) for trial factor F.
std::vector<std::string> reduction_sets(const std::vector<SetStrength>& sets, double factor);

struct TrialRecord {
  double factor = 0;         ///< trial F
  bool failing = false;      ///< the verdict
  std::string reason;        ///< why, in words (trial_verdict.h)
  int round = 0;             ///< 1-based
  double wall_seconds = 0;   ///< s, the solver run
  double max_displacement = 0;  ///< m, largest measure-point displacement in the trial
  double end_velocity = 0;      ///< m/s, largest measure-point speed over the last quarter
  std::string dir;              ///< the trial's folder
};

struct SearchOptions {
  double tolerance = 0.01;  ///< relative width of the final bracket, (hi − lo)/lo
  int per_round = 1;        ///< k trials per round
  double start = 1.0;       ///< first factor tried
  double max_factor = 64;   ///< give up above this (still stable)
  double min_factor = 1.0 / 64;  ///< give up below this (still failing)
};

struct SearchResult {
  bool found = false;        ///< a bracket of the requested width exists
  std::string status;        ///< "ok", or why not ("stable up to F = 64", …)
  double fos = 0;            ///< (lo + hi)/2 when found
  double lo = 0, hi = 0;     ///< largest stable, smallest failing factor (0 = none)
  int rounds = 0;
  bool monotone = true;      ///< no stable trial above a failing one
  std::vector<TrialRecord> trials;  ///< in the order they were run
};

/// Runs the search; `run_round(factors, round)` runs the trials of one round (in parallel) and
/// returns their records, in the same order.
SearchResult search_factor_of_safety(
    const SearchOptions& options,
    const std::function<std::vector<TrialRecord>(const std::vector<double>&, int)>& run_round);

}  // namespace nmm::studies
