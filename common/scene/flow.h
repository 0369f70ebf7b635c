// Fluid flow along the joints of a scene ("flow": {...}; docs/flow.md): the fluid, the hydraulic
// aperture, the initial pressure, fixed pressures where joints reach the body boundary under a
// polyline, injections through a point, steady or transient. The solver's side is solver/flow/.
#pragma once

#include <vector>

#include "common/scene/time_tables.h"
#include "common/vec2.h"

namespace nmm {

class JsonReader;
struct SceneDef;

/// A fixed pressure where joints reach the body boundary under a polyline.
struct FlowBoundaryDef {
  std::vector<Vec2> points;  ///< m, polyline, ≥ 2 points
  TimeTable pressure;        ///< Pa over time (one row at t = 0: constant)
};
/// A source of fluid into the joint (or crack) through a point.
struct FlowInjectionDef {
  Vec2 point;       ///< m, on or next to a joint (the nearest joint segment takes it)
  TimeTable rate;   ///< m³/s per m of thickness over time (one row: constant); negative: extraction
};
struct FlowDef {
  bool present = false;         ///< "flow" given
  double viscosity = 1e-3;      ///< Pa·s, μ
  double bulk_modulus = 2.2e9;  ///< Pa, K_f: storage a/K_f per m of joint and per Pa
  double density = 1000;        ///< kg/m³, ρ_f (hydrostatic heads with the scene's gravity)
  bool cavitation = false;      ///< "cavitation_pressure" given: the fluid lag (flow_balance.h)
  double cavitation_pressure = 0;  ///< Pa, the floor p_c: below it the fluid gives way to vapour
  double residual = 2e-5;       ///< m, the hydraulic aperture of a closed joint (> 0)
  double max_aperture = 1e-3;   ///< m, the cap on the hydraulic aperture (≥ residual)
  bool coupled = true;          ///< the pressure loads the faces and the apertures follow them
  double initial_pressure = 0;  ///< Pa, everywhere at the start
  bool initially_dry = false;   ///< the joints hold vapour at the cavitation pressure at the start
  std::vector<FlowBoundaryDef> boundaries;
  std::vector<FlowInjectionDef> injections;
  bool steady = false;          ///< the steady state at every step (no storage)
};

/// flow: {fluid: {viscosity, bulk_modulus, density, cavitation_pressure}, aperture: {residual, max, coupled},
/// initial_pressure, initially_dry, boundaries: [{points, pressure}], injections: [{point, rate}], steady}.
/// Reads the scene's water block (read before): flow replaces "water". With "fracture" the
/// cracks grown during the run join the flow network (docs/flow.md "Hydraulic fracturing").
FlowDef read_flow(const JsonReader& r, const SceneDef& scene);

}  // namespace nmm
