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
  /// conductances ([segment] m³/(s·Pa) per m) and volumes ([node] m³ per m).
  FlowStepResult step(const std::vector<double>& p0, const std::vector<double>& conductance,
                      const std::vector<double>& volume, double dt, double t_end);

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
