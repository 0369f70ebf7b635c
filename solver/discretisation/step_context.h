// The context of one step attempt (Box2D's b2StepContext): built once per attempt
// (TimeStepper::attempt, make_step_context) and read by everything that derives the step's inputs
// from the scene and the state — the assembly's integrators (form.h), the equilibrium indicators
// and the state update — so that the body force, Newmark's β and the inertia coefficients have
// one place where they are derived:
//     b = g − a_base(t_end)                           (integrators.h body_force_per_mass)
//     β = solver.newmark_beta, or ½ before the acceleration is known   (newmark.h step_beta)
//     c_d = 1/(βΔt²), c_v = 1/(βΔt), c_a = 1/(2β) − 1                  (newmark.h)
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/discretisation/configuration.h"
#include "solver/discretisation/integrators.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/newmark.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

struct StepContext {
  const Configuration& config;               ///< the step's frames and bases
  const RunState& s;                         ///< the state the step starts from
  const std::vector<std::uint8_t>& removed;  ///< [me] 1: excavated
  double t_end;                              ///< s, the step's end (tables, moving supports)
  double dt;                                 ///< s, the step's length
  std::array<double, 2> body_force;          ///< m/s², b = g − a_base(t_end)
  double beta;                               ///< –, Newmark's β of this step
  InertiaCoefficients inertia;               ///< the inertia term's coefficients (β, Δt)
};

/// The context of a step of dt from state s (its time s.time) in `config`.
inline StepContext make_step_context(const Model& model, const Configuration& config, const RunState& s,
                                     const std::vector<std::uint8_t>& removed, double dt) {
  const double t_end = s.time + dt;
  const double beta = step_beta(model.scene().solver, s);
  return {config, s, removed, t_end, dt, body_force_per_mass(model.scene(), t_end), beta,
          inertia_coefficients(beta, dt)};
}

}  // namespace nmm::solve
