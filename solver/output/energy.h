// Energy terms of a run (energy.csv, the energy panel of run_history.svg): what a user checks to
// trust a dynamic run — is kinetic + potential + strain energy conserved where nothing
// dissipates, and does friction take what the blocks lose? All in J per metre of thickness
// (2-D: per unit thickness), measured after a step from the run state alone, so the time
// stepping is not touched (docs/energy.md has the derivations):
//
//   kinetic    K = ½ Σ_e ρ_e Σ_kl (∫_e w_k w_l dA) v_k·v_l     the consistent mass the step uses;
//                  v_k the velocity the next step starts from (0 in static and quasi-static runs);
//                  cover order n ≥ 1: ½ Σ_e ρ_e ∫_e |Σ_a φ_a v_a|² dA over the element's shape
//                  functions φ_a (cover_space.h), integrated exactly
//   strain     U = ½ Σ_e A_e σ_eᵀ D_e⁻¹ σ_e                    elastic energy of the stress state
//                  (in-situ stress included; plane strain: D is the plane-strain matrix);
//                  n ≥ 1: ½ Σ_e ∫_e σ(x)ᵀ D_e⁻¹ σ(x) dA of the stress polynomial, exactly
//   gravity    V = −Σ_e ρ_e A0_e g·(c_e − c0_e)                c the element's centroid now, c0 at
//                  the start, A0 its initial area (mass is conserved); 0 at the start
//   springs    S = Σ_fixed ½ k_f |p − P|² + Σ_supported edges ½ k_s ∫ (u_d − h_d)² ds
//                  penalty springs (u_d the held displacement components, linear along the edge,
//                  h_d where a moving support holds them, velocity·∫f dt, 0 for a fixed one)
//   load_work  W = Σ_steps [Σ_loads f(t_n+1)·(p_n+1 − p_n)       work of the external loads since
//                  + Σ_traction edges ∫ t(t_n+1)·Δu ds           the start of this run: point loads,
//                  + Σ_e ρ_e A0_e b(t_n+1)·Δc_e                  tractions (t = normal·n + shear·s,
//                  − Σ_moving supports k_s ∫ ē_d·Δh_d ds
//                  + Σ_supports ∫ (σ_insitu·n)_d·Δu_d ds]
//                  or σ_insitu·n; two-point Gauss, exact for the linear Δu) and the body force of
//                  base shaking b = −a_base; each at the step's end time, as the implicit step
//                  applies it. (Gravity's work is −ΔV, not counted here.) A moving support's
//                  work: its springs pull on the held line with k_s·(u − h), which the motion
//                  Δh works against; ē = u − h averaged over the step (trapezoid: exact for the
//                  linear spring), linear along the edge. With an in-situ stress every support
//                  also pushes with the field's reaction σ_insitu·n in its held directions,
//                  locked in from the start (integrators.cpp support_terms), which works on the
//                  held line's motion Δu_d as an in-situ traction does (d the held directions).
//   friction   D = what the effects dissipate by friction and plastic slip (below; a sliding
//                  contact: ½(T_start + T)·slip, at its end force T in a step that cut the mesh:
//                  contact_effect.cpp)
//   effects    each effect with state adds its own terms (effect_energy.h; its equations at
//                  the top of its file): S_e into S, W_e into W, D_e into D, A or F — what the
//                  springs between faces hold, the work of a pressure on the faces, what slip,
//                  dashpots and new faces in the rock dissipate. A, F: columns of their own, each only where
//                  an effect that owns it takes part (EffectEnergy::energy_columns). The meter
//                  keeps, for the effects, the loop vertices' displacements of its last call
//                  and, after a step that changed the mesh (mesh_change.h), that step's start
//                  carried onto the new mesh (EnergyStep: the change itself moves no energy
//                  between columns).
//   damped     Q = the motion the steps throw away and what the time scheme damps, since this
//                  run's start (energy.cpp has the derivation). v1, a1 the velocity and
//                  acceleration a step reached (newmark.h: a1 = (d − Δt v0 − (½ − β)Δt² a0)/(βΔt²),
//                  v1 = v0 + Δt·a1; a static step of static_mode "dda" starts from rest with β = ½,
//                  so v1 = 2d/Δt), M the consistent mass:
//                  static "dda":  Σ_steps [½ v1ᵀM v1 + ¼ (Δt/Δt_prev) v1,prevᵀM v1]
//                  dynamic:       Σ_steps [½ dᵀM (a1,prev + a1) − ΔK + ½ (W_f(t1) − W_f(t0))]
//                  the dynamic step's discrete energy identity: Newmark with γ = 1 takes out
//                  ½ dᵀM (a1,prev + a1) − ΔK (≈ (γ − ½)·ωΔt/2 of critical damping for a mode of
//                  angular frequency ω), a1,prev the acceleration the previous step ended in
//                  balance with (before dynamic_factor: the velocity and acceleration a step with
//                  dynamic_factor < 1 throws away are in it); W_f the step's work of the point
//                  loads, tractions, base shaking and the absorbing boundaries' input traction
//                  with their time tables at the step's end
//                  (as W and the step take them) and at its start. A run's first step from rest
//                  at step 0, free of stress, starts out of balance by its loads and gravity:
//                  ½ dᵀM a1,prev is then ½ of their work in the step; any other start without
//                  an acceleration is taken in balance. Both add what the effects report of a
//                  start out of balance by their own forces' jump between steps
//                  (EnergyTerms::damped): contacts released at the start, ½ (0 − c_end)·d, less
//                  ½|T|·slip where one closes again and slides (contact_effect.h). A column of
//                  its own in static "dda" and dynamic runs.
//   residual   R = W − D − A − Q − F − [(K + U + V + S) − (K + U + V + S)_first row]
//                  energy lost elsewhere: the in-situ traction on faces between bodies (not
//                  metered), contact springs unloading, the contact solve's tolerance; in a
//                  dynamic run, the work of loads not at rest when it starts (what its first
//                  step's balance does not know) and the effects' time-varying loads.
// At cover order n ≥ 1 the traction work and the support springs still take the displacement
// linear between an edge's ends (the field there has degree n + 1): an O(h²) approximation that
// shows in the residual; K and U are exact.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/mesh.h"
#include "common/scene.h"
#include "preprocess/recut.h"
#include "solver/discretisation/boundary_conditions.h"
#include "solver/discretisation/configuration.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/effect_energy.h"
#include "solver/discretisation/elasticity.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

struct EnergyRow {
  std::int64_t step = 0;  ///< steps since step 0 of the first run
  double time = 0;        ///< s
  double kinetic = 0;     ///< J/m
  double strain = 0;      ///< J/m
  double gravity = 0;     ///< J/m, potential of gravity relative to the start
  double springs = 0;     ///< J/m, penalty springs of fixed points and supports, and what the effects' springs hold
  double load_work = 0;   ///< J/m, work of loads, tractions, base shaking, moving supports and the effects since this run's start
  double support_work = 0;  ///< J/m, the moving supports' part of load_work (not in energy.csv)
  double friction = 0;    ///< J/m, dissipated by friction and plastic slip since the start of this run
  double absorbed = 0;    ///< J/m, taken out through the model's boundary since the start of this run
  double damped = 0;      ///< J/m, motion the steps threw away and the time scheme damped since this run's start
  double fracture = 0;    ///< J/m, dissipated by new faces in the rock since the start of this run
  double residual = 0;    ///< J/m, W − D − A − Q − F − Δ(K + U + V + S)
};

/// The effects whose terms the meter sums, in the order it sums them (run_view.h energy_sources).
using EnergySources = std::vector<const EffectEnergy*>;

class EnergyMeter {
 public:
  /// `model`: the run's (RunView::model, run_view.h: materials, penalty springs, edge sets); it
  /// must outlive the meter. `space`: the run's approximation space (RunView::space); at
  /// cover order n ≥ 1 the kinetic and strain energies integrate its shape functions and stress
  /// polynomials.
  explicit EnergyMeter(const Model& model, const CoverSpace* space = nullptr);

  /// The state terms (K, U, V, S) of a state, with what `sources` store; the path terms stay 0.
  EnergyRow state_terms(const RunState& s, const EnergySources& sources) const;

  /// Call once before the first step and after every accepted step: accumulates the work of
  /// loads and what `sources` (the run's effects, in the same order at every call) report;
  /// `keep` adds the row to rows() (output steps).
  void after_step(const RunState& s, const EnergySources& sources, bool keep);

  /// Keeps the last measured row if it is not kept yet (the run's final state).
  void keep_last();

  /// An effect changed the run's mesh in the step since the last call (RunView::topology
  /// changed): the meter follows the run onto `model`'s mesh (and `space`), carrying its
  /// per-element and per-vertex records over by `map` — from the new mesh back to the mesh of the
  /// last call, composed over every change in between (RunView::recut) — and `start`, the step's
  /// start carried onto the new mesh (RunView::recut_start): the change itself moves no energy
  /// between columns, and the next after_step hands `start` to the effects (EnergyStep). Call
  /// it before that after_step. Throws std::logic_error if the map or the start is not of
  /// `model`'s mesh.
  /// `start_work` (J/m): r·d of the step on the new mesh, r what the change opened of the force
  /// `start` is out of balance by there (RunView::recut_start_work), handed to the effects at the
  /// next after_step (EnergyStep::cut_work).
  void carry_over(const Model& model, const CoverSpace* space, const pre::RecutMap& map, const RunState& start,
                  double start_work);

  /// The run's totals at the last call (J/m): the dissipation columns and W, S (summary.json,
  /// EffectEnergy::summarise_energy).
  EnergyTerms totals() const;
  /// Adds to `summary` what `sources` write of the totals (EffectEnergy::summarise_energy).
  void summarise(const EnergySources& sources, nlohmann::json& summary) const;

  const std::vector<EnergyRow>& rows() const { return rows_; }

  /// Writes DIR/energy.csv: "step,time,kinetic,strain,gravity,springs,load_work,friction", then
  /// "absorbed" and "fracture" where an effect that owns them took part (EnergyColumns), "damped"
  /// (between them) where the steps throw motion away or the scheme damps it (static runs of
  /// static_mode "dda", dynamic ones), and "residual".
  void write_csv(const std::string& dir) const;

 private:
  bool removed(const RunState& s, std::int32_t element) const { return element_removed(*mesh_, s, element); }
  // The state terms; `counted` (if given): each source's terms of the state (energy_state).
  EnergyRow measure(const RunState& s, const EnergySources& sources, std::vector<EnergyTerms>* counted) const;
  void centroids(const RunState& s, std::vector<double>& cx, std::vector<double>& cy) const;
  // J/m, since the previous call, with the time tables at time t (the step's end: what W counts)
  double traction_work(const RunState& s, double t) const;
  double shaking_work(const RunState& s, double t) const;
  // J/m, the absorbing boundaries' input traction's work over the step at its end time less at
  // its start time (damped_step's load_change)
  double absorbing_input_change(const RunState& s) const;
  double support_work(const RunState& s) const;   // J/m, since the previous call
  // J/m, factor·∫ t·Δu ds over `edges` in the held directions (`held`: x, y), Δu linear between
  // an edge's ends (Δu since the previous call), by the two-point Gauss rule; t =
  // traction(edge, x, y0, nx, ny, t) at each Gauss point: its place (x, y), y0 = y less its
  // vertical displacement (where an in-situ field is read, as cut), n the edge's outward normal.
  template <class Traction>
  double edge_work(const RunState& s, const std::vector<BoundaryEdge>& edges, const bool held[2], double factor,
                   const Traction& traction) const;
  // J/m, Q's step: `kinetic` K at the step's end; `load_change` W_f(t1) − W_f(t0), or in a
  // dynamic run's first step from rest, its work of the loads and gravity (energy.cpp)
  double damped_step(const RunState& s, double kinetic, double load_change);
  // J/m, ½ vᵀM v of the cover velocities `velocity` (laid out as RunState::velocity) on s's covers
  double kinetic(const RunState& s, const std::vector<double>& velocity) const { return 0.5 * mass_dot(s, velocity, velocity); }
  // J/m per (m/s)², xᵀM y of two cover vectors (laid out as RunState::velocity) on s's covers
  double mass_dot(const RunState& s, const std::vector<double>& x, const std::vector<double>& y) const;
  // m, where support i holds its edges at time t (velocity·∫f dt; 0 for a fixed support)
  std::array<double, 2> held(std::size_t support, double t) const;

  void initial_geometry();  // area0_, cx0_, cy0_ of mesh_ as cut

  const Model* model_;
  const Mesh* mesh_;
  const SceneDef* scene_;
  const CoverSpace* space_;  // null or order 0: the constant-cover formulas
  std::vector<double> prev_loop_u_;  // [2·v] m, loop displacements at the previous call
  double prev_time_ = 0;             // s, time of the previous call
  bool moving_supports_ = false;     // a support has a velocity
  std::vector<double> prev_cx_, prev_cy_;  // [me] m, centroids at the previous call (shaking)
  bool shaking_ = false;  // a base acceleration table is given
  std::vector<double> area0_;        // [me] m², initial area
  std::vector<double> cx0_, cy0_;    // [me] m, initial centroid
  std::vector<double> load_x_, load_y_;  // [load] m, position at the previous call
  bool started_ = false;
  double mech0_ = 0;                 // J/m, K + U + V + S of the first call
  // [source] J/m, each effect's totals counted in the state (energy_state) at the first call
  std::vector<EnergyTerms> counted0_;
  unsigned columns_ = kNoEnergyColumn;  // the optional columns the effects own (EnergyColumns)
  double load_work_ = 0, friction_ = 0, support_work_ = 0;
  double absorbed_ = 0;              // J/m, what the effects' steps took out through the boundary so far
  double released_ = 0;              // J/m, F: what the effects' steps dissipated in new faces so far
  double damped_ = 0;                // J/m, the motion the steps threw away and the scheme damped so far
  bool damping_ = false;             // static "dda" or dynamic steps: energy.csv has the damped column
  std::vector<double> prev_cover_u_, prev_velocity_, prev_accel_;  // at the previous call (damping_)
  bool prev_accel_known_ = false;
  std::vector<double> prev_v1_;       // m/s, the velocity the last step threw away (static runs)
  // m/s², the acceleration the last step reached, a1 before dynamic_factor (dynamic runs): what
  // its end, the next step's start, is out of balance by, over M; empty: not known
  std::vector<double> prev_a1_;
  bool unloaded_start_ = false;  // the run starts at step 0 at rest and free of stress (damped_step)
  double prev_dt_ = 0;                // s, that step's length
  std::size_t prev_cover_count_ = 0;  // covers of the mesh prev_v1_ is on
  std::size_t joints_ = 0;           // the scene's joints at the last call (a change's come after)
  // The start of a step that changed the mesh, carried onto the new mesh (carry_over), handed to
  // the effects at the step's end (EnergyStep::changed_start).
  bool changed_ = false;
  RunState changed_start_;
  double changed_work_ = 0;  // J/m, r·d of that step (carry_over's start_work)
  EnergyRow last_;
  std::int64_t last_kept_step_ = -1;
  std::vector<EnergyRow> rows_;
};

}  // namespace nmm::solve
