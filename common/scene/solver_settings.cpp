// The solver's settings of a scene: see solver_settings.h.
#include "common/scene/solver_settings.h"

#include "common/scene/json_reader.h"

namespace nmm {

SolverDef read_solver(const JsonReader& r) {
  r.check_keys({"time_step", "steps", "dynamic", "dynamic_factor", "newmark_beta",
                "max_displacement_ratio", "output_every", "fixed_point_stiffness",
                "sliver_cover_weight", "checkpoint_every", "support_stiffness", "static_mode",
                "excavation_steps", "cover_order", "history_every", "stop_at_ratio",
                "contact_tolerance"});
  SolverDef s;  // defaults from scene.h
  s.time_step = r.optional_number("time_step", s.time_step, interval(kMinTimeStep, true, kMaxTimeStep, true));
  s.steps = r.optional_integer("steps", s.steps, 0);
  if (r.has("dynamic")) s.dynamic = r["dynamic"].as_bool();
  if (r.has("static_mode"))
    s.static_mode = r["static_mode"].as_choice({"dda", "equilibrium"}, "static_mode") == 0
                        ? StaticMode::dda
                        : StaticMode::equilibrium;
  s.dynamic_factor = r.optional_number("dynamic_factor", s.dynamic_factor, interval(0, true, 1, true));
  s.newmark_beta = r.optional_number("newmark_beta", s.newmark_beta, interval(0.5, true, 1, true));
  s.fixed_point_stiffness =
      r.optional_number("fixed_point_stiffness", s.fixed_point_stiffness, interval(0, true, kMaxSpringStiffness, true));
  s.max_displacement_ratio = r.optional_number("max_displacement_ratio", s.max_displacement_ratio,
                                               interval(0, false, 1, false));
  s.output_every = r.optional_integer("output_every", s.output_every, 1);
  s.history_every = r.optional_integer("history_every", s.history_every, 1);
  s.stop_at_ratio = r.optional_number("stop_at_ratio", s.stop_at_ratio, interval(0, false, 1, false));
  // Below 1/3 every element keeps at least one cover above it (its three weights sum to 1).
  s.sliver_cover_weight = r.optional_number("sliver_cover_weight", s.sliver_cover_weight,
                                            interval(0, true, 0.3, false));
  s.checkpoint_every = r.optional_integer("checkpoint_every", s.checkpoint_every, 0);
  s.support_stiffness = r.optional_number("support_stiffness", s.support_stiffness,
                                          interval(0, true, kMaxSpringStiffness, true));
  s.excavation_steps = r.optional_integer("excavation_steps", s.excavation_steps, 1);
  s.contact_tolerance =
      r.optional_number("contact_tolerance", s.contact_tolerance, interval(1e-12, true, 1e-2, true));
  s.cover_order = static_cast<int>(r.optional_integer("cover_order", s.cover_order, 0));
  if (s.cover_order > 2) r["cover_order"].fail("cover_order must be 0, 1 or 2");
  return s;
}

}  // namespace nmm
