// The flow state carried onto a re-cut mesh (docs/flow.md "Hydraulic fracturing"): when cracks
// re-cut the mesh, the flow network is built again from the joints and the crack segments as the
// new mesh divides them (flow_network.h), and the pressures and apertures of the network before
// are carried onto it by position:
//   - a node where a node was takes its pressure;
//   - a node on a segment of the network before (a crack that divides a joint or a crack where it
//     meets it) takes the pressure linear between that segment's ends,
//       p = (1 − t)·p_a + t·p_b,   t its position along the segment;
//   - a node of a new crack only takes the pressure of the node it is reached from along the new
//     network (breadth first from the nodes above, in node order): a crack that grows from a
//     pressurised one is filled at its parent's pressure at its tip; one that reaches no fluid
//     starts at the scene's initial_pressure;
//   - a segment that is a piece of a segment before keeps that segment's aperture, linear
//     between its ends (so Σ V = ∫ a ds is unchanged by dividing it); a segment of a new crack
//     starts at the residual aperture (a fresh crack starts closed, fracture.h).
// The fluid a new crack holds at the pressure carried to it,
//     ΔV = Σ_free V_i·(1 + p_i/K_f) after − the same sum before      (m³ per m; transient runs)
// is water the run put there, not water that flowed in: it is booked as `flow_filled` (summary.json
// flow.filled_m3) and left out of `flow_stored`, so stored = injected − outflow still closes to the
// linear solve's round-off (flow_balance.h) and the fill is reported beside it. From the step after
// the re-cut the new nodes store and conduct like every other node.
// With a fluid lag (`cavitation_pressure`, flow_balance.h) a new crack opens dry instead: its
// nodes start at p_c with vapour s_i = V_i·(1 + p_c/K_f) and no fluid, which then flows in; the
// nodes carried over keep the share of their room the vapour took, d_i = s_i/(V_i·(1 + p_i/K_f))
// (linear along an old segment for a node on it), s_i = d_i·V_i·(1 + p_i/K_f) on the new network,
// and ΔV above counts the fluid, V·(1 + p/K_f) − s.
#pragma once

#include "common/scene/flow.h"
#include "solver/discretisation/run_state.h"
#include "solver/flow/flow_network.h"

namespace nmm::solve {

/// s.flow_pressure and s.flow_aperture, on `before`'s nodes and segments, carried onto `now`
/// (above); s.flow_filled gains the fill of the new cracks (transient runs). `tol` m: two nodes
/// within it are one (the networks' own merging distance, 1e-6·h).
void transfer_flow(const FlowNetwork& before, const FlowNetwork& now, const FlowDef& flow, double tol, RunState& s);

}  // namespace nmm::solve
