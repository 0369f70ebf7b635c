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
//                  + Σ_closed contacts (½ N·closure + ½ |T·s_el|)
//                  penalty springs (u_d the held displacement components, linear along the edge,
//                  h_d where a moving support holds them, velocity·∫f dt, 0 for a fixed one;
//                  N normal force, closure = −gap, T shear force, s_el elastic shear; exact for
//                  constant springs, the secant energy for nonlinear laws)
//   load_work  W = Σ_steps [Σ_loads f(t_n+1)·(p_n+1 − p_n)       work of the external loads since
//                  + Σ_traction edges ∫ t(t_n+1)·Δu ds           the start of this run: point loads,
//                  + Σ_wet faces ∫ −p·n·Δu ds                    (water in the joints, joint_water.h:
//                                                                exact on each linear piece of p)
//                  + Σ_e ρ_e A0_e b(t_n+1)·Δc_e                  tractions (t = normal·n + shear·s,
//                  − Σ_moving supports k_s ∫ ē_d·Δh_d ds]
//                  or σ_insitu·n; two-point Gauss, exact for the linear Δu) and the body force of
//                  base shaking b = −a_base; each at the step's end time, as the implicit step
//                  applies it. (Gravity's work is −ΔV, not counted here.) A moving support's
//                  work: its springs pull on the held line with k_s·(u − h), which the motion
//                  Δh works against; ē = u − h averaged over the step (trapezoid: exact for the
//                  linear spring), linear along the edge.
//   friction   D = Σ_steps Σ_sliding (|T|·|s − s_el| − N·Δv)     work of friction in sliding
//                  contacts (s the trial elastic shear, s_el the shear left at the limit: the
//                  step's slip), less what the asperities return as opening: a Barton–Bandis
//                  joint that dilates by Δv (joint_law.h) pushes its faces apart with N over it
//                  (and takes N·|Δv| back sliding down toward its start)
//   bolts      S includes their springs' elastic energy (bolt_elastic_energy), D their plastic
//              work (grout slip, steel yield: BoltState::plastic_work, counted by each step)
//   absorbed   A = Σ_steps v1ᵀ C_e d over absorbing edges: what the dashpots took out, and W the
//                  work of their input traction and carried reaction (absorbing_boundary.h);
//                  a column of its own (between friction and residual) only with absorbing boundaries
//   fracture   F = Σ_steps that cracked ½ r·d = −½ Σ_new faces Σ_sides ∫ (σ0 n)·Δu ds
//                  the strain energy the cracks released (a column of its own, before residual,
//                  only where the rock can break). Derivation: cracks found in a step re-cut the
//                  mesh and the step is solved again from its start, carried onto the cut mesh
//                  with the same fields (state_transfer.h: K, U, V, S unchanged — no energy moves
//                  between columns at the cut). On the cut mesh the start state is out of balance
//                  by r: each side of a new face lost the traction σ0·n the uncut element
//                  carried across it, so its covers get r_k = −∫ w_k σ0 n ds (w_k their weights,
//                  n the side's outward normal, σ0 its element's start stress). The step solves
//                  A d = b + r (b what it would solve uncut; A = K + a0 M, a0 = 2/Δt² with
//                  inertia in the matrix, 0 in static_mode "equilibrium"). With U(d) = U0 +
//                  f_int0·d + ½ dᵀK d a linear step's W − ΔU is b·d + r·d − ½ dᵀK d; in a static
//                  step (K d = b + r) that is ½ b·d + ½ r·d: ½ b·d is what every static step
//                  leaves (its load increment taken at the step's end, O(Δt)), and
//                  ½ r·d = −½ Σ ∫ (σ0 n)·Δu ds — Irwin's crack-closure integral with the opening
//                  the faces reach: the strain energy the crack released, which the static step
//                  takes out (nothing keeps it as motion). It is exact for a linear static step
//                  (the faces' contacts closed or open throughout it); with inertia in the
//                  matrix the step's own loss is ½ dᵀK d + a0 dᵀM d (DDA's static steps, v = 0
//                  after) or ½ dᵀK d (dynamic: a0 dᵀM d stays as K), so F books the release
//                  within a0 M/K of what the step takes out — in a dynamic run the release that
//                  becomes motion (≤ ½ a0 dᵀM d) is booked at once and the scheme's damping of it
//                  later shows in R as that much less. Δu is linear along the edge and σ0
//                  constant (cover order 0: fracturing needs it): the sum is exact. Several re-cuts
//                  in one step: r is that of every face cut since the last accepted step, d the
//                  final solution. Softening crack faces (cohesive_law.h) add what their damage
//                  dissipated, Σ_steps Σ_faces L·[D(κ_end) − D(κ_start)] (D the work of the
//                  traction to κ on the envelope less the elastic energy the secant gives back:
//                  that part is in S as ½N·closure), and the work their cohesion does in slip
//                  moves from D to F; a stiff face takes the traction at the cut, so ½ r·d
//                  is then small.
//   damped     Q = Σ_steps [½ v1ᵀM v1 − K]                      the motion the steps throw away: v1 the
//                  velocity a step reached (newmark.h: v1 = v0 + Δt·a1, a1 = (d − Δt v0 −
//                  (½ − β)Δt² a0)/(βΔt²); a static step of static_mode "dda" starts from rest and
//                  has β = ½, so v1 = 2d/Δt), K what the next step keeps of it (0 in a static
//                  run, dynamic_factor²·½ v1ᵀM v1 in a dynamic one). A column of its own only where
//                  the steps throw motion away (static "dda" runs, dynamic_factor < 1). Why it is
//                  what R would otherwise hold: a static step solves (K + a0 M) d = b, a0 = 2/Δt²,
//                  and its W − Δ(U + S) = b·d − ½ dᵀK d = ½ dᵀK d + a0 dᵀM d, of which a0 dᵀM d
//                  = ½ v1ᵀM v1 is the kinetic energy its inertia term gave the covers: a block that
//                  slides under gravity in static steps (0.18 mm a step on the step-path slope)
//                  loses all its motion at every step. (The mass is taken at the step's end
//                  position: O(d) from the step's.)
//   residual   R = W − D − A − Q − F − [(K + U + V + S) − (K + U + V + S)_first row]
//                  energy lost elsewhere: the time scheme's numerical damping (Newmark γ = 1), the
//                  in-situ traction on faces between bodies (not metered), contact springs unloading.
// At cover order n ≥ 1 the traction work and the support springs still take the displacement
// linear between an edge's ends (the field there has degree n + 1): an O(h²) approximation that
// shows in the residual; K and U are exact.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/discretisation/boundary_conditions.h"
#include "solver/discretisation/configuration.h"
#include "solver/contact/contact_set.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/elasticity.h"
#include "solver/discretisation/joint_water.h"
#include "common/mesh.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"
#include "preprocess/recut.h"
#include "common/scene.h"

namespace nmm::solve {

struct EnergyRow {
  std::int64_t step = 0;  ///< steps since step 0 of the first run
  double time = 0;        ///< s
  double kinetic = 0;     ///< J/m
  double strain = 0;      ///< J/m
  double gravity = 0;     ///< J/m, potential of gravity relative to the start
  double springs = 0;     ///< J/m, penalty springs of fixed points and closed contacts
  double load_work = 0;   ///< J/m, work of loads, tractions, base shaking, moving supports since this run's start
  double support_work = 0;  ///< J/m, the moving supports' part of load_work (not in energy.csv)
  double friction = 0;    ///< J/m, work of friction (and the bolts' plastic work) since the start of this run
  double absorbed = 0;    ///< J/m, taken out by absorbing boundaries since the start of this run
  double damped = 0;      ///< J/m, motion the steps threw away (each static step from rest) since this run's start
  double fracture = 0;    ///< J/m, released (dissipated) by cracking since the start of this run
  double residual = 0;    ///< J/m, W − D − A − Q − F − Δ(K + U + V + S)
};

class EnergyMeter {
 public:
  /// `model`: the run's (RunView::model, run_view.h: materials, penalty springs, edge sets, water); it
  /// must outlive the meter. `space`: the run's approximation space (RunView::space); at
  /// cover order n ≥ 1 the kinetic and strain energies integrate its shape functions and stress
  /// polynomials.
  explicit EnergyMeter(const Model& model, const CoverSpace* space = nullptr);

  /// The state terms (K, U, V, S) of a state; the path terms stay 0.
  EnergyRow state_terms(const RunState& s, const std::vector<Contact>& contacts) const;

  /// Call once before the first step and after every accepted step: accumulates the work of
  /// loads and friction; `keep` adds the row to rows() (output steps).
  void after_step(const RunState& s, const std::vector<Contact>& contacts, bool keep);

  /// Keeps the last measured row if it is not kept yet (the run's final state).
  void keep_last();

  /// Cracks re-cut the run's mesh in the step since the last call (RunView::topology changed):
  /// the meter follows the run onto `model`'s mesh (and `space`), carrying its per-element and
  /// per-vertex records over by `map` — from the new mesh back to the mesh of the last call,
  /// composed over every re-cut in between (RunView::recut) — and `start`, the step's start
  /// carried onto the new mesh (RunView::recut_start): the cut itself changes no energy term, and
  /// the next after_step books the strain energy the cracks released (fracture). Call it before
  /// that after_step. Throws std::logic_error if the map or the start is not of `model`'s mesh.
  void carry_over(const Model& model, const CoverSpace* space, const pre::RecutMap& map, const RunState& start);

  /// J/m, the energy cracking released since the start of this run (summary.json
  /// fracture.dissipated_j).
  double fracture() const { return released_; }
  /// The rock can break: energy.csv has the fracture column.
  bool fracturing() const { return fracturing_; }

  const std::vector<EnergyRow>& rows() const { return rows_; }

  /// Writes DIR/energy.csv: "step,time,kinetic,strain,gravity,springs,load_work,friction", then
  /// "absorbed" with absorbing boundaries, "damped" where the steps throw motion away (static
  /// runs of static_mode "dda", dynamic ones with dynamic_factor < 1), "fracture" where the
  /// rock can break, and "residual".
  void write_csv(const std::string& dir) const;

 private:
  bool removed(const RunState& s, std::int32_t element) const;
  void centroids(const RunState& s, std::vector<double>& cx, std::vector<double>& cy) const;
  double traction_work(const RunState& s) const;  // J/m, since the previous call
  double shaking_work(const RunState& s) const;   // J/m, since the previous call
  double water_work(const RunState& s) const;     // J/m, since the previous call
  double support_work(const RunState& s) const;   // J/m, since the previous call
  double fracture_release(const RunState& s) const;  // J/m, ½ r·d of the step's new faces
  double damped_kinetic(const RunState& s, double kept);  // J/m, what the step threw away (Q's step)
  // J/m, ½ vᵀM v of the cover velocities `velocity` (laid out as RunState::velocity) on s's covers
  double kinetic(const RunState& s, const std::vector<double>& velocity) const;
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
  double plastic0_ = 0;              // J/m, the bolts' plastic work at the first call
  double absorbed0_ = 0, absorbing_load0_ = 0;  // J/m, the absorbing boundaries' work at the first call
  double flow_load0_ = 0;  // J/m, the flow pressure's work on the joint faces at the first call
  double load_work_ = 0, friction_ = 0, support_work_ = 0;
  double released_ = 0;              // J/m, F: the cracks' released strain energy so far
  double damped_ = 0;                // J/m, the motion the steps threw away so far
  bool damping_ = false;             // the steps throw motion away: energy.csv has the damped column
  std::vector<double> prev_cover_u_, prev_velocity_, prev_accel_;  // at the previous call (damping_)
  bool prev_accel_known_ = false;
  std::vector<double> prev_v1_;       // m/s, the velocity the last step threw away (static runs)
  double prev_dt_ = 0;                // s, that step's length
  std::size_t prev_cover_count_ = 0;  // covers of the mesh prev_v1_ is on
  bool fracturing_ = false;          // the rock can break: energy.csv has the fracture column
  std::size_t joints_ = 0;           // the scene's joints at the last call (the cracks' come after)
  // The start of a step that re-cut the mesh, carried onto the new mesh (carry_over), for the
  // crack-closure sum at its end.
  struct CrackStart {
    bool pending = false;
    std::size_t first_new_joint = 0;             // the scene's joints before the step's cracks
    std::vector<double> loop_xy, loop_u, stress;  // [2·v] m, [2·v] m, [3·me] Pa
  } crack_start_;
  EnergyRow last_;
  std::int64_t last_kept_step_ = -1;
  std::vector<EnergyRow> rows_;
};

}  // namespace nmm::solve
