// The step's integrators: see integrators.h for the terms and their equations.
#include "solver/discretisation/integrators.h"

#include "solver/discretisation/excavation.h"
#include "solver/discretisation/insitu_stress.h"
#include "common/time_table.h"

namespace nmm::solve {

namespace {
constexpr int kRow[2][2] = {{0, 2}, {2, 1}};  // strain row of (direction s, derivative i)
}  // namespace

ElementGeometry element_geometry(const Configuration& config, const Mesh& mesh,
                                 const std::vector<double>& loop_xy, std::size_t e) {
  ElementGeometry g;
  g.order = config.space().order();
  const std::size_t lb = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - lb;
  if (g.order == 0) {
    g.frame = &config.frame(e);
    g.pm = polygon_moments(loop_xy.data() + 2 * lb, n, g.frame->ox, g.frame->oy);
    g.B = strain_matrix(g.frame->w);
    return g;
  }
  g.basis = &config.basis(e);
  g.m = monomial_moments(loop_xy.data() + 2 * lb, n, g.basis->ox, g.basis->oy, g.basis->h,
                         2 * g.order + 2);
  return g;
}

std::array<double, 2> body_force_per_mass(const SceneDef& scene, double t) {
  return {(scene.has_gravity ? scene.gravity.x : 0.0) - table_value(scene.base_acceleration_x, t, 0.0),
          (scene.has_gravity ? scene.gravity.y : 0.0) - table_value(scene.base_acceleration_y, t, 0.0)};
}

namespace integrators {

void elasticity(const ElementGeometry& g, const Mat3& D, Mat6& k) {
  k.noalias() += g.pm.a * (g.B.transpose() * D * g.B);
}

void elasticity(const ElementGeometry& g, const Mat3& D, Eigen::MatrixXd& k) {
  const ElementBasis& eb = *g.basis;
  const int nf = eb.functions();
  for (int a = 0; a < nf; ++a) {
    const Poly* da[2] = {&eb.dx[a], &eb.dy[a]};
    for (int bb = a; bb < nf; ++bb) {
      const Poly* db[2] = {&eb.dx[bb], &eb.dy[bb]};
      double G[2][2];
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) G[i][j] = integral(*da[i], *db[j], g.m);
      for (int sd = 0; sd < 2; ++sd)
        for (int td = 0; td < 2; ++td) {
          // On the diagonal block the (v, u) coupling stands for both (u, v) and (v, u): K
          // is symmetric, each entry added once.
          if (bb == a && sd < td) continue;
          double v = 0;
          for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j) v += D(kRow[sd][i], kRow[td][j]) * G[i][j];
          k(2 * a + sd, 2 * bb + td) += v;
          if (bb != a || sd != td) k(2 * bb + td, 2 * a + sd) += v;
        }
    }
  }
}

void initial_stress(const ElementGeometry& g, const double* sigma, Vec6& f) {
  f.noalias() += -g.pm.a * (g.B.transpose() * Vec3(sigma[0], sigma[1], sigma[2]));
}

void initial_stress(const ElementGeometry& g, const double* sigma, Eigen::VectorXd& f) {
  const ElementBasis& eb = *g.basis;
  const int nf = eb.functions();
  const std::size_t T = static_cast<std::size_t>(monomial_count(g.order));
  Poly sig[3];
  for (int r = 0; r < 3; ++r) {
    sig[r].degree = g.order;
    for (std::size_t t = 0; t < T; ++t) sig[r].c[t] = sigma[3 * t + r];
  }
  for (int a = 0; a < nf; ++a) {
    const Poly* da[2] = {&eb.dx[a], &eb.dy[a]};
    for (int sd = 0; sd < 2; ++sd)
      for (int i = 0; i < 2; ++i) f[2 * a + sd] -= integral(*da[i], sig[kRow[sd][i]], g.m);
  }
}

void body_force(const ElementGeometry& g, double rho, double bx, double by, Vec6& f) {
  for (int i = 0; i < 3; ++i) {
    const double iw = integral_w(g.frame->w, g.pm, i);
    f[2 * i] += rho * bx * iw;
    f[2 * i + 1] += rho * by * iw;
  }
}

void body_force(const ElementGeometry& g, double rho, double bx, double by, Eigen::VectorXd& f) {
  for (int a = 0; a < g.basis->functions(); ++a) {
    const double ia = integral(g.basis->phi[a], g.m);
    f[2 * a] += rho * bx * ia;
    f[2 * a + 1] += rho * by * ia;
  }
}

void inertia(const ElementGeometry& g, double rho, const InertiaCoefficients& c, const std::int32_t* ec,
             const RunState& s, Mat6& k, Vec6& f) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double mij = rho * integral_ww(g.frame->w, g.pm, i, j);
      k(2 * i, 2 * j) += c.on_d * mij;
      k(2 * i + 1, 2 * j + 1) += c.on_d * mij;
      const int cj = 2 * ec[j];
      f[2 * i] += mij * (c.on_v * s.velocity[cj] + c.on_a * s.accel[cj]);
      f[2 * i + 1] += mij * (c.on_v * s.velocity[cj + 1] + c.on_a * s.accel[cj + 1]);
    }
}

void inertia(const ElementGeometry& g, double rho, const InertiaCoefficients& c, const std::int32_t* ec,
             const RunState& s, int terms, Eigen::MatrixXd& k, Eigen::VectorXd& f) {
  const ElementBasis& eb = *g.basis;
  const int nf = eb.functions(), P = terms;
  const std::size_t dpc = 2 * static_cast<std::size_t>(terms);
  std::vector<double> mass(static_cast<std::size_t>(nf) * nf);
  for (int a = 0; a < nf; ++a)
    for (int bb = a; bb < nf; ++bb) mass[a * nf + bb] = mass[bb * nf + a] = rho * integral(eb.phi[a], eb.phi[bb], g.m);
  for (int a = 0; a < nf; ++a)
    for (int bb = 0; bb < nf; ++bb) {
      const double mab = mass[a * nf + bb];
      k(2 * a, 2 * bb) += c.on_d * mab;
      k(2 * a + 1, 2 * bb + 1) += c.on_d * mab;
      // v0, a0 of term j of the element's cover kb (its own copy, equal to its master's)
      const std::size_t vb = dpc * static_cast<std::size_t>(ec[bb / P]) + 2 * static_cast<std::size_t>(bb % P);
      f[2 * a] += mab * (c.on_v * s.velocity[vb] + c.on_a * s.accel[vb]);
      f[2 * a + 1] += mab * (c.on_v * s.velocity[vb + 1] + c.on_a * s.accel[vb + 1]);
    }
}

}  // namespace integrators

EdgeFrame edge_frame(const Configuration& config, std::int32_t e) {
  return EdgeFrame{&config.basis(static_cast<std::size_t>(e)), config.space().order() + 2};
}

void add_edge_force(const CoverSpace& space, std::int32_t e, const std::vector<double>& f, double factor,
                    Eigen::VectorXd& rhs) {
  const int* g = space.element_unknowns(static_cast<std::size_t>(e));
  for (int i = 0; i < space.element_dofs(); ++i) rhs[g[i]] += factor * f[i];
}

namespace {

/// The in-situ traction σ_insitu·n on the edge a–b (loop displacements ua, ub): the field at a
/// point's position in the mesh as cut (x − u), with n current.
auto insitu_traction(const InsituStressDef& insitu, const double* ua, const double* ub, const double* a,
                     const double* b) {
  return [=, &insitu](double x, double y, double nx, double ny, double* t) {
    const double len2 = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
    const double xi = len2 > 0 ? ((x - a[0]) * (b[0] - a[0]) + (y - a[1]) * (b[1] - a[1])) / len2 : 0;
    const double y0 = y - ((1 - xi) * ua[1] + xi * ub[1]);
    const auto sg = insitu_stress_at(insitu, x, y0);
    t[0] = sg[0] * nx + sg[2] * ny;
    t[1] = sg[2] * nx + sg[1] * ny;
  };
}

/// The in-situ traction forces on boundary edge be in state s.
std::vector<double> insitu_edge_forces(const Configuration& config, const InsituStressDef& insitu,
                                       const RunState& s, const BoundaryEdge& be) {
  const double* a = s.loop_xy.data() + 2 * be.vertex;
  const double* b = s.loop_xy.data() + 2 * be.next;
  return edge_traction_forces(
      edge_frame(config, be.element), a, b,
      insitu_traction(insitu, s.loop_u.data() + 2 * be.vertex, s.loop_u.data() + 2 * be.next, a, b));
}

}  // namespace

void fixed_point_terms(const Model& model, const Configuration& config, const RunState& s,
                       SystemMatrix& system, Eigen::VectorXd& rhs) {
  const CoverSpace& space = config.space();
  const int nd = space.element_dofs(), nf = nd / 2;
  const double kf = model.fixed_point_stiffness();
  Eigen::MatrixXd k(nd, nd);
  std::vector<double> phi(static_cast<std::size_t>(nf));
  for (const TrackedPoint& p : s.fixed) {
    config.shape_values(static_cast<std::size_t>(p.element), p.x, p.y, phi.data());
    k.setZero();
    for (int a = 0; a < nf; ++a)
      for (int bb = 0; bb < nf; ++bb) {
        k(2 * a, 2 * bb) = kf * phi[a] * phi[bb];
        k(2 * a + 1, 2 * bb + 1) = kf * phi[a] * phi[bb];
      }
    system.add_group(p.element, k.data());
    const int* g = space.element_unknowns(p.element);
    for (int a = 0; a < nf; ++a) {
      rhs[g[2 * a]] -= kf * phi[a] * (p.x - p.x0);
      rhs[g[2 * a + 1]] -= kf * phi[a] * (p.y - p.y0);
    }
  }
}

void point_load_terms(const Model& model, const Configuration& config, const RunState& s, double t_end,
                      Eigen::VectorXd& rhs) {
  const SceneDef& scene = model.scene();
  const CoverSpace& space = config.space();
  const int nf = space.element_dofs() / 2;
  std::vector<double> phi(static_cast<std::size_t>(nf));
  for (std::size_t l = 0; l < s.loads.size(); ++l) {
    const TrackedPoint& p = s.loads[l];
    const int* g = space.element_unknowns(p.element);
    const double factor =
        l < scene.load_tables.size() ? table_value(scene.load_tables[l], t_end) : 1.0;
    config.shape_values(static_cast<std::size_t>(p.element), p.x, p.y, phi.data());
    for (int a = 0; a < nf; ++a) {
      rhs[g[2 * a]] += phi[a] * factor * scene.loads[l].force.x;
      rhs[g[2 * a + 1]] += phi[a] * factor * scene.loads[l].force.y;
    }
  }
}

void support_terms(const Model& model, const Configuration& config, const RunState& s,
                   const std::vector<std::uint8_t>& removed, double t_end, SystemMatrix& system,
                   Eigen::VectorXd& rhs) {
  const SceneDef& scene = model.scene();
  const CoverSpace& space = config.space();
  const int nd = space.element_dofs();
  Eigen::MatrixXd k(nd, nd);
  const double* xy = s.loop_xy.data();
  for (std::size_t i = 0; i < model.support_edges().size(); ++i) {
    const SupportDef& sd = scene.supports[i];
    // A moving support holds its edges at u = velocity·∫f dt (f its velocity table, 1 without)
    // at the end of the step: the spring sees the displacement less that.
    const double travel = table_integral(sd.table, t_end);
    const double held[2] = {sd.velocity.x * travel, sd.velocity.y * travel};
    for (const BoundaryEdge& be : model.support_edges()[i]) {
      if (removed[be.element]) continue;
      k.setZero();
      std::vector<double> f(static_cast<std::size_t>(nd), 0.0);
      const double* u0 = s.loop_u.data() + 2 * be.vertex;
      const double* u1 = s.loop_u.data() + 2 * be.next;
      const double ua[2] = {u0[0] - held[0], u0[1] - held[1]}, ub[2] = {u1[0] - held[0], u1[1] - held[1]};
      edge_support(edge_frame(config, be.element), xy + 2 * be.vertex, xy + 2 * be.next, ua, ub,
                   sd.fix_x, sd.fix_y, model.support_stiffness(), k.data(), f.data());
      system.add_group(be.element, k.data());
      add_edge_force(space, be.element, f, 1.0, rhs);
    }
  }
  // Supports start carrying the in-situ stress's reaction (σ_insitu·n in their held
  // directions) as a locked-in force, so that a model in in-situ equilibrium on rollers does not
  // first have to move by σ/k_s to load its springs; the springs carry only what changes.
  if (!scene.insitu_stress.present) return;
  for (std::size_t i = 0; i < model.support_edges().size(); ++i) {
    const SupportDef& sd = scene.supports[i];
    for (const BoundaryEdge& be : model.support_edges()[i]) {
      if (removed[be.element]) continue;
      std::vector<double> f = insitu_edge_forces(config, scene.insitu_stress, s, be);
      for (int c = 0; c < nd / 2; ++c) {
        if (!sd.fix_x) f[2 * c] = 0;
        if (!sd.fix_y) f[2 * c + 1] = 0;
      }
      add_edge_force(space, be.element, f, 1.0, rhs);
    }
  }
}

void traction_terms(const Model& model, const Configuration& config, const RunState& s,
                    const std::vector<std::uint8_t>& removed, double t_end, Eigen::VectorXd& rhs) {
  const SceneDef& scene = model.scene();
  const double* xy = s.loop_xy.data();
  for (std::size_t i = 0; i < model.traction_edges().size(); ++i) {
    const TractionDef& td = scene.tractions[i];
    const double factor = table_value(td.table, t_end);
    for (const BoundaryEdge& be : model.traction_edges()[i]) {
      if (removed[be.element]) continue;
      std::vector<double> f;
      if (td.from_insitu) {
        f = insitu_edge_forces(config, scene.insitu_stress, s, be);
      } else {
        const double sn = td.normal, ss = td.shear, sx = be.sx, sy = be.sy;
        f = edge_traction_forces(edge_frame(config, be.element), xy + 2 * be.vertex, xy + 2 * be.next,
                                 [=](double, double, double nx, double ny, double* t) {
                                   t[0] = sn * nx + ss * sx;
                                   t[1] = sn * ny + ss * sy;
                                 });
      }
      add_edge_force(config.space(), be.element, f, factor, rhs);
    }
  }
}

void water_terms(const Model& model, const Configuration& config, const RunState& s,
                 const std::vector<std::uint8_t>& removed, Eigen::VectorXd& rhs) {
  add_water_forces(
      model.water(), s.loop_xy.data(), removed,
      [&](std::int32_t e) { return edge_frame(config, e); },
      [&](std::int32_t e, const std::vector<double>& f, double factor) {
        add_edge_force(config.space(), e, f, factor, rhs);
      });
}

void interface_traction_terms(const Model& model, const Configuration& config, const RunState& s,
                              const std::vector<std::uint8_t>& removed, Eigen::VectorXd& rhs) {
  const SceneDef& scene = model.scene();
  for (const InterfaceEdge& ie : model.interface_edges()) {
    const BoundaryEdge& be = ie.edge;
    if (removed[be.element]) continue;
    const double factor = interface_traction_factor(s, ie.other_body, scene.solver.excavation_steps);
    if (factor == 0) continue;
    add_edge_force(config.space(), be.element, insitu_edge_forces(config, scene.insitu_stress, s, be),
                   factor, rhs);
  }
}

}  // namespace nmm::solve
