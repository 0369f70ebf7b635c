// The supports' reactions: see support_reaction.h for the equations.
#include "solver/discretisation/support_reaction.h"

#include <cmath>

#include "common/time_table.h"
#include "solver/discretisation/boundary_conditions.h"
#include "solver/discretisation/insitu_stress.h"

namespace nmm::solve {

namespace {

/// The support's travel and direction at time t (s).
SupportReaction travelled(const SupportDef& sd, double t, double held[2]) {
  SupportReaction r;
  const double speed = std::hypot(sd.velocity.x, sd.velocity.y);
  const double f = table_integral(sd.table, t);  // s: ∫0^t f dt'
  held[0] = sd.velocity.x * f;
  held[1] = sd.velocity.y * f;
  if (speed > 0) {
    r.travel = speed * f;
    r.dx = sd.velocity.x / speed;
    r.dy = sd.velocity.y / speed;
  }
  return r;
}

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

/// The reactions with `increment(e, x, y, out)` adding the step's displacement increment of
/// element e at (x, y) to out[2] (nothing: a state alone).
template <class Increment>
std::vector<SupportReaction> reactions(const Model& model, const RunState& s, const std::vector<std::uint8_t>& removed,
                                       double t, int points, Increment increment) {
  const SceneDef& scene = model.scene();
  const double k_s = model.support_stiffness();
  const double* gp = gauss_points(points);
  const double* gw = gauss_weights(points);
  std::vector<SupportReaction> out(model.support_edges().size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const SupportDef& sd = scene.supports[i];
    double held[2];
    out[i] = travelled(sd, t, held);
    double spring[2] = {0, 0}, insitu[2] = {0, 0};
    for (const BoundaryEdge& be : model.support_edges()[i]) {
      if (!removed.empty() && removed[be.element]) continue;
      const double* a = s.loop_xy.data() + 2 * be.vertex;
      const double* b = s.loop_xy.data() + 2 * be.next;
      const double* ua = s.loop_u.data() + 2 * be.vertex;
      const double* ub = s.loop_u.data() + 2 * be.next;
      const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
      for (int q = 0; q < points; ++q) {
        const double xi = gp[q];
        double u[2] = {(1 - xi) * ua[0] + xi * ub[0], (1 - xi) * ua[1] + xi * ub[1]};
        increment(be.element, a[0] + xi * (b[0] - a[0]), a[1] + xi * (b[1] - a[1]), u);
        for (int d = 0; d < 2; ++d) spring[d] -= k_s * gw[q] * len * (u[d] - held[d]);
      }
      if (scene.insitu_stress.present) insitu_edge_reaction(scene.insitu_stress, a, b, ua, ub, points, insitu);
    }
    if (sd.fix_x) out[i].fx = spring[0] + insitu[0];
    if (sd.fix_y) out[i].fy = spring[1] + insitu[1];
  }
  return out;
}

}  // namespace

std::vector<SupportReaction> support_reactions(const Model& model, const StepContext& step, const Eigen::VectorXd& d) {
  const Configuration& config = step.config;
  const CoverSpace& space = config.space();
  const int nf = space.element_dofs() / 2;
  std::vector<double> phi(static_cast<std::size_t>(nf));
  return reactions(model, step.s, step.removed, step.t_end, space.order() + 2,
                   [&](std::int32_t e, double x, double y, double u[2]) {
                     config.basis(static_cast<std::size_t>(e)).values(x, y, phi.data());
                     const int* g = space.element_unknowns(static_cast<std::size_t>(e));
                     for (int k = 0; k < nf; ++k) {
                       u[0] += phi[k] * d[g[2 * k]];
                       u[1] += phi[k] * d[g[2 * k + 1]];
                     }
                   });
}

std::vector<SupportReaction> support_reactions(const Model& model, const RunState& s,
                                               const std::vector<std::uint8_t>& removed) {
  return reactions(model, s, removed, s.time, model.scene().solver.cover_order + 2,
                   [](std::int32_t, double, double, double*) {});
}

}  // namespace nmm::solve
