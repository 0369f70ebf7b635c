// Energy terms of a run: see energy.h for the formulas, docs/energy.md for their derivation.
//
// The time scheme's damping (Q, the `damped` column of a dynamic run; damped_step). A dynamic
// step (newmark.h: γ = 1, β = solver.newmark_beta, ½ until the acceleration is known) solves for
// the covers' increment d = u1 − u0 and sets
//     a1 = (d − Δt v0 − (½ − β)Δt² a0)/(βΔt²),   v1 = v0 + Δt a1   (so a1 = Δv/Δt),
// and its solution balances the covers at its end: M a1 = g1, g the net force on them (loads,
// gravity, −F_int, springs, contacts). The step before ended so too: M a1,prev = g0, a1,prev its
// acceleration before dynamic_factor k (this step carries v0 = k v1,prev, a0 = k a1,prev).
// Where the forces are linear in u over the step (elasticity, springs) and the loads constant,
// the net force's work over the step is exactly its trapezoid ½ dᵀ(g0 + g1), which is
// W − Δ(U + S + V): ΔU = dᵀF_int,0 + ½ dᵀK d = ½ dᵀ(F_int,0 + F_int,1), and likewise for the
// springs; gravity's −ΔV and a moving support's work are exact. The kinetic energy the meter
// reports changes by ΔK = K(v0,next) − K(v0), K(v) = ½ vᵀM v. So the step's energy identity is
//     W − Δ(U + S + V + K) = ½ dᵀ(g0 + g1) − ΔK = ½ dᵀM (a1,prev + a1) − ΔK =: Q_step     (1)
// in the step's d, Δv (a1), a1,prev and M alone, for every β: what the step takes out of the
// motion. With β = ½ (Shi's scheme) d = Δt (v0 + ½Δv), so dᵀM a1 = (v0 + ½Δv)ᵀM Δv = K(v1) −
// K(v0), and with k = 1 Q_step = −½ dᵀM (a1 − a1,prev); in free vibration M (a1 − a1,prev) =
// −K d, so Q_step = ½ dᵀK d ≥ 0: each step damps the strain energy of its own increment. A mode
// of angular frequency ω (|d| ≈ |v|Δt) loses Σ ½ ω² m |v|² Δt² over the 2π/(ωΔt) steps of a
// cycle, π ωΔt·E of its energy E: a damping ratio ωΔt/4 = (γ − ½)ωΔt/2 of critical (docs/
// energy.md). β > ½ adds (β − ½)Δt² (a1 − a1,prev)ᵀM a1 to (1) (from d's a0 term), which damps
// the stiff modes (ωΔt ≫ 1). With k < 1, (1) holds the motion the step throws away,
// (1 − k²) K(v1), too: ΔK is the kinetic energy of what the next step keeps.
// Loads on a time table act in the step at its end, f1·d, as W counts them (energy.h), while
// the trapezoid of (1) takes ½ (f0 + f1)·d: Q_step adds ½ (W_f(t1) − W_f(t0)), W_f the step's
// work of the point loads, tractions, base shaking and the absorbing boundaries' input traction
// 2C·v_in(t) with their tables at t1 and t0. (The dashpots' force −C v1 at the step's end, which
// `absorbed` counts, differs from the trapezoid by ½ (v1 − v1,prev)ᵀC d, which with d ≈ Δt·v̄
// sums to −¼Δt [vᵀC v] over the run: 0 from rest to rest.)
// A run's first step from rest at step 0, free of stress (v0 = a0 = 0, β = ½): its start is out
// of balance by what its loads and gravity put on at once, g0 = f(t1) + M g (springs
// unstretched), whose work in the step the meter has, ½ dᵀg0 = ½ (W_f(t1) − ΔV). Any other
// start without a known acceleration (a restart of a static run) is taken to be in balance
// (a1,prev = 0); a start out of balance otherwise (an in-situ stress not in balance with its
// tractions, a pretensioned bolt) shows ½ of its first step's work in R. What is not linear over a step — a contact that closes or opens, slip, a
// re-cut (crack_release.h books its release in F) — and the effects' own loads (a face's water,
// the absorbing boundaries' input) stay in R.
#include "solver/output/energy.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "solver/discretisation/element_integration.h"
#include "solver/discretisation/insitu_stress.h"
#include "common/time_table.h"
#include "common/atomic_file.h"

namespace nmm::solve {

EnergyMeter::EnergyMeter(const Model& model, const CoverSpace* space)
    : model_(&model), mesh_(&model.mesh()), scene_(&model.scene()),
      space_(space && space->order() > 0 ? space : nullptr) {
  const SceneDef& scene = *scene_;
  initial_geometry();
  shaking_ = !scene.base_acceleration_x.empty() || !scene.base_acceleration_y.empty();
  for (const SupportDef& sd : scene.supports) moving_supports_ |= sd.velocity.x != 0 || sd.velocity.y != 0;
  // Where the steps throw motion away or damp it: DDA's static steps (inertia in the matrix,
  // each step from rest) and dynamic ones (Newmark γ = 1 damps; dynamic_factor < 1 throws away).
  damping_ = scene.solver.dynamic || scene.solver.static_mode == StaticMode::dda;
  joints_ = scene.joints.size();
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
                             const RunState& start, double start_work) {
  // The map leads back to the mesh of the last call (RunView::recut, composed over every re-cut
  // of the step): its indices must lie within the records of that mesh.
  const std::size_t old_vertices = prev_loop_u_.size() / 2, old_elements = prev_cx_.size();
  // The model, mesh and scene of the last call are gone with the mesh the change replaced: only
  // the meter's own records of them are read.
  model_ = &model;
  mesh_ = &model.mesh();
  scene_ = &model.scene();
  space_ = space && space->order() > 0 ? space : nullptr;
  if (map.element_parent.size() != mesh_->element_count() || map.vertex_parent.size() != mesh_->loop_vertex_count() ||
      start.loop_u.size() != 2 * mesh_->loop_vertex_count())
    throw std::logic_error("EnergyMeter::carry_over: the re-cut map or the step's start is not of the new mesh");
  initial_geometry();  // a piece starts as it was cut: its share of its parent's area and centroid
  // A vertex kept its place: its last displacement is the one it had; a vertex the change made
  // starts where the step's start put it (its parent element's field there, state_transfer.h).
  if (!prev_loop_u_.empty()) {
    std::vector<double> prev = start.loop_u;
    for (std::size_t v = 0; v < map.vertex_parent.size(); ++v) {
      const std::int32_t was = map.vertex_parent[v];
      if (was < 0) continue;
      if (static_cast<std::size_t>(was) >= old_vertices)
        throw std::logic_error("EnergyMeter::carry_over: a vertex's parent lies beyond the mesh it was cut from");
      for (int d = 0; d < 2; ++d) prev[2 * v + d] = prev_loop_u_[2 * static_cast<std::size_t>(was) + d];
    }
    prev_loop_u_ = std::move(prev);
  }
  // A piece's last centroid: where the step's start put it.
  if (!prev_cx_.empty()) {
    for (const std::int32_t p : map.element_parent)
      if (static_cast<std::size_t>(p) >= old_elements)
        throw std::logic_error("EnergyMeter::carry_over: an element's parent lies beyond the mesh it was cut from");
    centroids(start, prev_cx_, prev_cy_);
  }
  // The step's start as the step saw it (damped_step).
  if (!prev_cover_u_.empty()) {
    prev_cover_u_ = start.cover_u;
    prev_velocity_ = start.velocity;
    prev_accel_ = start.accel;
  }
  // The velocity the last step threw away and the acceleration it reached, on its pieces (a new
  // cover takes its parent's, as the step's start takes its parent's cover function:
  // state_transfer.h).
  const auto on_pieces = [&](std::vector<double>& x) {
    if (x.empty()) return;
    const std::size_t m = x.size() / std::max<std::size_t>(1, map.cover_parent.empty() ? 1 : prev_cover_count_);
    std::vector<double> v(m * map.cover_parent.size());
    for (std::size_t c = 0; c < map.cover_parent.size(); ++c)
      for (std::size_t k = 0; k < m; ++k) v[m * c + k] = x.at(m * static_cast<std::size_t>(map.cover_parent[c]) + k);
    x = std::move(v);
  };
  on_pieces(prev_v1_);
  on_pieces(prev_a1_);
  // The step's start on the new mesh, for the effects' terms of the step (EnergyStep).
  changed_start_ = start;
  changed_work_ = start_work;
  changed_ = true;
}

double EnergyMeter::damped_step(const RunState& s, double kinetic_end, double load_change) {
  // The velocity v1 = v0 + Δt·a1 the step reached (newmark.h: a1 = (d − Δt·v0 − (½ − β)Δt²·a0)
  // / (βΔt²)), before a static run's next step starts from rest (v0 = a0 = 0, β = ½: v1 = 2d/Δt)
  // or a dynamic one's from dynamic_factor·v1.
  // Static: ½ K(v1) + ¼ (Δt/Δt_prev) v1_prevᵀM v1 (energy.h); dynamic: (1) at the top of this
  // file, ½ dᵀM (a1,prev + a1) − ΔK + ½ load_change.
  const SolverDef& sv = scene_->solver;
  const double dt = s.time - prev_time_;
  if (!(dt > 0)) return 0;
  const bool from_rest = !sv.dynamic || prev_velocity_.size() != s.cover_u.size();
  const double beta = sv.dynamic && prev_accel_known_ ? sv.newmark_beta : 0.5;  // step_beta (newmark.h)
  const std::size_t n = s.cover_u.size();
  std::vector<double> v1(n), a1(n), d(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double v0 = from_rest ? 0 : prev_velocity_[i], a0 = from_rest || prev_accel_.size() != n ? 0 : prev_accel_[i];
    d[i] = s.cover_u[i] - prev_cover_u_[i];
    a1[i] = (d[i] - dt * v0 - (0.5 - beta) * dt * dt * a0) / (beta * dt * dt);
    v1[i] = v0 + dt * a1[i];
  }
  if (sv.dynamic) {
    // a1,prev: what the step's start is out of balance by, over M (0 where not known: a run's
    // first step from rest, whose load_change then carries its start's loads and gravity).
    std::vector<double> a_sum = a1;
    if (prev_a1_.size() == n)
      for (std::size_t i = 0; i < n; ++i) a_sum[i] += prev_a1_[i];
    prev_a1_ = std::move(a1);
    return 0.5 * mass_dot(s, d, a_sum) - (kinetic_end - last_.kinetic) + 0.5 * load_change;
  }
  const double k1 = kinetic(s, v1);
  double q = 0.5 * k1;
  if (prev_v1_.size() == v1.size() && prev_dt_ > 0) {
    // ¼ uᵀM w = ¼ [K(u + w) − K(u) − K(w)], K(x) = ½ xᵀM x
    std::vector<double> sum(v1.size());
    for (std::size_t i = 0; i < v1.size(); ++i) sum[i] = v1[i] + prev_v1_[i];
    q += 0.25 * (dt / prev_dt_) * (kinetic(s, sum) - k1 - kinetic(s, prev_v1_));
  }
  prev_v1_ = std::move(v1);
  prev_dt_ = dt;
  return q;
}

double EnergyMeter::mass_dot(const RunState& s, const std::vector<double>& x, const std::vector<double>& y) const {
  double k = 0;
  if (x.empty() || y.empty()) return k;
  Configuration config(*mesh_, space_);
  config.place(s.cover_xy);
  for (std::size_t e = 0; e < mesh_->element_count(); ++e) {
    if (removed(s, static_cast<std::int32_t>(e))) continue;
    const double density = model_->density(e);
    const std::int32_t* ec = &mesh_->element_covers[3 * e];
    const double ox = config.frame(e).ox, oy = config.frame(e).oy;
    const std::size_t b = mesh_->element_loop_offset[e], n = mesh_->element_loop_offset[e + 1] - b;
    const TriangleWeights& w = config.frame(e).w;
    if (space_ && w.twice_area > 0) {
      // Cover order n ≥ 1: the two fields, integrated exactly.
      const int P = space_->terms(), nf = 3 * P, order = space_->order();
      const std::size_t dpc = static_cast<std::size_t>(space_->dofs_per_cover());
      const ElementBasis& basis = config.basis(e);
      const MonomialMoments mm = monomial_moments(s.loop_xy.data() + 2 * b, n, ox, oy,
                                                  space_->scale(), 2 * order + 2);
      Poly xx, xy, yx, yy;
      xx.degree = xy.degree = yx.degree = yy.degree = order + 1;
      for (int a = 0; a < nf; ++a) {
        // the fields of term j of the element's cover k (its own copy, equal to its master's)
        const std::size_t va = dpc * static_cast<std::size_t>(ec[a / P]) + 2 * static_cast<std::size_t>(a % P);
        for (int i = 0; i < basis.phi[a].size(); ++i) {
          xx.c[i] += basis.phi[a].c[i] * x[va];
          xy.c[i] += basis.phi[a].c[i] * x[va + 1];
          yx.c[i] += basis.phi[a].c[i] * y[va];
          yy.c[i] += basis.phi[a].c[i] * y[va + 1];
        }
      }
      k += density * (integral(xx, yx, mm) + integral(xy, yy, mm));
    } else if (!space_ && w.twice_area > 0) {
      // The consistent mass, as the step assembles it.
      const PolygonMoments m = polygon_moments(s.loop_xy.data() + 2 * b, n, ox, oy);
      for (int i = 0; i < 3; ++i)
        for (int l = 0; l < 3; ++l) {
          const double xy_ = x[2 * ec[i]] * y[2 * ec[l]] + x[2 * ec[i] + 1] * y[2 * ec[l] + 1];
          k += density * integral_ww(w, m, i, l) * xy_;
        }
    }
  }
  return k;
}

EnergyRow EnergyMeter::state_terms(const RunState& s, const EnergySources& sources) const {
  return measure(s, sources, nullptr);
}

EnergyRow EnergyMeter::measure(const RunState& s, const EnergySources& sources, std::vector<EnergyTerms>* counted) const {
  EnergyRow r;
  r.step = s.step;
  r.time = s.time;
  r.kinetic = kinetic(s, s.velocity);
  const double gx = scene_->has_gravity ? scene_->gravity.x : 0.0;
  const double gy = scene_->has_gravity ? scene_->gravity.y : 0.0;
  // The state's own configuration (its cover positions, not those of the step's start).
  Configuration config(*mesh_, space_);
  config.place(s.cover_xy);
  for (std::size_t e = 0; e < mesh_->element_count(); ++e) {
    if (removed(s, static_cast<std::int32_t>(e))) continue;
    const double density = model_->density(e);
    const double ox = config.frame(e).ox, oy = config.frame(e).oy;
    const std::size_t b = mesh_->element_loop_offset[e], n = mesh_->element_loop_offset[e + 1] - b;
    const PolygonMoments m = polygon_moments(s.loop_xy.data() + 2 * b, n, ox, oy);
    const TriangleWeights& w = config.frame(e).w;
    if (space_ && w.twice_area > 0) {
      // Cover order n ≥ 1: the stress polynomial, integrated exactly.
      const int P = space_->terms(), order = space_->order();
      const MonomialMoments mm = monomial_moments(s.loop_xy.data() + 2 * b, n, ox, oy,
                                                  space_->scale(), 2 * order + 2);
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
  // What the effects hold, added on in the sources' order; and the totals they count in the state.
  if (counted) counted->assign(sources.size(), EnergyTerms{});
  const EnergyState e{*model_, s};
  for (std::size_t i = 0; i < sources.size(); ++i) {
    EnergyTerms t;
    t.stored = r.springs;
    sources[i]->energy_state(e, t);
    r.springs = t.stored;
    if (counted) (*counted)[i] = t;
  }
  return r;
}

void EnergyMeter::after_step(const RunState& s, const EnergySources& sources, bool keep) {
  std::vector<EnergyTerms> counted;
  EnergyRow r = measure(s, sources, &counted);
  for (const EffectEnergy* src : sources) columns_ |= src->energy_columns();
  if (started_) {
    // W_f: the step's work of the point loads, tractions and base shaking, with their time
    // tables at the step's end (what W counts) and at its start (damped_step's load_change).
    const bool dynamic = scene_->solver.dynamic;
    double loads_end = 0, loads_start = 0;
    for (std::size_t l = 0; l < s.loads.size() && l < scene_->loads.size(); ++l) {
      const bool table = l < scene_->load_tables.size();
      const double factor = table ? table_value(scene_->load_tables[l], s.time) : 1.0;
      const double fd = scene_->loads[l].force.x * (s.loads[l].x - load_x_[l]) +
                        scene_->loads[l].force.y * (s.loads[l].y - load_y_[l]);
      load_work_ += factor * fd;
      loads_end += factor * fd;
      loads_start += (table ? table_value(scene_->load_tables[l], prev_time_) : 1.0) * fd;
    }
    const double supports = support_work(s);
    support_work_ += supports;
    // The effects' terms of the step: the work into the step's sum (after the tractions' and
    // the shaking's, before the supports'), the dissipation into the run's totals.
    EnergyTerms step;
    const double surface_end = traction_work(s, s.time) + shaking_work(s, s.time);
    step.work = surface_end;
    double load_change = 0;  // J/m, W_f(t1) − W_f(t0); in a dynamic run's first step from rest, W_f(t1) − ΔV
    if (dynamic && damping_) {
      if (prev_a1_.empty() && unloaded_start_)
        load_change = loads_end + surface_end - (r.gravity - last_.gravity);
      else
        load_change = loads_end + surface_end - loads_start - traction_work(s, prev_time_) - shaking_work(s, prev_time_);
      load_change += absorbing_input_change(s);
    }
    step.friction = friction_;
    step.absorbed = absorbed_;
    step.fracture = released_;
    const EnergyStep e{*model_, s, prev_loop_u_, changed_ ? &changed_start_ : nullptr, joints_,
                       changed_ ? changed_work_ : 0.0};
    for (const EffectEnergy* src : sources) src->energy_step(e, step);
    load_work_ += step.work + supports;
    friction_ = step.friction;
    absorbed_ = step.absorbed;
    released_ = step.fracture;
    if (damping_ && prev_cover_u_.size() == s.cover_u.size()) damped_ += damped_step(s, r.kinetic, load_change);
    // What the step released of its start's jump in the effects' forces (the contacts': a vertex
    // that slid off its edge, contact_effect.h), which its motion took; where the steps keep no
    // motion to throw away (static_mode "equilibrium") it stays in R.
    if (damping_) damped_ += step.damped;
  }
  if (damping_) {
    // A run that starts where a dynamic step ended (a restart): that step's a1 is the state's
    // acceleration over dynamic_factor.
    const double k = scene_->solver.dynamic_factor;
    if (!started_ && scene_->solver.dynamic && s.accel_known && k > 0) {
      prev_a1_ = s.accel;
      for (double& a : prev_a1_) a /= k;
    }
    // A run's start at step 0, at rest and free of stress: out of balance by its loads and
    // gravity alone (damped_step). Any other start without a known acceleration (a restart of a
    // static run's checkpoint) is taken to be in balance.
    if (!started_) {
      unloaded_start_ = s.step == 0 && !s.accel_known;
      for (double x : s.stress) unloaded_start_ = unloaded_start_ && x == 0;
      for (double x : s.velocity) unloaded_start_ = unloaded_start_ && x == 0;
    }
    prev_cover_count_ = mesh_->cover_count();
    prev_cover_u_ = s.cover_u;
    prev_velocity_ = s.velocity;
    prev_accel_ = s.accel;
    prev_accel_known_ = s.accel_known;
  }
  if (changed_) {
    changed_ = false;
    changed_start_ = RunState{};
    changed_work_ = 0;
  }
  joints_ = scene_->joints.size();
  prev_loop_u_ = s.loop_u;  // the tractions', the moving supports' and the effects' work of the next step
  prev_time_ = s.time;
  if (shaking_) centroids(s, prev_cx_, prev_cy_);
  load_x_.resize(s.loads.size());
  load_y_.resize(s.loads.size());
  for (std::size_t l = 0; l < s.loads.size(); ++l) {
    load_x_[l] = s.loads[l].x;
    load_y_[l] = s.loads[l].y;
  }
  const double mech = r.kinetic + r.strain + r.gravity + r.springs;
  // The totals the effects count in the state (effect_energy.h energy_state), since this run's
  // first call.
  if (!started_) {
    mech0_ = mech;
    counted0_ = counted;
  }
  if (counted0_.size() != counted.size())
    throw std::logic_error("EnergyMeter::after_step: the effects are not those of the first call");
  started_ = true;
  r.load_work = load_work_;
  r.support_work = support_work_;
  r.friction = friction_;
  r.absorbed = absorbed_;
  r.fracture = released_;
  for (std::size_t i = 0; i < counted.size(); ++i) {
    r.load_work += counted[i].work - counted0_[i].work;
    r.friction += counted[i].friction - counted0_[i].friction;
    r.absorbed += counted[i].absorbed - counted0_[i].absorbed;
    r.fracture += counted[i].fracture - counted0_[i].fracture;
  }
  r.damped = damped_;
  r.residual = r.load_work - r.friction - r.absorbed - r.damped - r.fracture - (mech - mech0_);
  last_ = r;
  if (keep) {
    rows_.push_back(r);
    last_kept_step_ = r.step;
  }
}

EnergyTerms EnergyMeter::totals() const {
  EnergyTerms t;
  t.stored = last_.springs;
  t.work = last_.load_work;
  t.friction = last_.friction;
  t.absorbed = last_.absorbed;
  t.fracture = last_.fracture;
  return t;
}

void EnergyMeter::summarise(const EnergySources& sources, nlohmann::json& summary) const {
  if (!started_) return;
  const EnergyTerms t = totals();
  for (const EffectEnergy* src : sources) src->summarise_energy(t, summary);
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

template <class Traction>
double EnergyMeter::edge_work(const RunState& s, const std::vector<BoundaryEdge>& edges, const bool held[2],
                              double factor, const Traction& traction) const {
  static constexpr double kGauss[2] = {0.21132486540518711775, 0.78867513459481288225};
  double w = 0;
  for (const BoundaryEdge& be : edges) {
    if (removed(s, be.element)) continue;
    const double* a = s.loop_xy.data() + 2 * be.vertex;
    const double* b = s.loop_xy.data() + 2 * be.next;
    const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
    if (!(len > 0)) continue;
    const double nx = dy / len, ny = -dx / len;  // CCW loop: outside on the right
    for (double xi : kGauss) {
      const double uy = (1 - xi) * s.loop_u[2 * be.vertex + 1] + xi * s.loop_u[2 * be.next + 1];
      double t[2];
      traction(be, a[0] + xi * dx, a[1] + xi * dy - uy, nx, ny, t);
      for (int d = 0; d < 2; ++d) {
        if (!held[d]) continue;
        const double du_a = s.loop_u[2 * be.vertex + d] - prev_loop_u_[2 * be.vertex + d];
        const double du_b = s.loop_u[2 * be.next + d] - prev_loop_u_[2 * be.next + d];
        w += 0.5 * len * factor * t[d] * ((1 - xi) * du_a + xi * du_b);
      }
    }
  }
  return w;
}

double EnergyMeter::traction_work(const RunState& s, double t_table) const {
  // ∫ t·Δu ds on each edge, Δu linear between its ends, by the two-point Gauss rule (exact for
  // a constant t; for σ_insitu·n, linear along the edge, too).
  double w = 0;
  if (prev_loop_u_.size() != s.loop_u.size()) return 0;
  static constexpr bool kBoth[2] = {true, true};
  for (std::size_t i = 0; i < model_->traction_edges().size(); ++i) {
    const TractionDef& td = scene_->tractions[i];
    w += edge_work(s, model_->traction_edges()[i], kBoth, table_value(td.table, t_table),
                   [&](const BoundaryEdge& be, double x, double y0, double nx, double ny, double t[2]) {
                     if (td.from_insitu) {
                       const auto sg = insitu_stress_at(scene_->insitu_stress, x, y0);
                       t[0] = sg[0] * nx + sg[2] * ny;
                       t[1] = sg[2] * nx + sg[1] * ny;
                     } else {
                       t[0] = td.normal * nx + td.shear * be.sx;
                       t[1] = td.normal * ny + td.shear * be.sy;
                     }
                   });
  }
  return w;
}

double EnergyMeter::absorbing_input_change(const RunState& s) const {
  // The absorbing boundaries' input traction t_in = 2·C·v_in(t) (absorbing_boundary.h: C = ρcp
  // n nᵀ + ρcs t tᵀ, uniform along an edge) works on the edge's motion, linear between its ends:
  // (t_in(t1) − t_in(t0))·L·(Δu_a + Δu_b)/2, the edge where the step started (its end less Δu).
  if (prev_loop_u_.size() != s.loop_u.size()) return 0;
  double w = 0;
  for (std::size_t i = 0; i < model_->absorbing_edges().size() && i < scene_->absorbing.size(); ++i) {
    const AbsorbingDef& ad = scene_->absorbing[i];
    if (ad.input_x.time.empty() && ad.input_y.time.empty()) continue;
    const double dv[2] = {table_value(ad.input_x, s.time, 0.0) - table_value(ad.input_x, prev_time_, 0.0),
                          table_value(ad.input_y, s.time, 0.0) - table_value(ad.input_y, prev_time_, 0.0)};
    if (dv[0] == 0 && dv[1] == 0) continue;
    for (const BoundaryEdge& be : model_->absorbing_edges()[i]) {
      if (removed(s, be.element)) continue;
      const std::int32_t a = be.vertex, b = be.next;
      double du[2][2], xy[2][2];  // [end a, b][x, y]
      for (int k = 0; k < 2; ++k) {
        const std::int32_t v = k == 0 ? a : b;
        for (int d = 0; d < 2; ++d) {
          du[k][d] = s.loop_u[2 * v + d] - prev_loop_u_[2 * v + d];
          xy[k][d] = s.loop_xy[2 * v + d] - du[k][d];
        }
      }
      const double dx = xy[1][0] - xy[0][0], dy = xy[1][1] - xy[0][1], len = std::hypot(dx, dy);
      if (!(len > 0)) continue;
      const double n[2] = {dy / len, -dx / len}, t[2] = {dx / len, dy / len};  // CCW: outside on the right
      const std::size_t e = static_cast<std::size_t>(be.element);
      const Mat3& D = model_->elasticity(e);
      const double rho = model_->density(e), zp = std::sqrt(rho * D(0, 0)), zs = std::sqrt(rho * D(2, 2));
      for (int r = 0; r < 2; ++r) {
        const double tr = 2 * ((zp * n[r] * n[0] + zs * t[r] * t[0]) * dv[0] + (zp * n[r] * n[1] + zs * t[r] * t[1]) * dv[1]);
        w += tr * len * 0.5 * (du[0][r] + du[1][r]);
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
  if (prev_loop_u_.size() != s.loop_u.size()) return 0;
  double w = 0;
  // The in-situ stress's reaction the supports carry locked in (integrators.cpp support_terms):
  // a force σ_insitu·n on the held line in each held direction, which works on its motion,
  // ∫ (σ_insitu·n)_d Δu_d ds, as the in-situ tractions do (traction_work: two-point Gauss, the
  // field at a point's position in the mesh as cut, n at the step's end).
  if (scene_->insitu_stress.present)
    for (std::size_t i = 0; i < model_->support_edges().size(); ++i) {
      const SupportDef& sd = scene_->supports[i];
      const bool held[2] = {sd.fix_x, sd.fix_y};
      w += edge_work(s, model_->support_edges()[i], held, 1.0,
                     [&](const BoundaryEdge&, double x, double y0, double nx, double ny, double t[2]) {
                       const auto sg = insitu_stress_at(scene_->insitu_stress, x, y0);
                       t[0] = sg[0] * nx + sg[2] * ny;
                       t[1] = sg[2] * nx + sg[1] * ny;
                     });
    }
  // −k_s ∫ ē·Δh ds on each held component, ē = ½(e_prev + e_now), e = u − h linear along the
  // edge and Δh uniform: L·Δh·(ē_a + ē_b)/2.
  if (!moving_supports_) return w;
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

double EnergyMeter::shaking_work(const RunState& s, double t_table) const {
  if (!shaking_ || prev_cx_.size() != mesh_->element_count()) return 0;
  const double bx = -table_value(scene_->base_acceleration_x, t_table, 0.0);
  const double by = -table_value(scene_->base_acceleration_y, t_table, 0.0);
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
  // The absorbed and fracture columns only where an effect that owns them takes part.
  const bool absorbing = (columns_ & kAbsorbedColumn) != 0, fracturing = (columns_ & kFractureColumn) != 0;
  std::string out = "step,time,kinetic,strain,gravity,springs,load_work,friction";
  if (absorbing) out += ",absorbed";
  if (damping_) out += ",damped";
  if (fracturing) out += ",fracture";
  out += ",residual\n";
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
    if (damping_) put(r.damped);
    if (fracturing) put(r.fracture);
    put(r.residual);
    out += '\n';
  }
  write_file_atomically((std::filesystem::path(dir) / "energy.csv").string(), out);
}

}  // namespace nmm::solve
