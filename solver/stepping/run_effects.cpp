// The physical effects a run computes: see run_effects.h.
#include "solver/stepping/run_effects.h"

#include <algorithm>

namespace nmm::solve {

std::vector<std::string> run_effects(const Model& model, const RunState& s, const ContactSet& contacts,
                                     bool fracture) {
  const SceneDef& scene = model.scene();
  std::vector<std::string> e;
  if (model.mesh().element_count() > 0) e.push_back("elasticity");
  if (scene.solver.dynamic) e.push_back("inertia");
  else if (model.step_inertia()) e.push_back("static_inertia");
  if (scene.has_gravity && (scene.gravity.x != 0 || scene.gravity.y != 0)) e.push_back("gravity");
  if (!s.loads.empty()) e.push_back("point_loads");
  if (!s.fixed.empty()) e.push_back("fixed_points");
  if (!scene.supports.empty()) e.push_back("supports");
  if (!scene.tractions.empty()) e.push_back("tractions");
  if (model.water().active()) e.push_back("water");
  if (scene.insitu_stress.present) e.push_back("insitu_stress");
  if (!scene.base_acceleration_x.empty() || !scene.base_acceleration_y.empty())
    e.push_back("base_acceleration");
  if (std::any_of(s.body_removed.begin(), s.body_removed.end(), [](std::uint8_t r) { return r != 0; }))
    e.push_back("excavation");
  for (const std::string& c : contacts.effects()) e.push_back(c);
  if (!s.bolts.empty()) e.push_back("bolts");
  if (!scene.absorbing.empty()) e.push_back("absorbing");
  if (scene.flow.present) e.push_back("flow");
  if (fracture) e.push_back("fracture");
  return e;
}

}  // namespace nmm::solve
