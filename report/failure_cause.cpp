// The likely cause of a stopped run: see failure_cause.h.
#include "report/failure_cause.h"

#include <algorithm>
#include <string>

#include "common/number_format.h"
#include "common/scene_checks.h"

namespace nmm::report {

Outcome run_outcome(const nlohmann::json& summary) {
  Outcome o;
  o.reason = summary.value("status", std::string("unknown"));
  o.time = summary.value("stop_time", summary.value("simulated_time", 0.0));
  if (!stop_code_from_name(summary.value("stop_code", std::string()), o.code))
    o.code = o.reason == "ok" ? StopCode::ok : o.reason == "interrupted" ? StopCode::interrupted : StopCode::failed;
  if (!o.failed()) o.reason.clear();
  return o;
}

std::string likely_failure_cause(const Mesh& mesh, const SceneDef& scene, StopCode code) {
  if (code == StopCode::ok || code == StopCode::interrupted) return "";

  // The body the mesh is coarsest against (largest mesh size / inradius above 1).
  double worst = 1;
  std::size_t body = scene.bodies.size();
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const double r = body_inradius_estimate(scene.bodies[b]);
    if (r > 0 && mesh.mesh_size / r > worst) worst = mesh.mesh_size / r, body = b;
  }
  if (body < scene.bodies.size()) {
    const Ring& ring = scene.bodies[body].outer;
    double x0 = ring.front().x, x1 = x0, y0 = ring.front().y, y1 = y0;
    for (const Vec2& p : ring) {
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
      y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    }
    const double r = body_inradius_estimate(scene.bodies[body]);
    return "mesh size " + format_rough(mesh.mesh_size, 3) + " m against body " +
           std::to_string(body) + ", " + format_rough(x1 - x0, 3) + " m wide and " +
           format_rough(y1 - y0, 3) + " m high: the mesh is coarser than the body, which moves as a few stiff elements "
           "whose corners jump from step to step. Cut the scene again with mesh.size at most " +
           format_rough(0.5 * r, 2) + " m.";
  }
  if (code == StopCode::step_displacement || code == StopCode::penetration)
    return "a block moved farther in one step than contacts can follow: a block falling or "
           "flying off (hold the model with supports or fixed points), or solver.time_step too "
           "long for the joint stiffness (try a smaller one).";
  if (code == StopCode::contact_not_converged)
    return "contacts keep changing state: try a smaller solver.time_step, a lower "
           "max_displacement_ratio or a softer penalty (joint_sets.NAME.normal.kn).";
  if (code == StopCode::bolts_not_settled)
    return "the bolts' springs kept switching between elastic and yielding or slipping within a "
           "step: try a smaller solver.time_step, or more segments (bolts[].segments).";
  if (code == StopCode::fracture_cascade)
    return "cracks kept growing through the rock within one step even at the shortest step: the "
           "load rate may be too high for a quasi-static run (a slower support velocity, or run dynamic).";
  if (code == StopCode::flow_not_converged)
    return "the pressures of the fluid and the openings of the joints it fills did not agree within "
           "a step even at the shortest step: try a smaller solver.time_step or a stiffer fluid "
           "(flow.fluid.bulk_modulus).";
  if (code == StopCode::unconstrained)
    return "a block is held by nothing: give it fixed points or supports, or run dynamic.";
  return "";
}

}  // namespace nmm::report
