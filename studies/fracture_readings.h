// What nmm-study reads off its fracture runs (docs/accuracy.md "Fracture"), each against a closed
// form of reference/: the tension bar's peak and the energy its cracks dissipate
// (reference/cohesive_bar.h), a rock test's peak load (reference/rock_tests.h), the stress
// intensity factors of a crack (reference/crack_plate.h) and the load at which a crack first
// grows by the rock's toughness.
//
// A specimen's load is its moving support's reaction along its travel (N/m: reactions.csv's, what
// a testing machine's load cell reads), not the mean stress of the body that
// tests/fracture_matrix.cpp reads: ∫_body σ dA = ∮ t ⊗ x ds holds in equilibrium, which a static
// step that moves a support or follows a crack is not quite in (DDA's static step keeps the
// inertia 2M/Δt² of its motion). The two read-offs differ by 0.1 % at the cohesive bar's peak and
// by 1.6–2.5 % at the disc's load at its run's end (docs/accuracy.md "Fracture"). The cracked plate's load, in
// equilibrium steps without inertia, is its mean σyy (the load per unit width).
// Energies are metered after every accepted step as nmm-solve meters them (solver/output/energy.h,
// carried over every re-cut): `fracture` the energy.csv column (what cohesive faces dissipate, and
// the strain energy a crack releases in the step it opens), `damped` the motion DDA's static steps
// throw away as a cracked body springs back. Without softening a bar that cracks across releases
// the elastic energy it held at its peak, U + S (strain and the supports' springs), into these two
// columns; with softening its crack dissipates G_f per m² of crack into `fracture`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "common/outcome.h"

namespace nmm::solve {
class TimeStepper;
}  // namespace nmm::solve

namespace nmm::studies {

/// A run's largest load and what its cracks dissipated.
struct FractureRun {
  Outcome outcome;
  std::int64_t steps = 0;        ///< accepted steps
  double peak = 0;               ///< N/m, the largest load of an accepted state
  std::int64_t peak_step = 0;    ///< the accepted step of that state
  double first_crack_load = 0;   ///< N/m, the load of the last accepted intact state (0: none cracked)
  std::int64_t first_crack_step = -1;  ///< the accepted step whose state broke the rock (-1: none)
  double fracture = 0;           ///< J/m, energy.csv's fracture column at the end
  double released = 0;           ///< J/m, fracture + damped since the last intact state
  double stored_intact = 0;      ///< J/m, U + S of the last intact state (strain + springs)
  double residual = 0;           ///< J/m, energy.csv's residual at the end
  int cracks = 0;                ///< cracks (fracture.h crack_count)
  int segments = 0;              ///< crack segments cut
};

/// Runs `st` to t_end (s), reading after every accepted step the load of the scene's support
/// number `support` (N/m, along its travel: SupportReaction::load) and metering the energy.
/// `on_step(n)` after the n-th accepted step.
FractureRun run_fracture(solve::TimeStepper& st, double t_end, std::size_t support,
                         const std::function<void(std::int64_t)>& on_step);

/// The load at which a tip first grows by the rock's toughness: `st` steps (at most until t_end)
/// until a crack segment appears; `load` is the load of the step that grew it, read as the last
/// intact step's mean σyy plus the increment of the step before (the load grows by a constant
/// step under the moving support), `previous` that intact step's.
struct GrowthLoad {
  Outcome outcome;
  std::int64_t steps = 0;        ///< accepted steps, the one that grew included
  double load = 0;               ///< Pa, mean σyy of the step that grew (extrapolated: above)
  double previous = 0;           ///< Pa, mean σyy of the last intact step
  int segments = 0;              ///< segments grown in that step
  bool grew = false;             ///< a tip grew before t_end
};
GrowthLoad run_until_growth(solve::TimeStepper& st, double t_end, const std::function<void(std::int64_t)>& on_step);

}  // namespace nmm::studies
