// The solver's settings of a scene ("solver": {...}): the time step and the number of steps,
// dynamic or static analysis, Newmark's β, Shi's step control, output and checkpoint intervals,
// the penalty stiffnesses, the cover functions' order and the contact solve's tolerance. Every
// key is optional; the defaults are the fields' initial values below (docs/solver.md).
#pragma once

#include <cstdint>

namespace nmm {

class JsonReader;

/// What `"dynamic": false` solves: DDA's static analysis (each step from rest, the inertia term
/// kept in the step's matrix, so blocks held only by contacts are well posed and settle) or the
/// pure equilibrium K d = F of a body held by fixed points (docs/solver.md, "Static analysis").
enum class StaticMode { dda, equilibrium };

struct SolverDef {
  double time_step = 1e-3;                ///< s, > 0
  std::int64_t steps = 1000;              ///< number of time steps, >= 0
  bool dynamic = true;                    ///< false: static analysis (every step from rest)
  StaticMode static_mode = StaticMode::dda;  ///< what a static run solves (see StaticMode)
  double dynamic_factor = 1.0;            ///< –, in [0, 1]: v0 of the next step = factor · v1
  double newmark_beta = 0.6;              ///< –, in [0.5, 1]: 0.5 is Shi's scheme exactly
  double fixed_point_stiffness = 0;       ///< N/m per unit thickness; 0: 100 × largest E·1 m
  double max_displacement_ratio = 0.001;  ///< –, g2 in Shi's step control, in (0, 1)
  std::int64_t output_every = 10;         ///< steps between outputs (frames), >= 1
  /// steps between history.csv rows, >= 1; 0 (absent): output_every. Rows cost no frame.
  std::int64_t history_every = 0;
  /// –, in (0, 1): stop the run once the maximum unbalanced force ratio falls below it (and, in a
  /// dynamic run, no cover moves faster than the rest velocity): UDEC's `solve ratio`
  /// (solver/stepping/equilibrium_indicator.cpp); 0 (absent): run all steps
  double stop_at_ratio = 0;
  /// –, in [0, 0.3): a physical cover whose weight stays below this everywhere on its support (a
  /// sliver left where a joint passes next to the edge of its star) shares the unknowns of the
  /// neighbour cover it overlaps most; 0 never ties (solver/discretisation/cover_unknowns.cpp)
  double sliver_cover_weight = 1e-3;
  /// steps between checkpoints written during the run (0: only after the last step)
  std::int64_t checkpoint_every = 0;
  /// N/m² (N/m per m of boundary, unit thickness); 0: 100 × largest E / mesh size
  double support_stiffness = 0;
  /// steps over which the in-situ traction on a face freed by excavation is released (1: at once)
  std::int64_t excavation_steps = 1;
  /// –, degree n of the cover functions (seed eq. 1): 0 constant (2 unknowns per physical
  /// cover), 1 linear (6), 2 quadratic (12); a choice of the run, not of the mesh
  /// (docs/higher-order-covers.md)
  int cover_order = 0;
  /// –, τ in [1e-12, 1e-2]: the contact solve accepts a step when no unknown is out of balance by
  /// more than this fraction of the largest contact force, friction strengths follow the
  /// normal forces to within the same force, and (with a softening joint law) the displacement
  /// that would remove the rest is within 3e-4·τ·w0 (docs/contact.md "Tolerance and error")
  double contact_tolerance = 1e-3;
};

/// solver: {time_step, steps, dynamic, static_mode, dynamic_factor, newmark_beta, ...}; a key
/// left out keeps its default.
SolverDef read_solver(const JsonReader& r);

}  // namespace nmm
