// NMM time stepping with Shi's implicit scheme (Shi 1988, 1991; docs/physics.md §2).
//
// Unknowns: the displacement increment d = (u, v) of every physical cover during the step
// (constant cover functions); a sliver cover shares the unknowns of a neighbour
// (cover_unknowns.cpp). In an element, u(x) = Σ_k w_k(x)·d_k over its triangle's three
// covers, with w_k the linear weights of the triangle in its configuration at the start of the
// step (each element's triangle has the covers' own node positions, so a cover moves its
// elements as one piece and covers on two faces of a joint move apart).
//
// Each step solves (Newmark, γ = 1, β = solver.newmark_beta)
//     (K + M/(βΔt²)) d = F_ext − F_int + M·[v0/(βΔt) + (1/(2β) − 1)·a0]     (dynamic)
//     (K + 2M/Δt²) d = F_ext − F_int                           (static, static_mode "dda")
//     K d = F_ext − F_int                              (static, static_mode "equilibrium")
// then a1 = (d − Δt·v0 − (½ − β)Δt²·a0)/(βΔt²), v1 = v0 + Δt·a1, and the next step starts from
// v0 = k·v1, a0 = k·a1 (k = solver.dynamic_factor; static runs keep v = a = 0).
// β = ½ is Shi's DDA scheme exactly: (K + 2/Δt² M) d = F + 2/Δt M v0, v1 = 2d/Δt − v0. It is
// stable but keeps no damping at high frequency: where a stiff contact stops a cover (d ≈ 0) its
// velocity flips sign every step (v1 = −v0) for ever, and blocks resting on each other rock and
// then launch. With β > ½ (and γ = 1, still 2β ≥ γ: unconditionally stable) the stiff limit
// damps: its amplification matrix [[1 − 1/β, 1 − 1/(2β)], [−1/β, 1 − 1/(2β)]] has spectral
// radius 0.41 at β = 0.6 (the default, near the minimum), while constant acceleration is still
// integrated exactly (free fall, a sliding block) and slow vibrations barely feel it.
// K, M, F_int and the loads are integrators.h's, one integrator per term (elasticity, initial
// stress, body force, inertia, fixed points and loads, edges); in-situ stress in σ before step 1:
// insitu_stress.h; excavated bodies: excavation.h (their covers pinned, K += k_pin I).
// Everything carried from step to step is in RunState s_ (run_state.h) and the contact history:
// a checkpoint of both continues a run bitwise exactly (--restart).
// All integrals are exact simplex integrals over the element polygon (element_integration.cpp).
// After the solve: σ_e += D B d_e, and every loop vertex, cover node and tracked point moves by
// the displacement field (geometry update: large displacement over many small steps). The stress
// is not rotated with the element: rotations per step are small (Shi's DDA does the same).
//
// Penalty stiffnesses (fixed points, supports, the default interface): model.h.
//
// Static analysis is DDA's (Shi 1988): every step starts from rest (v0 = a0 = 0) but keeps the
// inertia term 2M/Δt² (β = ½) in its matrix. A block held only by contacts is then well posed
// (its rigid-body modes have mass), and an out-of-balance force F moves it by at most ½(F/m)Δt²
// per step, so a block system settles over steps onto its equilibrium instead of the step being
// singular. The pure equilibrium solve K d = F (a continuum held by fixed points, reached in
// one step) is static_mode "equilibrium"; it needs every block held by two fixed points.
//
// After each step's solve, before the state moves on, the equilibrium indicators (unbalanced
// force ratio, largest velocity: equilibrium_indicator.cpp) are taken from d, v0 and a0; they
// carry no state. history.csv rows come every history_every steps, frames every output_every.
//
// Only the effects a scene calls for are computed: no mass in an equilibrium solve, no gravity
// term without gravity, nothing for loads or fixed points that are not there.
#include "solver/time_stepper.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <sstream>

#include "solver/contact_history.h"
#include "solver/contact_solve.h"
#include "solver/contact_tolerances.h"
#include "solver/solver_threads.h"
#include "common/stopwatch.h"
#include "common/error.h"
#include "solver/excavation.h"
#include "solver/insitu_stress.h"
#include "solver/integrators.h"
#include "common/ring_geometry.h"
#include "common/time_table.h"

namespace nmm::solve {

namespace {

std::string fmt_point(double x, double y) {
  std::ostringstream os;
  os << "(" << x << ", " << y << ")";
  return os.str();
}

}  // namespace

TimeStepper::TimeStepper(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name)
    : mesh_(mesh), scene_(scene), scene_name_(scene_name), model_(mesh, scene, scene_name),
      control_(scene.solver, model_.w0(), scene.solver.time_step), contacts_(model_) {
  const std::size_t ne = mesh.element_count(), nc = mesh.cover_count();
  space_ = CoverSpace(mesh, scene.solver.cover_order, scene.solver.sliver_cover_weight);
  config_ = Configuration(mesh, &space_);
  indicator_ = EquilibriumIndicator(mesh, scene, space_);
  contacts_.use_space(space_);
  contacts_.set_elastic_predictor(!step_inertia());
  // Higher-order coefficients may be linearly dependent (cover_space.h, system_matrix.h).
  if (space_.order() > 0) {
    std::vector<int> reg;
    for (std::size_t c = 0; c < nc; ++c) {
      if (space_.basis_cover(c) != static_cast<int>(c)) continue;  // tied: its master's
      for (int l = 0; l < space_.dofs_per_cover(); ++l)
        if (space_.higher_order(l)) reg.push_back(space_.first_unknown(c) + l);
    }
    system_.set_regularised(std::move(reg), kRegularisation);
  }
  const std::size_t dpc = static_cast<std::size_t>(space_.dofs_per_cover());
  s_.cover_xy.resize(2 * nc);
  for (std::size_t c = 0; c < nc; ++c) {
    s_.cover_xy[2 * c] = mesh.node_xy[2 * mesh.cover_node[c]];
    s_.cover_xy[2 * c + 1] = mesh.node_xy[2 * mesh.cover_node[c] + 1];
  }
  s_.cover_u.assign(dpc * nc, 0.0);
  s_.velocity.assign(dpc * nc, 0.0);
  s_.accel.assign(dpc * nc, 0.0);
  s_.stress.assign(3 * stress_terms() * ne, 0.0);
  s_.loop_xy = mesh.loop_xy;
  s_.loop_u.assign(s_.loop_xy.size(), 0.0);
  s_.body_removed.assign(scene.bodies.size(), 0);
  s_.body_removed_at.assign(scene.bodies.size(), -1);
  if (scene.insitu_stress.present)
    apply_insitu_stress(scene.insitu_stress, mesh, space_.order(), space_.scale(), s_.stress);

  s_.fixed = model_.fixed_points();
  s_.loads = model_.load_points();
  s_.measure = model_.measure_points();

  // Fixed points and loads couple only the covers of their element: the element pattern holds
  // until contacts couple pairs of elements (update_pattern).
  build_pattern_with_pairs();
  rhs_.resize(unknowns());
  set_threads(0);
  excavate(scene.excavate);
}

void TimeStepper::set_threads(int threads) {
  threads_ = set_solver_threads(threads > 0 ? threads : default_solver_threads(unknowns()));
}

std::vector<std::string> TimeStepper::effects() const {
  std::vector<std::string> e;
  if (mesh_.element_count() > 0) e.push_back("elasticity");
  if (scene_.solver.dynamic) e.push_back("inertia");
  else if (step_inertia()) e.push_back("static_inertia");  // DDA static: mass term, v0 = 0
  if (scene_.has_gravity && (scene_.gravity.x != 0 || scene_.gravity.y != 0)) e.push_back("gravity");
  if (!s_.loads.empty()) e.push_back("point_loads");
  if (!s_.fixed.empty()) e.push_back("fixed_points");
  if (!scene_.supports.empty()) e.push_back("supports");
  if (!scene_.tractions.empty()) e.push_back("tractions");
  if (model_.water().active()) e.push_back("water");
  if (scene_.insitu_stress.present) e.push_back("insitu_stress");
  if (!scene_.base_acceleration_x.empty() || !scene_.base_acceleration_y.empty())
    e.push_back("base_acceleration");
  if (std::any_of(s_.body_removed.begin(), s_.body_removed.end(), [](std::uint8_t r) { return r != 0; }))
    e.push_back("excavation");
  for (const std::string& c : contacts_.effects()) e.push_back(c);
  return e;
}

void TimeStepper::check_static_support() const {
  // Without inertia, each block needs two fixed points or it is free to move as a rigid body
  // (one point still lets it turn), and the stiffness matrix is singular.
  std::vector<int> held(mesh_.block_count(), 0);
  for (const TrackedPoint& p : s_.fixed) ++held[mesh_.element_block[p.element]];
  // A support along an edge holds what two points would (the system says so if it does not).
  for (const auto& edges : model_.support_edges())
    for (const BoundaryEdge& be : edges) held[mesh_.element_block[be.element]] += 2;
  for (std::size_t b = 0; b < held.size(); ++b) {
    if (held[b] >= 2 || s_.body_removed[mesh_.block_body[b]]) continue;
    std::size_t e = 0;
    while (mesh_.element_block[e] != static_cast<std::int32_t>(b)) ++e;
    const std::int32_t c = mesh_.element_covers[3 * e];
    std::ostringstream os;
    os << "static run: block " << b << " (body " << mesh_.block_body[b] << ") is held by "
       << held[b] << " fixed point" << (held[b] == 1 ? "" : "s")
       << ", so its covers (e.g. cover " << c << " at node "
       << fmt_point(mesh_.node_xy[2 * mesh_.cover_node[c]], mesh_.node_xy[2 * mesh_.cover_node[c] + 1])
       << ") are unconstrained: give each block two fixed points, or use DDA's static analysis "
          "(solver.static_mode \"dda\", the default) or a dynamic run";
    throw RunError(os.str());
  }
}

void TimeStepper::compute_frames() {
  const std::int64_t e = config_.place(s_.cover_xy);
  if (e >= 0)
    throw RunError("element " + std::to_string(e) + ": its triangle has folded over at t = " +
                   std::to_string(s_.time) + " s (displacements too large for the time step)");
}

void TimeStepper::update_pattern() {
  // Elements, then one coupling group per pair of elements with a contact (open or closed: all
  // the step's contacts can close within it). The pattern only grows: pairs that part keep their
  // (zero) entries, so the pattern — and with it CHOLMOD's symbolic analysis — changes only when
  // a pair of elements first has a contact. (Pairs merely within the search distance are not
  // added in advance: that margin doubled to tripled the factorisation's flops on brick walls,
  // docs/contact.md "Sparse pattern".)
  const int first = static_cast<int>(mesh_.element_count());
  const auto now = contacts_.contact_pairs();
  if (std::includes(s_.pattern_pairs.begin(), s_.pattern_pairs.end(), now.begin(), now.end())) {
    contacts_.assign_groups(s_.pattern_pairs, first);
    return;
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  std::set_union(s_.pattern_pairs.begin(), s_.pattern_pairs.end(), now.begin(), now.end(),
                 std::back_inserter(pairs));
  s_.pattern_pairs = std::move(pairs);
  build_pattern_with_pairs();
  contacts_.assign_groups(s_.pattern_pairs, first);
}

void TimeStepper::build_pattern_with_pairs() {
  const auto& pairs = s_.pattern_pairs;
  std::vector<int> offsets{0}, dofs;
  const int m = space_.element_dofs();
  for (std::size_t e = 0; e < mesh_.element_count(); ++e) {
    dofs.insert(dofs.end(), space_.element_unknowns(e), space_.element_unknowns(e) + m);
    offsets.push_back(static_cast<int>(dofs.size()));
  }
  for (const auto& [a, b] : pairs) {
    dofs.insert(dofs.end(), space_.element_unknowns(a), space_.element_unknowns(a) + m);
    dofs.insert(dofs.end(), space_.element_unknowns(b), space_.element_unknowns(b) + m);
    offsets.push_back(static_cast<int>(dofs.size()));
  }
  system_.build_pattern(unknowns(), offsets, dofs);
}

void TimeStepper::assemble(double dt) {
  // The terms are integrators.h's; only the effects the scene calls for are assembled.
  const bool dynamic = step_inertia();  // the matrix has the inertia term
  const double t_end = s_.time + dt;
  const auto [bx, by] = body_force_per_mass(scene_, t_end);
  const bool gravity = bx != 0 || by != 0;
  // Until one step has given the acceleration, a0 is unknown: that step takes β = ½, for which
  // a0 drops out, so constant acceleration is exact from the first step on.
  // A static step starts from rest: β = ½ (Shi's 2M/Δt²), a0 and v0 drop out.
  const double beta = s_.accel_known && scene_.solver.dynamic ? scene_.solver.newmark_beta : 0.5;
  InertiaCoefficients inertia;
  if (dynamic) inertia = {1.0 / (beta * dt * dt), 1.0 / (beta * dt), 1.0 / (2 * beta) - 1.0};
  system_.set_zero();
  rhs_.setZero();
  const int nd = space_.element_dofs();
  const std::size_t T = stress_terms();
  Eigen::MatrixXd k(nd, nd);
  Eigen::VectorXd fe(nd);
  Mat6 k6;
  Vec6 f6;
  for (std::size_t e = 0; e < mesh_.element_count(); ++e) {
    const int* g = space_.element_unknowns(e);
    if (removed_elem_[e]) {  // excavated: its covers' unknowns are held at zero
      k = model_.pin_stiffness() * Eigen::MatrixXd::Identity(nd, nd);
      system_.add_group(e, k.data());
      continue;
    }
    const std::int32_t* ec = &mesh_.element_covers[3 * e];
    const ElementGeometry geo = element_geometry(config_, mesh_, s_.loop_xy, e);
    const double rho = model_.density(e);
    const double* sigma = s_.stress.data() + 3 * T * e;
    if (space_.order() == 0) {  // constant strain: the 6×6 fast paths
      integrators::elasticity(geo, model_.elasticity(e), k6);
      integrators::initial_stress(geo, sigma, f6);
      if (gravity) integrators::body_force(geo, rho, bx, by, f6);
      if (dynamic) integrators::inertia(geo, rho, inertia, ec, s_, k6, f6);
      system_.add_group(e, k6.data());
      for (int i = 0; i < 6; ++i) rhs_[g[i]] += f6[i];
      continue;
    }
    k.setZero();
    integrators::elasticity(geo, model_.elasticity(e), k);
    integrators::initial_stress(geo, sigma, fe);
    if (gravity) integrators::body_force(geo, rho, bx, by, fe);
    if (dynamic) integrators::inertia(geo, rho, inertia, ec, s_, space_.terms(), k, fe);
    system_.add_group(e, k.data());
    for (int i = 0; i < nd; ++i) rhs_[g[i]] += fe[i];
  }
  point_terms(model_, config_, s_, t_end, system_, rhs_);
  edge_terms(model_, config_, s_, removed_elem_, t_end, system_, rhs_);
}

void TimeStepper::update(const Eigen::VectorXd& d, double dt) {
  const std::size_t ne = mesh_.element_count();
  const int nd = space_.element_dofs(), nf = nd / 2;
  const std::size_t T = stress_terms();
  double max_d = 0;
  std::vector<double> de(static_cast<std::size_t>(nd)), phi(static_cast<std::size_t>(nf));
  for (std::size_t e = 0; e < ne; ++e) {
    const int* g = space_.element_unknowns(e);
    for (int i = 0; i < nd; ++i) de[i] = d[g[i]];
    if (space_.order() == 0) {
      // n = 0 specialised (constant strain; the first-order code path, see assemble()).
      const ElementFrame& f = config_.frame(e);
      const Vec6 de6 = Eigen::Map<const Vec6>(de.data());
      const Vec3 ds = model_.elasticity(e) * (strain_matrix(f.w) * de6);
      for (int i = 0; i < 3; ++i) s_.stress[3 * e + i] += ds[i];
      for (std::int32_t v = mesh_.element_loop_offset[e]; v < mesh_.element_loop_offset[e + 1]; ++v) {
        const double x = s_.loop_xy[2 * v] - f.ox, y = s_.loop_xy[2 * v + 1] - f.oy;
        double ux = 0, uy = 0;
        for (int k = 0; k < 3; ++k) {
          const double w = f.w.at(k, x, y);
          ux += w * de6[2 * k];
          uy += w * de6[2 * k + 1];
        }
        s_.loop_xy[2 * v] += ux;
        s_.loop_xy[2 * v + 1] += uy;
        s_.loop_u[2 * v] += ux;
        s_.loop_u[2 * v + 1] += uy;
      }
      continue;
    }
    const ElementBasis& eb = config_.basis(e);
    // Δσ = D·B·d: strain polynomials of degree n, then D per coefficient.
    Poly eps[3];
    for (int r = 0; r < 3; ++r) eps[r].degree = space_.order();
    for (int a = 0; a < nf; ++a)
      for (std::size_t t = 0; t < T; ++t) {
        eps[0].c[t] += eb.dx[a].c[t] * de[2 * a];
        eps[1].c[t] += eb.dy[a].c[t] * de[2 * a + 1];
        eps[2].c[t] += eb.dy[a].c[t] * de[2 * a] + eb.dx[a].c[t] * de[2 * a + 1];
      }
    const Mat3& D = model_.elasticity(e);
    for (std::size_t t = 0; t < T; ++t) {
      const Vec3 ds = D * Vec3(eps[0].c[t], eps[1].c[t], eps[2].c[t]);
      for (int r = 0; r < 3; ++r) s_.stress[3 * (T * e + t) + r] += ds[r];
    }
    for (std::int32_t v = mesh_.element_loop_offset[e]; v < mesh_.element_loop_offset[e + 1]; ++v) {
      eb.values(s_.loop_xy[2 * v], s_.loop_xy[2 * v + 1], phi.data());
      double ux = 0, uy = 0;
      for (int a = 0; a < nf; ++a) {
        ux += phi[a] * de[2 * a];
        uy += phi[a] * de[2 * a + 1];
      }
      s_.loop_xy[2 * v] += ux;
      s_.loop_xy[2 * v + 1] += uy;
      s_.loop_u[2 * v] += ux;
      s_.loop_u[2 * v + 1] += uy;
    }
  }
  for (std::vector<TrackedPoint>* points : {&s_.fixed, &s_.loads, &s_.measure})
    config_.move_points(d, *points);
  config_.move_cover_nodes(d, s_.cover_xy);
  const bool dynamic = scene_.solver.dynamic;
  const double beta = s_.accel_known ? scene_.solver.newmark_beta : 0.5;
  const double k = scene_.solver.dynamic_factor;
  for (Eigen::Index i = 0; i < d.size(); ++i) max_d = std::max(max_d, std::abs(d[i]));
  // Per cover; a tied cover takes its master's increment (and so keeps its master's velocity).
  const std::size_t dpc = static_cast<std::size_t>(space_.dofs_per_cover());
  for (std::size_t i = 0; i < s_.cover_u.size(); ++i) {
    const double di = d[space_.first_unknown(i / dpc) + static_cast<int>(i % dpc)];
    s_.cover_u[i] += di;
    if (dynamic) {
      const double a1 = (di - dt * s_.velocity[i] - (0.5 - beta) * dt * dt * s_.accel[i]) / (beta * dt * dt);
      s_.velocity[i] = k * (s_.velocity[i] + dt * a1);
      s_.accel[i] = k * a1;
    }
  }
  s_.max_step_displacement = std::max(s_.max_step_displacement, max_d);
  s_.accel_known = dynamic;
}

std::string TimeStepper::attempt(double dt) {
  // Where no two faces can touch (an opening excavated from one unjointed block), the plain
  // solve: no contact detection, no contact problem.
  const bool contact = contacts_.active() && model_.contacts_can_arise();
  if (!step_inertia() && !contact) check_static_support();
  Stopwatch watch;
  compute_frames();
  timings_.assembly += watch.seconds();
  if (contact) {
    contacts_.begin_step(
        s_.loop_xy, config_,
        control_.search_distance() + contacts_.max_dilation(),
        kContactTolerances.new_depth * mesh_.mesh_size, model_.w0());
    update_pattern();
  }
  timings_.contact_detection = contacts_.detection_seconds();
  watch.restart();
  assemble(dt);
  if (contact) {
    system_.save();
    rhs_base_ = rhs_;
  }
  timings_.assembly += watch.seconds();

  // Without contact: one factorisation and solve. With contact: the step's convex contact
  // problem (contact_solve.cpp), Newton iterations on a reused factorisation.
  Eigen::VectorXd d;
  auto not_positive_definite = [&]() {
    const int u = system_.failed_unknown();
    std::ostringstream os;
    os << "the system matrix is not positive definite";
    if (u >= 0) {
      const int c = space_.cover_of_unknown(u);
      os << " at cover " << c << " (node "
         << fmt_point(mesh_.node_xy[2 * mesh_.cover_node[c]], mesh_.node_xy[2 * mesh_.cover_node[c] + 1])
         << "): it is unconstrained (held by no fixed point or closed contact); add fixed "
            "points or run dynamic";
    }
    return os.str();
  };
  if (!contact) {
    watch.restart();
    const bool ok = system_.factorize();
    ++timings_.factorisations;
    timings_.factorisation += watch.seconds();
    if (!ok) throw RunError(not_positive_definite());
    watch.restart();
    d = system_.solve(rhs_);
    ++timings_.solves_count;
    timings_.solves += watch.seconds();
  } else {
    const ContactSolveStats before = solve_stats_;
    const double tau = scene_.solver.contact_tolerance;
    const ContactSolveOutcome outcome =
        solve_contact_step(system_, contacts_, rhs_base_, tau,
                           contacts_.softening() ? displacement_tolerance(tau, model_.w0()) : 0.0, d,
                           solve_stats_);
    timings_.factorisations += solve_stats_.factorisations - before.factorisations;
    timings_.factorisation += solve_stats_.factorisation_seconds - before.factorisation_seconds;
    timings_.solves_count += solve_stats_.cg_iterations - before.cg_iterations +
                             (solve_stats_.factorisations - before.factorisations);
    timings_.solves += solve_stats_.cg_seconds - before.cg_seconds +
                       solve_stats_.line_search_seconds - before.line_search_seconds;
    s_.iterations += static_cast<std::uint64_t>(solve_stats_.newton - before.newton);
    s_.friction_unsettled += static_cast<std::uint64_t>(solve_stats_.unsettled - before.unsettled);
    if (outcome.status == ContactSolveOutcome::Status::not_positive_definite)
      throw RunError(not_positive_definite());
    if (!outcome.ok()) return outcome.reason;
  }
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (!std::isfinite(d[i]))
      throw RunError("the displacement of cover " + std::to_string(space_.cover_of_unknown(static_cast<int>(i))) +
                     " is not a finite number at t = " + std::to_string(s_.time) + " s");
  if (contact) {
    const std::string why =
        control_.rejection(d.cwiseAbs().maxCoeff(), contacts_.max_penetration(), step_inertia());
    if (!why.empty()) return why;
    contacts_.end_step();
    s_.max_penetration = std::max(s_.max_penetration, contacts_.max_penetration());
    s_.max_capped = std::max(s_.max_capped, contacts_.capped_count());
  }
  watch.restart();
  measure_balance(d, dt, contact);
  update(d, dt);
  timings_.geometry_update += watch.seconds();
  s_.time += dt;
  ++s_.step;
  return "";
}

void TimeStepper::measure_balance(const Eigen::VectorXd& d, double dt, bool contact) {
  // The same body force, β and loads as the step's assembly (assemble()), at the step's end.
  const double t_end = s_.time + dt;
  const auto [bx, by] = body_force_per_mass(scene_, t_end);
  StepBalance b;
  b.d = &d;
  b.v0 = &s_.velocity;
  b.a0 = &s_.accel;
  b.dt = dt;
  b.beta = s_.accel_known && scene_.solver.dynamic ? scene_.solver.newmark_beta : 0.5;
  Eigen::VectorXd kd;
  if (!step_inertia()) {
    // No mass: the force the solve balanced, K·d (with contacts: the saved matrix, K without
    // the contact springs; without: K·d = the right-hand side itself).
    if (contact) system_.saved_times(d, kd);
    b.balance = contact ? &kd : &rhs_;
  }
  b.applied_sum = applied_force_sum(scene_, s_, t_end, std::hypot(bx, by),
                                    indicator_.active_mass(s_.body_removed), model_.traction_edges(),
                                    model_.interface_edges(), removed_elem_);
  b.stress = &s_.stress;
  b.stress_terms = stress_terms();
  balance_ = indicator_.measure(b, s_.body_removed);
}

void TimeStepper::step(double dt) {
  const std::string why = attempt(dt);
  if (!why.empty()) throw RunError(why);
}

void TimeStepper::impose_displacement(const Eigen::VectorXd& d) {
  compute_frames();  // the element frames of the current configuration
  update(d, 1.0);
}

const Eigen::VectorXd& TimeStepper::assemble_rhs(double dt) {
  compute_frames();
  assemble(dt);
  return rhs_;
}

std::array<double, 2> TimeStepper::displacement_at(const TrackedPoint& p) const {
  return {p.x - p.x0, p.y - p.y0};
}

std::string TimeStepper::run_until(double t_end, const std::function<void(std::int64_t)>& on_step) {
  // Attempts under Shi's step control (step_control.h): without contact nothing is rejected and
  // every step has the full length time_step.
  const SolverDef& sv = scene_.solver;
  control_ = StepControl(sv, model_.w0(), s_.dt);
  std::int64_t done = 0;
  stopped_at_ratio_ = false;
  while (!control_.done(s_.time, t_end)) {
    // Between steps only, so an interrupted run stops in a consistent state.
    if (stop_check_ && stop_check_()) return "interrupted";
    const double h = control_.next(s_.time, t_end);
    std::string why;
    try {
      why = attempt(h);
    } catch (const RunError& e) {
      return e.what();
    }
    if (!why.empty()) {
      static const bool trace = std::getenv("NMM_TRACE_CUTS") != nullptr;
      if (trace) std::fprintf(stderr, "cut at t = %.9g: %s\n", s_.time, why.c_str());
      ++s_.cuts;
      if (!control_.cut(h)) {
        std::ostringstream os;
        os << "time step cut below its floor (" << control_.floor() << " s) at t = " << s_.time
           << " s because " << why;
        return os.str();
      }
      continue;
    }
    control_.accept();
    s_.dt = control_.dt();
    // UDEC's `solve ratio`: the run has reached equilibrium (equilibrium_indicator.cpp).
    stopped_at_ratio_ = sv.stop_at_ratio > 0 && balance_.max_ratio < sv.stop_at_ratio &&
                        (!sv.dynamic || balance_.max_velocity < RestCriterion::kVelocity);
    on_step(++done);
    if (stopped_at_ratio_) return "ok";
  }
  return "ok";
}

}  // namespace nmm::solve

namespace nmm::solve {

std::string TimeStepper::contact_history() const { return save_contact_history(contacts_); }

std::string TimeStepper::state_hash() const {
  return nmm::solve::state_hash(s_, contact_history(), mesh_);
}

void TimeStepper::write_checkpoint(const std::string& path) const {
  // With contact the factorisation lives on from step to step (a preconditioner): the checkpoint
  // keeps its matrix so that a restart continues bitwise as the straight run.
  write_state_file(path, s_, contact_history(), mesh_,
                   contacts_.active() && model_.contacts_can_arise() ? system_.factor_source()
                                                                           : std::string());
}

void TimeStepper::restart_from(const std::string& path) {
  std::string history, factor;
  const RunState st = state_from_sections(read_checkpoint_file(path), mesh_, path, history,
                                          space_.dofs_per_cover(), space_.terms(), &factor);
  restore(st, history, path);
  if (!factor.empty() && contacts_.active() && !system_.factor_from_source(factor))
    throw InputError(path, "section FACTOR", "not the matrix of a factorisation of this run's size");
}

void TimeStepper::restore(const RunState& st, const std::string& history, const std::string& name) {
  if (st.body_removed.size() != scene_.bodies.size())
    throw InputError(name, "section BODIES", "the checkpoint has " +
                                                 std::to_string(st.body_removed.size()) +
                                                 " bodies, the scene " +
                                                 std::to_string(scene_.bodies.size()));
  // Tracked points: the checkpoint's where the scene still names the same points; points the
  // run's scene adds or changes start where the scene puts them, in the current configuration.
  auto same = [](const std::vector<TrackedPoint>& a, const std::vector<TrackedPoint>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (a[i].x0 != b[i].x0 || a[i].y0 != b[i].y0) return false;
    return true;
  };
  RunState next = st;
  if (!same(next.fixed, s_.fixed)) next.fixed = s_.fixed;
  if (!same(next.loads, s_.loads)) next.loads = s_.loads;
  if (!same(next.measure, s_.measure)) next.measure = s_.measure;
  s_ = std::move(next);
  load_contact_history(contacts_, history, mesh_, name);
  // The same pattern as the run that wrote the checkpoint: the same symbolic analysis, the same
  // round-off.
  if (!s_.pattern_pairs.empty()) {
    build_pattern_with_pairs();
    contacts_.assign_groups(s_.pattern_pairs, static_cast<int>(mesh_.element_count()));
  }
  apply_removed();
  excavate(scene_.excavate);
}

void TimeStepper::excavate(const std::vector<int>& bodies) {
  excavate_bodies(bodies, mesh_, stress_terms(), s_);
  apply_removed();
}

void TimeStepper::apply_removed() {
  removed_elem_ = removed_elements(mesh_, s_);
  const bool any = std::any_of(removed_elem_.begin(), removed_elem_.end(),
                               [](std::uint8_t r) { return r != 0; });
  contacts_.set_removed_elements(any ? removed_elem_ : std::vector<std::uint8_t>{});
  if (!any) return;
  // Removed covers keep no velocity: they stand still, held at zero.
  for (std::size_t c = 0; c < mesh_.cover_count(); ++c)
    if (s_.body_removed[mesh_.cover_body[c]])
      for (int i = 0; i < space_.dofs_per_cover(); ++i) {
        const std::size_t j = c * static_cast<std::size_t>(space_.dofs_per_cover()) + i;
        s_.velocity[j] = s_.accel[j] = 0;
      }
}

}  // namespace nmm::solve
