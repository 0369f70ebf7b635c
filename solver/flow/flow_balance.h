// The volume balance of the flow network over one step (docs/flow.md), backward Euler in time:
// at every free node i (m³/s per m of thickness)
//   (V_i/K_f)·(p_i − p_i⁰)/Δt + Σ_j C_ij·(φ_i − φ_j) = Q_i
// with φ = p − ρ_f·g·x the pressure less the fluid's weight above the origin (g the scene's
// gravity, m/s²; none: φ = p), C_ij the segment's conductance and V_i the node's fluid volume
// (flow_network.h) at the step's apertures, p⁰ the pressure at the step's start and Q_i the
// injections' rates at the step's end. The storage term summed over the free nodes is the change
// of the fluid volume Σ V·(1 + p/K_f) the network holds at those apertures, so the balance
// stored = injected − outflow holds to the linear solve's round-off. Nodes under a `boundaries`
// entry have its pressure (no storage: the reservoir beyond the boundary); their inflow from the
// network is the outflow through that boundary, and an injection into one leaves through it.
// `steady`: no storage; a piece of network that reaches no boundary keeps its pressures (an
// injection into one has no steady state: bad input). The matrix is symmetric positive definite
// (storage > 0, or a fixed node in every piece); Eigen's sparse LDLᵀ factorises it, its
// ordering analysed once per network.
//
// Two-way transient coupling (flow_effect.h): the apertures move within the step, so the fluid
// a free node holds changes with its volume too. Given the volumes V⁰ at the step's start, the
// volumes V at the step's end (the faces of the mechanical iterate) and a compliance c_i (m³/Pa
// per m: the volume the node's faces give per Pa, fixed-stress) with the last iterate's pressures
// p^k, the storage term becomes
//   [V_i·(1 + p_i/K_f) − V⁰_i·(1 + p_i⁰/K_f) + c_i·(p_i − p_i^k)] / Δt
//     = [(V_i/K_f + c_i)·(p_i − p_i⁰) + (V_i − V⁰_i)·(1 + p_i⁰/K_f) − c_i·(p_i^k − p_i⁰)] / Δt,
// the change of the fluid volume V·(1 + p/K_f) plus the opening the faces will add when the
// pressure moves from p^k (c·(p − p^k)), which vanishes as the iterates converge. `stored` is the
// change of V·(1 + p/K_f) alone, so stored = injected − outflow − Σ c_i·(p_i − p_i^k): the
// coupling's convergence error.
//
// The fluid lag (`fluid.cavitation_pressure` p_c; Garagash & Detournay 2000, J. Appl. Mech. 67,
// 183–192, for the tip of a fluid-driven crack; Lecampion & Detournay 2007, Comput. Methods
// Appl. Mech. Engrg. 196, 4863–4880, for a fixed mesh): the fluid cannot be pulled below p_c;
// an opening the fluid does not reach in time fills with vapour at p_c instead. Each free node
// holds a vapour volume s_i ≥ 0 (m³ per m, RunState::flow_void), so its fluid is
// V_i·(1 + p_i/K_f) − s_i, and the balance above becomes, with M_i(p) = V_i·(1 + p/K_f) and
// M⁰_i = V⁰_i·(1 + p⁰_i/K_f),
//   [M_i(p_i) − s_i − M⁰_i + s⁰_i + c_i·(p_i − p_i^k)]/Δt + Σ_j C_ij·(φ_i − φ_j) = Q_i,
//   p_i ≥ p_c,   s_i ≥ 0,   (p_i − p_c)·s_i = 0:
// a node is filled (s_i = 0, p_i free) or in the lag (p_i = p_c, s_i what the balance leaves).
// Solved by a primal–dual active set (Hintermüller, Ito & Kunisch 2002, SIAM J. Optim. 13,
// 865–888): lag nodes held at p_c, the rest solved; a filled node below p_c joins the lag, a lag
// node whose s_i came out negative (more fluid than room) is filled; again until no node moves.
// The matrix is an M-matrix (storage on the diagonal, the conductances' Laplacian), for which the
// set settles in finitely many solves with p and s ≥ 0 exact. Its pattern stays the one analysed
// (a lag row is the identity with its off-diagonal entries held as zeros). Without gravity a
// lag node's neighbours sit at p_c or above, so its fluid only grows: a dry node (s = V) fills
// from the filled nodes next to it and the front between them is where the fluid ends.
// `stored` counts the fluid, M − s; a step in which no node reaches p_c is the balance without
// the lag, bit for bit.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/scene.h"
#include "solver/flow/flow_network.h"

namespace nmm::solve {

/// What one step's balance gives.
struct FlowStepResult {
  std::vector<double> pressure;       ///< [node] Pa at the step's end
  std::vector<double> outflow_rate;   ///< [boundary] m³/s per m, leaving through each boundary
  double injected = 0;                ///< m³ per m injected over the step
  double outflow = 0;                 ///< m³ per m leaving through the boundaries over the step
  double stored = 0;                  ///< m³ per m, the change of the volume the network holds
  double exchanged = 0;               ///< m³ per m, |injected| and |through each boundary| over the step
  std::vector<double> void_volume;    ///< [node] m³ per m, the vapour s_i at the step's end (lag only)
  int lag_solves = 0;                 ///< active-set solves of the step (lag only)
};

/// The storage of a step whose apertures move (the header's two-way term); all [node].
struct FlowStorage {
  const std::vector<double>& volume0;     ///< m³ per m at the step's start
  const std::vector<double>& compliance;  ///< m³/Pa per m, c_i
  const std::vector<double>& iterate;     ///< Pa, p^k
};

class FlowBalance {
 public:
  /// The balance of `network` with the scene's fluid, boundaries and gravity (all outlive it);
  /// an InputError naming `scene_name` for a steady injection into joints that reach no boundary.
  FlowBalance(const FlowNetwork& network, const SceneDef& scene, const std::string& scene_name);
  ~FlowBalance();
  FlowBalance(const FlowBalance&) = delete;
  FlowBalance& operator=(const FlowBalance&) = delete;

  /// One step of dt (s) ending at t_end (s) from pressures p0 ([node] Pa), with the step's
  /// conductances ([segment] m³/(s·Pa) per m) and volumes ([node] m³ per m) at its end; with
  /// `moving`, the volumes at the start differ (the two-way storage term above); with
  /// `void0` ([node] m³ per m, the vapour at the start) and a cavitation pressure, the fluid lag.
  FlowStepResult step(const std::vector<double>& p0, const std::vector<double>& conductance,
                      const std::vector<double>& volume, double dt, double t_end,
                      const FlowStorage* moving = nullptr, const std::vector<double>* void0 = nullptr);

 private:
  struct Solver;
  const FlowNetwork& network_;
  const FlowDef& flow_;
  double gx_ = 0, gy_ = 0;             // m/s², the scene's gravity (0 without)
  std::vector<int> unknown_;           // [node] its unknown, or -1 (fixed, or pinned when steady)
  int unknowns_ = 0;
  std::unique_ptr<Solver> solver_;
};

}  // namespace nmm::solve
