// Absorbing boundaries: see absorbing_boundary.h for the equations.
#include "solver/discretisation/absorbing_boundary.h"

#include <algorithm>
#include <cmath>

#include "common/time_table.h"
#include "solver/discretisation/integrators.h"

namespace nmm::solve {

namespace {

/// The dashpot matrix C_e (2nf × 2nf) and the input forces f_in (2nf) of the edge a → b, with
/// impedances zp = ρ·cp, zs = ρ·cs (Pa·s/m) and input velocity vin (m/s).
void edge_terms(const EdgeFrame& f, const double a[2], const double b[2], double zp, double zs,
                const double vin[2], Eigen::MatrixXd& c, Eigen::VectorXd& f_in) {
  const int nf = f.basis->functions(), nd = 2 * nf;
  c.setZero(nd, nd);
  f_in.setZero(nd);
  const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
  if (!(len > 0)) return;
  const double n[2] = {dy / len, -dx / len}, t[2] = {dx / len, dy / len};  // CCW: outside on the right
  double C[2][2];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) C[i][j] = zp * n[i] * n[j] + zs * t[i] * t[j];
  const double t_in[2] = {2 * (C[0][0] * vin[0] + C[0][1] * vin[1]), 2 * (C[1][0] * vin[0] + C[1][1] * vin[1])};
  std::vector<double> phi(static_cast<std::size_t>(nf));
  const double* gp = gauss_points(f.points);
  const double* gw = gauss_weights(f.points);
  for (int q = 0; q < f.points; ++q) {
    f.basis->values(a[0] + gp[q] * dx, a[1] + gp[q] * dy, phi.data());
    const double w = gw[q] * len;
    for (int i = 0; i < nf; ++i) {
      for (int j = 0; j < nf; ++j)
        for (int r = 0; r < 2; ++r)
          for (int s = 0; s < 2; ++s) c(2 * i + r, 2 * j + s) += w * phi[i] * phi[j] * C[r][s];
      f_in[2 * i] += w * phi[i] * t_in[0];
      f_in[2 * i + 1] += w * phi[i] * t_in[1];
    }
  }
}

/// Visits every absorbing edge of an element not excavated in `step` with its C_e, f_in(t_end)
/// and element e: visit(e, C_e, f_in).
template <class Visit>
void for_absorbing_edges(const Model& model, const StepContext& step, Visit visit) {
  const SceneDef& scene = model.scene();
  const double* xy = step.s.loop_xy.data();
  Eigen::MatrixXd c;
  Eigen::VectorXd f_in;
  for (std::size_t i = 0; i < model.absorbing_edges().size(); ++i) {
    const AbsorbingDef& ad = scene.absorbing[i];
    const double vin[2] = {table_value(ad.input_x, step.t_end, 0.0), table_value(ad.input_y, step.t_end, 0.0)};
    for (const BoundaryEdge& be : model.absorbing_edges()[i]) {
      if (step.removed[be.element]) continue;
      const std::size_t e = static_cast<std::size_t>(be.element);
      const Mat3& D = model.elasticity(e);
      const double rho = model.density(e);
      edge_terms(edge_frame(step.config, be.element), xy + 2 * be.vertex, xy + 2 * be.next,
                 std::sqrt(rho * D(0, 0)), std::sqrt(rho * D(2, 2)), vin, c, f_in);
      visit(e, c, f_in);
    }
  }
}

/// v0 and a0 of element e's local unknowns (the state's, per cover: a tied cover's are its
/// master's), as the inertia term reads them.
void element_motion(const StepContext& step, const Mesh& mesh, std::size_t e, Eigen::VectorXd& v0,
                    Eigen::VectorXd& a0) {
  const CoverSpace& space = step.config.space();
  const int nf = space.element_dofs() / 2, P = space.terms();
  const std::size_t dpc = static_cast<std::size_t>(space.dofs_per_cover());
  const std::int32_t* ec = &mesh.element_covers[3 * e];
  v0.resize(2 * nf);
  a0.resize(2 * nf);
  for (int a = 0; a < nf; ++a) {
    const std::size_t at = dpc * static_cast<std::size_t>(ec[a / P]) + 2 * static_cast<std::size_t>(a % P);
    for (int r = 0; r < 2; ++r) {
      v0[2 * a + r] = step.s.velocity[at + r];
      a0[2 * a + r] = step.s.accel[at + r];
    }
  }
}

/// The dashpots act in dynamic steps (with the inertia coefficients of one).
bool dashpots_act(const Model& model, const StepContext& step) {
  return model.scene().solver.dynamic && step.inertia.on_v > 0;
}

}  // namespace

void absorbing_terms(const Model& model, const StepContext& step, SystemMatrix& system, Eigen::VectorXd& rhs) {
  if (dashpots_act(model, step)) {
    const double kc = step.inertia.on_v;                // 1/(βΔt)
    const double cv = step.dt * step.inertia.on_v - 1;  // 1/β − 1
    const double ca = step.dt * step.inertia.on_a;      // (1/(2β) − 1)·Δt
    const CoverSpace& space = step.config.space();
    Eigen::VectorXd v0, a0, f;
    Eigen::MatrixXd k;
    for_absorbing_edges(model, step, [&](std::size_t e, const Eigen::MatrixXd& c, const Eigen::VectorXd& f_in) {
      k = kc * c;
      system.add_group(e, k.data());
      element_motion(step, model.mesh(), e, v0, a0);
      f.noalias() = c * (cv * v0 + ca * a0);
      f += f_in;
      const int* g = space.element_unknowns(e);
      for (Eigen::Index i = 0; i < f.size(); ++i) rhs[g[i]] += f[i];
    });
  }
  const std::vector<double>& r = step.s.absorbing_reaction;
  for (std::size_t i = 0; i < r.size(); ++i) rhs[static_cast<Eigen::Index>(i)] += r[i];
}

std::vector<double> absorbing_key(const SceneDef& scene) {
  if (scene.absorbing.empty()) return {};
  std::vector<double> key{static_cast<double>(scene.absorbing.size())};
  for (const AbsorbingDef& a : scene.absorbing) {
    key.push_back(static_cast<double>(a.points.size()));
    for (const Vec2& p : a.points) {
      key.push_back(p.x);
      key.push_back(p.y);
    }
  }
  return key;
}

bool absorbing_reaction_due(const SceneDef& scene, const RunState& s) {
  return !scene.absorbing.empty() && s.absorbing_key != absorbing_key(scene);
}

std::vector<double> absorbing_reaction_of(const Model& model, const Configuration& config,
                                          const Eigen::VectorXd& residual, int cover_unknowns) {
  const CoverSpace& space = config.space();
  std::vector<std::uint8_t> held(static_cast<std::size_t>(cover_unknowns), 0);
  for (const auto& edges : model.absorbing_edges())
    for (const BoundaryEdge& be : edges) {
      const int* g = space.element_unknowns(static_cast<std::size_t>(be.element));
      for (int i = 0; i < space.element_dofs(); ++i) held[static_cast<std::size_t>(g[i])] = 1;
    }
  std::vector<double> r(static_cast<std::size_t>(cover_unknowns), 0.0);
  for (std::size_t i = 0; i < r.size(); ++i)
    if (held[i]) r[i] = -residual[static_cast<Eigen::Index>(i)];  // the force that balances it
  return r;
}

namespace {

/// –, the linear weight λ_k of element e's k-th cover at (x, y) as cut: the barycentric
/// coordinate in the triangle of its three covers' nodes (the cover function's weight at order 0).
double cover_weight(const Mesh& mesh, std::size_t e, int k, double x, double y) {
  double nx[3], ny[3];
  for (int i = 0; i < 3; ++i) {
    const auto c = static_cast<std::size_t>(mesh.element_covers[3 * e + static_cast<std::size_t>(i)]);
    const auto node = static_cast<std::size_t>(mesh.cover_node[c]);
    nx[i] = mesh.node_xy[2 * node];
    ny[i] = mesh.node_xy[2 * node + 1];
  }
  const double twice = (nx[1] - nx[0]) * (ny[2] - ny[0]) - (nx[2] - nx[0]) * (ny[1] - ny[0]);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  return ((nx[i] - x) * (ny[j] - y) - (nx[j] - x) * (ny[i] - y)) / twice;
}

}  // namespace

std::vector<double> absorbing_reaction_onto(const std::vector<double>& r, const CoverSpace& old_space,
                                            const std::vector<std::int32_t>& cover_parent, const Model& model,
                                            const CoverSpace& space) {
  if (r.empty()) return {};
  const Mesh& mesh = model.mesh();
  const std::size_t nc = mesh.cover_count(), dpc = static_cast<std::size_t>(space.dofs_per_cover());
  // Each new cover's weight on the absorbing edges (w) and over its elements (a), as cut.
  std::vector<double> w(nc, 0.0), a(nc, 0.0);
  for (const auto& edges : model.absorbing_edges())
    for (const BoundaryEdge& be : edges) {
      const auto e = static_cast<std::size_t>(be.element);
      const double* p = &mesh.loop_xy[2 * static_cast<std::size_t>(be.vertex)];
      const double* q = &mesh.loop_xy[2 * static_cast<std::size_t>(be.next)];
      const double len = std::hypot(q[0] - p[0], q[1] - p[1]), mx = 0.5 * (p[0] + q[0]), my = 0.5 * (p[1] + q[1]);
      for (int k = 0; k < 3; ++k)
        w[static_cast<std::size_t>(mesh.element_covers[3 * e + static_cast<std::size_t>(k)])] +=
            len * cover_weight(mesh, e, k, mx, my);
    }
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    // The loop's area and centroid (shoelace).
    const auto b = static_cast<std::size_t>(mesh.element_loop_offset[e]), end = static_cast<std::size_t>(mesh.element_loop_offset[e + 1]);
    double area2 = 0, cx = 0, cy = 0;
    for (std::size_t v = b; v < end; ++v) {
      const std::size_t u = v + 1 < end ? v + 1 : b;
      const double x0 = mesh.loop_xy[2 * v], y0 = mesh.loop_xy[2 * v + 1], x1 = mesh.loop_xy[2 * u], y1 = mesh.loop_xy[2 * u + 1];
      const double c = x0 * y1 - x1 * y0;
      area2 += c;
      cx += (x0 + x1) * c;
      cy += (y0 + y1) * c;
    }
    if (!(std::abs(area2) > 0)) continue;
    cx /= 3 * area2;
    cy /= 3 * area2;
    for (int k = 0; k < 3; ++k)
      a[static_cast<std::size_t>(mesh.element_covers[3 * e + static_cast<std::size_t>(k)])] +=
          0.5 * std::abs(area2) * cover_weight(mesh, e, k, cx, cy);
  }
  // Per old block of unknowns (a cover's, shared by the covers tied to it): the new covers it
  // goes to, and their weights' sums.
  const std::size_t old_blocks = r.size() / dpc;
  std::vector<double> w_sum(old_blocks, 0.0), a_sum(old_blocks, 0.0);
  std::vector<int> first_new(old_blocks, -1), pieces(old_blocks, 0);
  std::vector<std::uint8_t> one_block(old_blocks, 1);  // all its covers go to one new block
  const auto old_block = [&](std::size_t c) {
    return static_cast<std::size_t>(old_space.first_unknown(static_cast<std::size_t>(cover_parent[c]))) / dpc;
  };
  for (std::size_t c = 0; c < nc; ++c) {
    const std::size_t U = old_block(c);
    const int u = space.first_unknown(c);
    w_sum[U] += w[c];
    a_sum[U] += a[c];
    ++pieces[U];
    if (first_new[U] < 0) first_new[U] = u;
    else if (first_new[U] != u) one_block[U] = 0;
  }
  std::vector<double> out(static_cast<std::size_t>(space.unknowns()), 0.0);
  std::vector<std::uint8_t> copied(old_blocks, 0);
  for (std::size_t c = 0; c < nc; ++c) {
    const std::size_t U = old_block(c);
    const auto u = static_cast<std::size_t>(space.first_unknown(c));
    if (one_block[U]) {  // not parted: the same force on the same covers, bit for bit
      if (copied[U]) continue;
      copied[U] = 1;
      for (std::size_t j = 0; j < dpc; ++j) out[u + j] = r[dpc * U + j];
      continue;
    }
    const double share = w_sum[U] > 0 ? w[c] / w_sum[U] : a_sum[U] > 0 ? a[c] / a_sum[U] : 1.0 / pieces[U];
    for (std::size_t j = 0; j < dpc; ++j) out[u + j] += share * r[dpc * U + j];
  }
  return out;
}

AbsorbingWork absorbing_work(const Model& model, const StepContext& step, const Eigen::VectorXd& d) {
  AbsorbingWork w;
  if (dashpots_act(model, step)) {
    const double kc = step.inertia.on_v, cv = step.dt * step.inertia.on_v - 1, ca = step.dt * step.inertia.on_a;
    const CoverSpace& space = step.config.space();
    Eigen::VectorXd v0, a0, de(space.element_dofs()), v1;
    for_absorbing_edges(model, step, [&](std::size_t e, const Eigen::MatrixXd& c, const Eigen::VectorXd& f_in) {
      const int* g = space.element_unknowns(e);
      for (int i = 0; i < space.element_dofs(); ++i) de[i] = d[g[i]];
      element_motion(step, model.mesh(), e, v0, a0);
      v1 = kc * de - cv * v0 - ca * a0;  // Newmark's velocity at the step's end
      w.absorbed += v1.dot(c * de);
      w.loads += f_in.dot(de);
    });
  }
  const std::vector<double>& r = step.s.absorbing_reaction;
  for (std::size_t i = 0; i < r.size(); ++i) w.loads += r[i] * d[static_cast<Eigen::Index>(i)];
  return w;
}

}  // namespace nmm::solve
