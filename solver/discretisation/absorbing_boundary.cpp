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
