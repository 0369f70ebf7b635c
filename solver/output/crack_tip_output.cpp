// crack_tips.csv and summary.json fracture.tips: see crack_tip_output.h.
#include "solver/output/crack_tip_output.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <utility>

#include "common/atomic_file.h"
#include "common/math_constants.h"
#include "solver/discretisation/excavation.h"
#include "solver/flow/flow_effect.h"
#include "solver/fracture/interaction_integral.h"

namespace nmm::solve {

std::vector<TipReading> read_crack_tips(const RunView& run, CrackTipFinder& finder) {
  const Mesh& mesh = run.mesh;
  const SceneDef& scene = run.model.scene();
  std::vector<std::array<Vec2, 2>> cracks;
  for (const CrackSegment& c : run.fracture.segments()) cracks.push_back({c.a, c.b});
  const std::vector<CrackTip> tips = finder.find(mesh, scene, cracks);
  std::vector<TipReading> out;
  if (tips.empty()) return out;
  std::vector<std::uint8_t> skip = removed_elements(mesh, run.state);
  const std::vector<std::uint8_t>& debris = run.fracture.debris();
  for (std::size_t e = 0; e < debris.size() && e < skip.size(); ++e) skip[e] = skip[e] || debris[e];
  const std::vector<double> stress = mean_stress(run);  // n = 0: the element stresses themselves
  // The elements by the x of their triangle's first node, so that each tip looks only at those
  // within its radius and a triangle's side in x, not at every element.
  std::vector<std::pair<double, std::int32_t>> by_x(mesh.element_count());
  for (std::size_t e = 0; e < by_x.size(); ++e) {
    const std::size_t n = static_cast<std::size_t>(mesh.triangle_nodes[3 * static_cast<std::size_t>(mesh.element_triangle[e])]);
    by_x[e] = {mesh.node_xy[2 * n], static_cast<std::int32_t>(e)};
  }
  std::sort(by_x.begin(), by_x.end());
  // The crack faces that carry traction: the edges of closed contacts, and the two edges at
  // each closed contact's vertex.
  std::vector<std::uint8_t> loaded(mesh.loop_vertex_count(), 0);
  for (const Contact& c : run.contacts.contacts()) {
    if (c.state == ContactState::open) continue;
    loaded[static_cast<std::size_t>(c.at.edge)] = 1;
    const std::int32_t f0 = mesh.element_loop_offset[static_cast<std::size_t>(c.at.elem_a)];
    const std::int32_t f1 = mesh.element_loop_offset[static_cast<std::size_t>(c.at.elem_a) + 1];
    loaded[static_cast<std::size_t>(c.at.vertex)] = 1;
    loaded[static_cast<std::size_t>(c.at.vertex == f0 ? f1 - 1 : c.at.vertex - 1)] = 1;
  }
  // The fluid's pressure on open crack faces (docs/flow.md "Hydraulic fracturing").
  std::vector<double> pressure;
  for (const Effect* e : run.effects)
    if (const auto* f = dynamic_cast<const FlowEffect*>(e); f != nullptr && f->active() && scene.flow.coupled)
      pressure = f->network().face_pressures(run.state.flow_pressure, mesh.loop_vertex_count());
  std::vector<std::int32_t> near;
  for (const CrackTip& t : tips) {
    const double reach = t.radius + 1.01 * mesh.mesh_size;
    near.clear();
    for (auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(t.at.x - reach, std::int32_t{-1}));
         it != by_x.end() && it->first <= t.at.x + reach; ++it)
      near.push_back(it->second);
    const TipElasticity el = tip_elasticity(scene.materials[static_cast<std::size_t>(scene.bodies[t.body].material)], scene.plane);
    const StressIntensity k = interaction_integral(mesh, {t.at, t.direction, t.radius, t.body}, el, stress,
                                                   run.state.loop_u, skip, &near, &loaded,
                                                   pressure.empty() ? nullptr : &pressure);
    TipReading r;
    r.tip = t.id;
    r.k1 = k.k1;
    r.k2 = k.k2;
    r.radius = t.radius;
    r.angle_deg = (std::atan2(t.direction.y, t.direction.x) + mts_angle(k.k1, k.k2)) * 180 / kPi;
    if (r.angle_deg <= -180) r.angle_deg += 360;
    if (r.angle_deg > 180) r.angle_deg -= 360;
    // Where the tip is now: moved as the loop vertex at the tip (the end of its slit or crack).
    r.x = t.at.x + k.tip_u.x, r.y = t.at.y + k.tip_u.y;
    out.push_back(r);
  }
  return out;
}

CrackTipOutput::CrackTipOutput(std::string dir, std::int64_t output_every)
    : dir_(std::move(dir)), output_every_(output_every > 0 ? output_every : 1) {
  std::error_code ec;  // an earlier run's file in the folder would pass for this run's
  std::filesystem::remove(std::filesystem::path(dir_) / "crack_tips.csv", ec);
}

void CrackTipOutput::record(const RunView& run, std::int64_t n) {
  if (n == last_) return;
  last_ = n;
  const std::vector<TipReading> tips = read_crack_tips(run, finder_);
  tips_now_ = static_cast<int>(tips.size());
  any_ = any_ || !tips.empty();
  char row[320];
  for (const TipReading& t : tips) {
    std::snprintf(row, sizeof row, "%lld,%.9g,%d,%.9g,%.9g,%.9g,%.9g,%.6g\n", static_cast<long long>(run.state.step),
                  run.state.time, t.tip, t.x, t.y, t.k1, t.k2, t.angle_deg);
    rows_ += row;
  }
}

void CrackTipOutput::finish(const RunView& run, const Outcome&, std::int64_t done) {
  record(run, done);  // the last good state
  if (any_) write_file_atomically(dir_ + "/crack_tips.csv", "step,time,tip,x,y,k1,k2,angle_deg\n" + rows_);
}

void CrackTipOutput::summarise(nlohmann::json& summary) const {
  if (any_ || summary.contains("fracture")) summary["fracture"]["tips"] = tips_now_;
}

}  // namespace nmm::solve
