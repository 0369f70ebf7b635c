// The stress intensity factors at the crack tips of a run's state: see crack_tip_readout.h.
#include "solver/fracture/crack_tip_readout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "common/math_constants.h"
#include "solver/discretisation/excavation.h"
#include "solver/discretisation/stress_field.h"
#include "solver/fracture/interaction_integral.h"

namespace nmm::solve {

std::vector<TipReading> read_crack_tips(const Mesh& mesh, const SceneDef& scene, const CoverSpace& space,
                                        const RunState& s, const std::vector<CrackSegment>& cracks,
                                        const std::vector<std::uint8_t>& debris,
                                        const std::vector<std::uint8_t>& loaded, CrackTipFinder& finder,
                                        const std::vector<double>* pressure) {
  std::vector<std::array<Vec2, 2>> ends;
  for (const CrackSegment& c : cracks) ends.push_back({c.a, c.b});
  const std::vector<CrackTip> tips = finder.find(mesh, scene, ends);
  std::vector<TipReading> out;
  if (tips.empty()) return out;
  std::vector<std::uint8_t> skip = removed_elements(mesh, s);
  for (std::size_t e = 0; e < debris.size() && e < skip.size(); ++e) skip[e] = skip[e] || debris[e];
  const std::vector<double> stress = mean_stress(mesh, space, s);  // n = 0: the element stresses themselves
  // The elements by the x of their triangle's first node, so that each tip looks only at those
  // within its radius and a triangle's side in x, not at every element.
  std::vector<std::pair<double, std::int32_t>> by_x(mesh.element_count());
  for (std::size_t e = 0; e < by_x.size(); ++e) {
    const std::size_t n = static_cast<std::size_t>(mesh.triangle_nodes[3 * static_cast<std::size_t>(mesh.element_triangle[e])]);
    by_x[e] = {mesh.node_xy[2 * n], static_cast<std::int32_t>(e)};
  }
  std::sort(by_x.begin(), by_x.end());
  std::vector<std::int32_t> near;
  for (const CrackTip& t : tips) {
    const double reach = t.radius + 1.01 * mesh.mesh_size;
    near.clear();
    for (auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(t.at.x - reach, std::int32_t{-1}));
         it != by_x.end() && it->first <= t.at.x + reach; ++it)
      near.push_back(it->second);
    const TipElasticity el = tip_elasticity(scene.materials[static_cast<std::size_t>(scene.bodies[t.body].material)], scene.plane);
    const StressIntensity k = interaction_integral(mesh, {t.at, t.direction, t.radius, t.body, &t.behind}, el, stress, s.loop_u,
                                                   skip, &near, &loaded, pressure);
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

}  // namespace nmm::solve
