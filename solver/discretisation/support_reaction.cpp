// The supports' reactions on an accepted state: see support_reaction.h for the equations.
#include "solver/discretisation/support_reaction.h"

#include <cmath>

#include "common/time_table.h"
#include "solver/discretisation/boundary_conditions.h"
#include "solver/discretisation/insitu_stress.h"

namespace nmm::solve {

namespace {

/// N/m, ∫ σ_insitu·n ds on the edge a → b (loop displacements ua, ub), with the field taken at
/// a point's position in the mesh as cut (y − u_y) and n current, as support_terms applies it.
void insitu_edge_reaction(const InsituStressDef& insitu, const double* a, const double* b, const double* ua,
                          const double* ub, int points, double out[2]) {
  const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
  if (!(len > 0)) return;
  const double nx = dy / len, ny = -dx / len;  // CCW loop: the outside is on the right
  const double* gp = gauss_points(points);
  const double* gw = gauss_weights(points);
  for (int q = 0; q < points; ++q) {
    const double xi = gp[q];
    const double x = a[0] + xi * dx, y = a[1] + xi * dy;
    const auto sg = insitu_stress_at(insitu, x, y - ((1 - xi) * ua[1] + xi * ub[1]));
    out[0] += gw[q] * len * (sg[0] * nx + sg[2] * ny);
    out[1] += gw[q] * len * (sg[2] * nx + sg[1] * ny);
  }
}

}  // namespace

std::vector<SupportReaction> support_reactions(const Model& model, const RunState& s,
                                               const std::vector<std::uint8_t>& removed) {
  const SceneDef& scene = model.scene();
  const double k_s = model.support_stiffness();
  const double* xy = s.loop_xy.data();
  const double* u = s.loop_u.data();
  const int points = scene.solver.cover_order + 2;  // integrators.cpp edge_frame's rule
  std::vector<SupportReaction> out(model.support_edges().size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const SupportDef& sd = scene.supports[i];
    SupportReaction& r = out[i];
    const double speed = std::hypot(sd.velocity.x, sd.velocity.y);
    const double travelled = table_integral(sd.table, s.time);  // s: ∫0^t f dt'
    const double held[2] = {sd.velocity.x * travelled, sd.velocity.y * travelled};
    if (speed > 0) {
      r.travel = speed * travelled;
      r.dx = sd.velocity.x / speed;
      r.dy = sd.velocity.y / speed;
    }
    double spring[2] = {0, 0}, insitu[2] = {0, 0};
    for (const BoundaryEdge& be : model.support_edges()[i]) {
      if (!removed.empty() && removed[be.element]) continue;
      const double* a = xy + 2 * be.vertex;
      const double* b = xy + 2 * be.next;
      const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
      const double* ua = u + 2 * be.vertex;
      const double* ub = u + 2 * be.next;
      for (int d = 0; d < 2; ++d) spring[d] -= k_s * len * (0.5 * (ua[d] + ub[d]) - held[d]);
      if (scene.insitu_stress.present) insitu_edge_reaction(scene.insitu_stress, a, b, ua, ub, points, insitu);
    }
    if (sd.fix_x) r.fx = spring[0] + insitu[0];
    if (sd.fix_y) r.fy = spring[1] + insitu[1];
  }
  return out;
}

}  // namespace nmm::solve
