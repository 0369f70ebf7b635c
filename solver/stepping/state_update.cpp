// The state moved on by a step's increment: see state_update.h for the equations.
#include "solver/stepping/state_update.h"

#include <algorithm>
#include <cmath>

#include "solver/discretisation/newmark.h"

namespace nmm::solve {

namespace {

/// m, the displacement of point (x, y) of element e under its unknowns' increment de: at order 0
/// by the element's linear weights in its frame (the first-order code's path and round-off), at
/// n ≥ 1 by its shape functions (phi: scratch of element_dofs()/2 values). The state update and
/// the contact reach's check (largest_loop_move) move loop vertices by this one rule.
struct PointMove {
  double ux = 0, uy = 0;
};
PointMove point_move(const Configuration& config, std::size_t e, double x, double y, const double* de,
                     double* phi) {
  PointMove m;
  if (config.space().order() == 0) {
    const ElementFrame& f = config.frame(e);
    for (int k = 0; k < 3; ++k) {
      const double w = f.w.at(k, x - f.ox, y - f.oy);
      m.ux += w * de[2 * k];
      m.uy += w * de[2 * k + 1];
    }
  } else {
    config.basis(e).values(x, y, phi);
    const int nf = config.space().element_dofs() / 2;
    for (int a = 0; a < nf; ++a) {
      m.ux += phi[a] * de[2 * a];
      m.uy += phi[a] * de[2 * a + 1];
    }
  }
  return m;
}

/// Element e's loop vertices moved by point_move.
void move_loop_vertices(const Mesh& mesh, const Configuration& config, std::size_t e, const double* de,
                        double* phi, RunState& s) {
  for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v) {
    const PointMove m = point_move(config, e, s.loop_xy[2 * v], s.loop_xy[2 * v + 1], de, phi);
    s.loop_xy[2 * v] += m.ux;
    s.loop_xy[2 * v + 1] += m.uy;
    s.loop_u[2 * v] += m.ux;
    s.loop_u[2 * v + 1] += m.uy;
  }
}

/// n = 0 (constant strain; the first-order code's path and round-off): σ_e += D·B·d_e, and the
/// element's loop vertices move by the linear weights.
void update_constant_element(const Model& model, const Configuration& config, std::size_t e,
                             const double* de, RunState& s) {
  const Mesh& mesh = model.mesh();
  const ElementFrame& f = config.frame(e);
  const Vec6 de6 = Eigen::Map<const Vec6>(de);
  const Vec3 ds = model.elasticity(e) * (strain_matrix(f.w) * de6);
  for (int i = 0; i < 3; ++i) s.stress[3 * e + i] += ds[i];
  move_loop_vertices(mesh, config, e, de, nullptr, s);
}

/// n ≥ 1: Δσ = D·B·d as strain polynomials of degree n, D per coefficient; the loop vertices
/// move by the element's shape functions. phi: scratch of element_dofs()/2 values.
void update_polynomial_element(const Model& model, const Configuration& config, std::size_t e,
                               const double* de, double* phi, RunState& s) {
  const Mesh& mesh = model.mesh();
  const CoverSpace& space = config.space();
  const int nf = space.element_dofs() / 2;
  const std::size_t T = static_cast<std::size_t>(space.terms());
  const ElementBasis& eb = config.basis(e);
  Poly eps[3];
  for (int r = 0; r < 3; ++r) eps[r].degree = space.order();
  for (int a = 0; a < nf; ++a)
    for (std::size_t t = 0; t < T; ++t) {
      eps[0].c[t] += eb.dx[a].c[t] * de[2 * a];
      eps[1].c[t] += eb.dy[a].c[t] * de[2 * a + 1];
      eps[2].c[t] += eb.dy[a].c[t] * de[2 * a] + eb.dx[a].c[t] * de[2 * a + 1];
    }
  const Mat3& D = model.elasticity(e);
  for (std::size_t t = 0; t < T; ++t) {
    const Vec3 ds = D * Vec3(eps[0].c[t], eps[1].c[t], eps[2].c[t]);
    for (int r = 0; r < 3; ++r) s.stress[3 * (T * e + t) + r] += ds[r];
  }
  move_loop_vertices(mesh, config, e, de, phi, s);
}

}  // namespace

void update_state(const Model& model, const StepContext& step, const Eigen::VectorXd& d, RunState& s) {
  const Configuration& config = step.config;
  const double dt = step.dt;
  const CoverSpace& space = config.space();
  const int nd = space.element_dofs();
  std::vector<double> de(static_cast<std::size_t>(nd)), phi(static_cast<std::size_t>(nd / 2));
  for (std::size_t e = 0; e < model.mesh().element_count(); ++e) {
    const int* g = space.element_unknowns(e);
    for (int i = 0; i < nd; ++i) de[i] = d[g[i]];
    if (space.order() == 0)
      update_constant_element(model, config, e, de.data(), s);
    else
      update_polynomial_element(model, config, e, de.data(), phi.data(), s);
  }
  for (std::vector<TrackedPoint>* points : {&s.fixed, &s.loads, &s.measure})
    config.move_points(d, *points);
  config.move_cover_nodes(d, s.cover_xy);
  const SolverDef& sv = model.scene().solver;
  const bool dynamic = sv.dynamic;
  const double beta = step.beta;
  double max_d = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i) max_d = std::max(max_d, std::abs(d[i]));
  // Per cover; a tied cover takes its master's increment (and so keeps its master's velocity).
  const std::size_t dpc = static_cast<std::size_t>(space.dofs_per_cover());
  for (std::size_t i = 0; i < s.cover_u.size(); ++i) {
    const double di = d[space.first_unknown(i / dpc) + static_cast<int>(i % dpc)];
    s.cover_u[i] += di;
    if (dynamic) newmark_advance(di, dt, beta, sv.dynamic_factor, s.velocity[i], s.accel[i]);
  }
  s.max_step_displacement = std::max(s.max_step_displacement, max_d);
  s.accel_known = dynamic;
}

double largest_loop_move(const Model& model, const StepContext& step, const Eigen::VectorXd& d,
                         const RunState& s) {
  const Mesh& mesh = model.mesh();
  const Configuration& config = step.config;
  const CoverSpace& space = config.space();
  const int nd = space.element_dofs();
  std::vector<double> de(static_cast<std::size_t>(nd)), phi(static_cast<std::size_t>(nd / 2));
  double largest2 = 0;  // m², the largest |u|² so far
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const int* g = space.element_unknowns(e);
    for (int i = 0; i < nd; ++i) de[i] = d[g[i]];
    for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v) {
      const PointMove m = point_move(config, e, s.loop_xy[2 * v], s.loop_xy[2 * v + 1], de.data(), phi.data());
      largest2 = std::max(largest2, m.ux * m.ux + m.uy * m.uy);
    }
  }
  return std::sqrt(largest2);
}

}  // namespace nmm::solve
