// What a run derives from its mesh and scene, and its effects: see mesh_bound.h.
#include "solver/stepping/mesh_bound.h"

#include <algorithm>

#include "solver/contact/contact_history.h"
#include "solver/fracture/fracture.h"

namespace nmm::solve {

MeshBound::MeshBound(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name, std::size_t cracks)
    : model(mesh, scene, scene_name), form(model),
      // A run that can crack also ties covers of next to no support that its cracks cut
      // (cover_unknowns.cpp): corners cut off at nodes, clamped between stiff crack faces.
      space(mesh, scene.solver.cover_order, scene.solver.sliver_cover_weight, Fracture::kLeastCoverSupport,
            static_cast<std::int32_t>(scene.joints.size() - cracks)),
      config(mesh, &space),
      indicator(mesh, scene, space), momentum(mesh, space, indicator.group_mass()),
      bolts(model, space, scene_name), contact(model, space), absorbing(model, space), supports(model),
      flow(model, space),
      effects{&bolts, &contact, &absorbing, &supports, &flow}, checkpointed{&absorbing, &bolts, &flow},
      metered{&contact, &bolts, &absorbing, &flow, &model.water()} {}

int MeshBound::number(const RunState& s) {
  int unknowns = space.unknowns();
  std::size_t groups = model.mesh().element_count();
  for (Effect* e : effects) {
    e->number(s, unknowns, groups);
    unknowns += e->unknowns();
    groups += e->groups(s);
  }
  return unknowns;
}

void MeshBound::pattern_groups(const RunState& s, std::vector<int>& offsets, std::vector<int>& dofs) const {
  const int m = space.element_dofs();
  for (std::size_t e = 0; e < model.mesh().element_count(); ++e) {
    dofs.insert(dofs.end(), space.element_unknowns(e), space.element_unknowns(e) + m);
    offsets.push_back(static_cast<int>(dofs.size()));
  }
  for (const Effect* e : effects) e->add_groups(s, offsets, dofs);
}

std::string MeshBound::describe_unknown(int unknown) const {
  for (const Effect* e : effects)
    if (std::string d = e->describe_unknown(unknown); !d.empty()) return d;
  return "unknown " + std::to_string(unknown);
}

void MeshBound::continue_from(MeshBound& before, std::vector<ContactHistory> history, const pre::RecutMap* map,
                              RunState& s) {
  if (!map) {
    contact.continue_from(before.contact, std::move(history));
    flow.continue_from(before.flow, s);
    return;
  }
  const MeshPieces from{before.model.mesh(), before.space, map->element_parent, map->cover_parent,
                        map->vertex_parent};
  contact.continue_from(before.contact, std::move(history), &from);
  flow.continue_from(before.flow, s);
  for (const Effect* e : effects) e->carry_over(from, s);
}

void MeshBound::restore_contact_history(const std::string& bytes, const std::string& name) {
  load_contact_history(contact.set(), bytes, model.mesh(), name);
}

bool MeshBound::solved_by_effect() const {
  return std::any_of(effects.begin(), effects.end(), [](const Effect* e) { return e->active() && e->solves(); });
}

void MeshBound::set_removed(const std::vector<std::uint8_t>& removed) {
  const bool any = std::any_of(removed.begin(), removed.end(), [](std::uint8_t r) { return r != 0; });
  contact.set().set_removed_elements(any ? removed : std::vector<std::uint8_t>{});
}

MeshChange* MeshChanges::active() const {
  for (MeshChange* c : list)
    if (c->active()) return c;
  return nullptr;
}

std::size_t MeshChanges::joints_added() const {
  std::size_t n = 0;
  for (const MeshChange* c : list) n += c->joints_added();
  return n;
}

}  // namespace nmm::solve
