// Energy terms of a run: see energy.h for the formulas, docs/energy.md for their derivation.
#include "solver/output/energy.h"

#include <charconv>
#include <cmath>
#include <filesystem>

#include "solver/discretisation/element_integration.h"
#include "solver/discretisation/insitu_stress.h"
#include "common/time_table.h"
#include "common/atomic_file.h"
#include "solver/reinforcement/bolt_system.h"

namespace nmm::solve {

EnergyMeter::EnergyMeter(const Model& model, const CoverSpace* space)
    : model_(&model), mesh_(&model.mesh()), scene_(&model.scene()),
      space_(space && space->order() > 0 ? space : nullptr) {
  const SceneDef& scene = *scene_;
  initial_geometry();
  shaking_ = !scene.base_acceleration_x.empty() || !scene.base_acceleration_y.empty();
  for (const SupportDef& sd : scene.supports) moving_supports_ |= sd.velocity.x != 0 || sd.velocity.y != 0;
}

void EnergyMeter::initial_geometry() {
  const Mesh& mesh = *mesh_;
  const std::size_t ne = mesh.element_count();
  area0_.resize(ne);
  cx0_.resize(ne);
  cy0_.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::size_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
    const PolygonMoments m = polygon_moments(mesh.loop_xy.data() + 2 * b, n, 0, 0);
    area0_[e] = m.a;
    cx0_[e] = m.a != 0 ? m.sx / m.a : 0;
    cy0_[e] = m.a != 0 ? m.sy / m.a : 0;
  }
}

void EnergyMeter::carry_over(const Model& model, const CoverSpace* space, const pre::RecutMap& map,
                             const RunState& s) {
  model_ = &model;
  mesh_ = &model.mesh();
  scene_ = &model.scene();
  space_ = space && space->order() > 0 ? space : nullptr;
  initial_geometry();  // a piece starts as it was cut: its share of its parent's area and centroid
  // A vertex kept its place: its last displacement is the one it had; a vertex the crack made
  // starts from where it is (the step's work there is left out: it is the crack's few vertices).
  if (!prev_loop_u_.empty()) {
    std::vector<double> prev = s.loop_u;
    for (std::size_t v = 0; v < map.vertex_parent.size(); ++v)
      if (map.vertex_parent[v] >= 0)
        for (int d = 0; d < 2; ++d) prev[2 * v + d] = prev_loop_u_[2 * static_cast<std::size_t>(map.vertex_parent[v]) + d];
    prev_loop_u_ = std::move(prev);
  }
  // A piece's last centroid: its centroid now less its parent's move since (the parent's centroid
  // now being the area-weighted one of its pieces).
  if (!prev_cx_.empty()) {
    std::vector<double> cx, cy;
    centroids(s, cx, cy);
    const std::size_t parents = prev_cx_.size();
    std::vector<double> area(parents, 0), mx(parents, 0), my(parents, 0);
    for (std::size_t e = 0; e < cx.size(); ++e) {
      const std::size_t p = static_cast<std::size_t>(map.element_parent[e]);
      area[p] += area0_[e];
      mx[p] += area0_[e] * cx[e];
      my[p] += area0_[e] * cy[e];
    }
    std::vector<double> px(cx.size()), py(cx.size());
    for (std::size_t e = 0; e < cx.size(); ++e) {
      const std::size_t p = static_cast<std::size_t>(map.element_parent[e]);
      px[e] = cx[e] - (mx[p] / area[p] - prev_cx_[p]);
      py[e] = cy[e] - (my[p] / area[p] - prev_cy_[p]);
    }
    prev_cx_ = std::move(px);
    prev_cy_ = std::move(py);
  }
}

EnergyRow EnergyMeter::state_terms(const RunState& s, const std::vector<Contact>& contacts) const {
  EnergyRow r;
  r.step = s.step;
  r.time = s.time;
  const double gx = scene_->has_gravity ? scene_->gravity.x : 0.0;
  const double gy = scene_->has_gravity ? scene_->gravity.y : 0.0;
  // The state's own configuration (its cover positions, not those of the step's start).
  Configuration config(*mesh_, space_);
  config.place(s.cover_xy);
  for (std::size_t e = 0; e < mesh_->element_count(); ++e) {
    if (removed(s, static_cast<std::int32_t>(e))) continue;
    const double density = model_->density(e);
    const std::int32_t* ec = &mesh_->element_covers[3 * e];
    const double ox = config.frame(e).ox, oy = config.frame(e).oy;
    const std::size_t b = mesh_->element_loop_offset[e], n = mesh_->element_loop_offset[e + 1] - b;
    const PolygonMoments m = polygon_moments(s.loop_xy.data() + 2 * b, n, ox, oy);
    const TriangleWeights& w = config.frame(e).w;
    if (space_ && w.twice_area > 0) {
      // Cover order n ≥ 1: the velocity field and the stress polynomial, integrated exactly.
      const int P = space_->terms(), nf = 3 * P, order = space_->order();
      const std::size_t dpc = static_cast<std::size_t>(space_->dofs_per_cover());
      const ElementBasis& basis = config.basis(e);
      const MonomialMoments mm = monomial_moments(s.loop_xy.data() + 2 * b, n, ox, oy,
                                                  space_->scale(), 2 * order + 2);
      if (!s.velocity.empty()) {
        Poly vx, vy;
        vx.degree = vy.degree = order + 1;
        for (int a = 0; a < nf; ++a) {
          // v of term j of the element's cover k (its own copy, equal to its master's)
          const std::size_t va = dpc * static_cast<std::size_t>(ec[a / P]) + 2 * static_cast<std::size_t>(a % P);
          for (int i = 0; i < basis.phi[a].size(); ++i) {
            vx.c[i] += basis.phi[a].c[i] * s.velocity[va];
            vy.c[i] += basis.phi[a].c[i] * s.velocity[va + 1];
          }
        }
        r.kinetic += 0.5 * density * (integral(vx, vx, mm) + integral(vy, vy, mm));
      }
      const std::size_t T = static_cast<std::size_t>(P);
      Poly sig[3];
      for (int q = 0; q < 3; ++q) {
        sig[q].degree = order;
        for (std::size_t t = 0; t < T; ++t) sig[q].c[t] = s.stress[3 * (T * e + t) + q];
      }
      const Mat3& c = model_->compliance(e);
      for (int q = 0; q < 3; ++q)
        for (int l = 0; l < 3; ++l)
          if (c(q, l) != 0) r.strain += 0.5 * c(q, l) * integral(sig[q], sig[l], mm);
    } else if (!space_) {
      // Kinetic: the consistent mass, as the step assembles it.
      if (w.twice_area > 0 && !s.velocity.empty())
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) {
            const double vv = s.velocity[2 * ec[k]] * s.velocity[2 * ec[l]] +
                              s.velocity[2 * ec[k] + 1] * s.velocity[2 * ec[l] + 1];
            r.kinetic += 0.5 * density * integral_ww(w, m, k, l) * vv;
          }
      // Strain: ½ A σᵀ D⁻¹ σ.
      const Vec3 sigma(s.stress[3 * e], s.stress[3 * e + 1], s.stress[3 * e + 2]);
      r.strain += 0.5 * m.a * sigma.dot(model_->compliance(e) * sigma);
    }
    // Gravity: the centroid's drop, times the element's (conserved) mass.
    if (m.a != 0) {
      const double cx = ox + m.sx / m.a, cy = oy + m.sy / m.a;
      r.gravity -= density * area0_[e] * (gx * (cx - cx0_[e]) + gy * (cy - cy0_[e]));
    }
  }
  for (const TrackedPoint& f : s.fixed) {
    const double dx = f.x - f.x0, dy = f.y - f.y0;
    r.springs += 0.5 * model_->fixed_point_stiffness() * (dx * dx + dy * dy);
  }
  // Supports: e = u − h linear along the edge, ∫ e² ds = L (ea² + ea·eb + eb²) / 3 per component.
  for (std::size_t i = 0; i < model_->support_edges().size(); ++i) {
    const std::array<double, 2> h = held(i, s.time);
    for (const BoundaryEdge& be : model_->support_edges()[i]) {
      if (removed(s, be.element)) continue;
      const std::int32_t a = be.vertex, b = be.next;
      const double len = std::hypot(s.loop_xy[2 * b] - s.loop_xy[2 * a],
                                    s.loop_xy[2 * b + 1] - s.loop_xy[2 * a + 1]);
      for (int d = 0; d < 2; ++d) {
        if (!(d == 0 ? scene_->supports[i].fix_x : scene_->supports[i].fix_y)) continue;
        const double ua = s.loop_u[2 * a + d] - h[d], ub = s.loop_u[2 * b + d] - h[d];
        r.springs += 0.5 * model_->support_stiffness() * len * (ua * ua + ua * ub + ub * ub) / 3;
      }
    }
  }
  for (const Contact& c : contacts)
    if (c.state != ContactState::open)
      r.springs += 0.5 * std::max(0.0, c.normal_force * -c.gap) + 0.5 * std::abs(c.shear_force * c.shear_el);
  for (std::size_t b = 0; b < s.bolts.size(); ++b) r.springs += bolt_elastic_energy(scene_->bolts[b], s.bolts[b]);
  return r;
}

void EnergyMeter::after_step(const RunState& s, const std::vector<Contact>& contacts, bool keep) {
  EnergyRow r = state_terms(s, contacts);
  if (started_) {
    for (std::size_t l = 0; l < s.loads.size() && l < scene_->loads.size(); ++l) {
      const double factor =
          l < scene_->load_tables.size() ? table_value(scene_->load_tables[l], s.time) : 1.0;
      load_work_ += factor * (scene_->loads[l].force.x * (s.loads[l].x - load_x_[l]) +
                              scene_->loads[l].force.y * (s.loads[l].y - load_y_[l]));
    }
    for (const Contact& c : contacts) {
      if (c.state == ContactState::sliding) friction_ += std::abs(c.shear_force) * std::abs(c.shear - c.shear_el);
      friction_ -= c.normal_force * c.dilation_step;  // the asperities' opening (0 but Barton–Bandis)
    }
    const double supports = support_work(s);
    support_work_ += supports;
    load_work_ += traction_work(s) + shaking_work(s) + water_work(s) + supports;
  }
  if (!model_->traction_edges().empty() || model_->water().active() || moving_supports_) prev_loop_u_ = s.loop_u;
  prev_time_ = s.time;
  if (shaking_) centroids(s, prev_cx_, prev_cy_);
  load_x_.resize(s.loads.size());
  load_y_.resize(s.loads.size());
  for (std::size_t l = 0; l < s.loads.size(); ++l) {
    load_x_[l] = s.loads[l].x;
    load_y_[l] = s.loads[l].y;
  }
  const double mech = r.kinetic + r.strain + r.gravity + r.springs;
  // The bolts' plastic work and the absorbing boundaries' work, as the steps counted them in the
  // state (bolt_system.h, absorbing_boundary.h), since this run's first call.
  double plastic = 0;
  for (const BoltState& b : s.bolts) plastic += b.plastic_work;
  if (!started_) {
    mech0_ = mech;
    plastic0_ = plastic;
    absorbed0_ = s.absorbed_work;
    absorbing_load0_ = s.absorbing_load_work;
  }
  started_ = true;
  r.load_work = load_work_ + (s.absorbing_load_work - absorbing_load0_);
  r.support_work = support_work_;
  r.friction = friction_ + (plastic - plastic0_);
  r.absorbed = s.absorbed_work - absorbed0_;
  r.residual = r.load_work - r.friction - r.absorbed - (mech - mech0_);
  last_ = r;
  if (keep) {
    rows_.push_back(r);
    last_kept_step_ = r.step;
  }
}

bool EnergyMeter::removed(const RunState& s, std::int32_t element) const {
  const std::int32_t body = mesh_->element_body[element];
  return static_cast<std::size_t>(body) < s.body_removed.size() && s.body_removed[body];
}

void EnergyMeter::centroids(const RunState& s, std::vector<double>& cx, std::vector<double>& cy) const {
  const std::size_t ne = mesh_->element_count();
  cx.assign(ne, 0);
  cy.assign(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::size_t b = mesh_->element_loop_offset[e], n = mesh_->element_loop_offset[e + 1] - b;
    const PolygonMoments m = polygon_moments(s.loop_xy.data() + 2 * b, n, 0, 0);
    if (m.a != 0) cx[e] = m.sx / m.a, cy[e] = m.sy / m.a;
  }
}

double EnergyMeter::traction_work(const RunState& s) const {
  // ∫ t·Δu ds on each edge, Δu linear between its ends, by the two-point Gauss rule (exact for
  // a constant t; for σ_insitu·n, linear along the edge, too).
  static constexpr double kGauss[2] = {0.21132486540518711775, 0.78867513459481288225};
  double w = 0;
  if (prev_loop_u_.size() != s.loop_u.size()) return 0;
  for (std::size_t i = 0; i < model_->traction_edges().size(); ++i) {
    const TractionDef& td = scene_->tractions[i];
    const double factor = table_value(td.table, s.time);
    for (const BoundaryEdge& be : model_->traction_edges()[i]) {
      if (removed(s, be.element)) continue;
      const double* a = s.loop_xy.data() + 2 * be.vertex;
      const double* b = s.loop_xy.data() + 2 * be.next;
      const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
      if (!(len > 0)) continue;
      const double nx = dy / len, ny = -dx / len;  // CCW loop: outside on the right
      for (double xi : kGauss) {
        double t[2];
        if (td.from_insitu) {
          const double uy = (1 - xi) * s.loop_u[2 * be.vertex + 1] + xi * s.loop_u[2 * be.next + 1];
          const auto sg = insitu_stress_at(scene_->insitu_stress, a[0] + xi * dx, a[1] + xi * dy - uy);
          t[0] = sg[0] * nx + sg[2] * ny;
          t[1] = sg[2] * nx + sg[1] * ny;
        } else {
          t[0] = td.normal * nx + td.shear * be.sx;
          t[1] = td.normal * ny + td.shear * be.sy;
        }
        for (int d = 0; d < 2; ++d) {
          const double du_a = s.loop_u[2 * be.vertex + d] - prev_loop_u_[2 * be.vertex + d];
          const double du_b = s.loop_u[2 * be.next + d] - prev_loop_u_[2 * be.next + d];
          w += 0.5 * len * factor * t[d] * ((1 - xi) * du_a + xi * du_b);
        }
      }
    }
  }
  return w;
}

double EnergyMeter::water_work(const RunState& s) const {
  // ∫ −p·n·Δu ds on each wet face, per piece where p is linear (joint_water.h): the two-point
  // Gauss rule is exact for p times the linear Δu.
  static constexpr double kGauss[2] = {0.21132486540518711775, 0.78867513459481288225};
  const JointWater& water = model_->water();
  if (!water.active() || prev_loop_u_.size() != s.loop_u.size()) return 0;
  double w = 0;
  for (std::size_t i = 0; i < water.edges().size(); ++i) {
    const BoundaryEdge& be = water.edges()[i];
    if (removed(s, be.element)) continue;
    const int joint = water.edge_joint()[i];
    const double* a = s.loop_xy.data() + 2 * be.vertex;
    const double* b = s.loop_xy.data() + 2 * be.next;
    const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
    if (!(len > 0)) continue;
    const double nx = dy / len, ny = -dx / len;  // CCW loop: outside on the right
    for (const auto& [t0, t1] : water.linear_pieces(joint, a, b))
      for (double xi : kGauss) {
        const double t = t0 + xi * (t1 - t0);
        const double p = water.pressure_at(joint, a[0] + t * dx, a[1] + t * dy);
        for (int d = 0; d < 2; ++d) {
          const double du_a = s.loop_u[2 * be.vertex + d] - prev_loop_u_[2 * be.vertex + d];
          const double du_b = s.loop_u[2 * be.next + d] - prev_loop_u_[2 * be.next + d];
          w += 0.5 * (t1 - t0) * len * (-p) * (d == 0 ? nx : ny) * ((1 - t) * du_a + t * du_b);
        }
      }
  }
  return w;
}

std::array<double, 2> EnergyMeter::held(std::size_t support, double t) const {
  const SupportDef& sd = scene_->supports[support];
  const double travel = table_integral(sd.table, t);  // as solver/discretisation/integrators.cpp holds it
  return {sd.velocity.x * travel, sd.velocity.y * travel};
}

double EnergyMeter::support_work(const RunState& s) const {
  // −k_s ∫ ē·Δh ds on each held component, ē = ½(e_prev + e_now), e = u − h linear along the
  // edge and Δh uniform: L·Δh·(ē_a + ē_b)/2.
  if (!moving_supports_ || prev_loop_u_.size() != s.loop_u.size()) return 0;
  double w = 0;
  for (std::size_t i = 0; i < model_->support_edges().size(); ++i) {
    const SupportDef& sd = scene_->supports[i];
    if (sd.velocity.x == 0 && sd.velocity.y == 0) continue;
    const std::array<double, 2> h0 = held(i, prev_time_), h1 = held(i, s.time);
    for (const BoundaryEdge& be : model_->support_edges()[i]) {
      if (removed(s, be.element)) continue;
      const std::int32_t a = be.vertex, b = be.next;
      const double len = std::hypot(s.loop_xy[2 * b] - s.loop_xy[2 * a], s.loop_xy[2 * b + 1] - s.loop_xy[2 * a + 1]);
      for (int d = 0; d < 2; ++d) {
        if (!(d == 0 ? sd.fix_x : sd.fix_y)) continue;
        auto mean_e = [&](std::int32_t v) {
          return 0.5 * ((prev_loop_u_[2 * v + d] - h0[d]) + (s.loop_u[2 * v + d] - h1[d]));
        };
        w -= model_->support_stiffness() * len * (h1[d] - h0[d]) * 0.5 * (mean_e(a) + mean_e(b));
      }
    }
  }
  return w;
}

double EnergyMeter::shaking_work(const RunState& s) const {
  if (!shaking_ || prev_cx_.size() != mesh_->element_count()) return 0;
  const double bx = -table_value(scene_->base_acceleration_x, s.time, 0.0);
  const double by = -table_value(scene_->base_acceleration_y, s.time, 0.0);
  std::vector<double> cx, cy;
  centroids(s, cx, cy);
  double w = 0;
  for (std::size_t e = 0; e < mesh_->element_count(); ++e) {
    if (removed(s, static_cast<std::int32_t>(e))) continue;
    w += model_->density(e) * area0_[e] * (bx * (cx[e] - prev_cx_[e]) + by * (cy[e] - prev_cy_[e]));
  }
  return w;
}

void EnergyMeter::keep_last() {
  if (started_ && last_.step != last_kept_step_) {
    rows_.push_back(last_);
    last_kept_step_ = last_.step;
  }
}

void EnergyMeter::write_csv(const std::string& dir) const {
  // The absorbed column only where absorbing boundaries take energy out.
  const bool absorbing = !scene_->absorbing.empty();
  std::string out = absorbing ? "step,time,kinetic,strain,gravity,springs,load_work,friction,absorbed,residual\n"
                              : "step,time,kinetic,strain,gravity,springs,load_work,friction,residual\n";
  char buf[32];
  const auto put = [&](double v) {
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    out += ',';
    out.append(buf, res.ptr);
  };
  for (const EnergyRow& r : rows_) {
    out += std::to_string(r.step);
    for (double v : {r.time, r.kinetic, r.strain, r.gravity, r.springs, r.load_work, r.friction}) put(v);
    if (absorbing) put(r.absorbed);
    put(r.residual);
    out += '\n';
  }
  write_file_atomically((std::filesystem::path(dir) / "energy.csv").string(), out);
}

}  // namespace nmm::solve
