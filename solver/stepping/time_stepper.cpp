// NMM time stepping with Shi's implicit scheme (Shi 1988, 1991; docs/physics.md §2): the
// stepping core. A step of length Δt is one attempt:
//
//   frames      the configuration placed on the covers' positions (configuration.h)
//   contacts    detection within the search distance, the pattern grown by new element pairs
//   assembly    K and F by the scene's form (form.h): the integrators it calls for, one per
//               term (integrators.h: elasticity, initial stress, body force, inertia with
//               newmark.h's coefficients, fixed points, loads, supports, tractions, water,
//               in-situ traction); excavated covers pinned (excavation.h, K += k_pin I)
//   solve       one factorisation, or the step's contact problem (contact_solve.h)
//   acceptance  Shi's step control (step_control.h): a rejected attempt leaves the state as it
//               was and the caller cuts Δt
//   update      the state moved on by d (state_update.h), after the equilibrium indicators
//               (equilibrium_indicator.h) are taken from d, v0 and a0
//
// Unknowns: the cover functions' coefficients during the step (cover_space.h; a sliver cover
// shares a neighbour's, cover_unknowns.cpp). All integrals are exact simplex integrals over the
// element polygon (element_integration.cpp). Everything carried from step to step is in RunState
// s_ (run_state.h) and the contact history: a checkpoint of both continues a run bitwise exactly
// (restart.h). Only the effects a scene calls for are computed (run_effects.h).
#include "solver/stepping/time_stepper.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <sstream>

#include "solver/contact/contact_history.h"
#include "solver/contact/contact_solve.h"
#include "solver/contact/contact_tolerances.h"
#include "solver/discretisation/solver_threads.h"
#include "common/stopwatch.h"
#include "common/error.h"
#include "solver/discretisation/excavation.h"
#include "solver/stepping/initial_state.h"
#include "solver/discretisation/form.h"
#include "solver/discretisation/integrators.h"
#include "solver/discretisation/newmark.h"
#include "solver/stepping/restart.h"
#include "solver/stepping/state_update.h"
#include "solver/stepping/static_support.h"
#include "solver/fracture/recut_check.h"
#include "solver/fracture/state_transfer.h"
#include "solver/discretisation/absorbing_boundary.h"
#include "solver/reinforcement/bolt_layout.h"
#include "common/checkpoint_file.h"
#include "common/mesh_file.h"

namespace nmm::solve {

namespace {
// How many times the pairs the contacts use (this step's and the last accepted step's) the
// sparse pattern may hold before a growth rebuilds it from those alone (update_pattern).
// Measured on the DDA code's walls (contact_bench --peer, 100 steps, one thread): at 1.1 the
// 30 × 30 wall took 117 ms per static step and 332 dynamic against 132 and 423 with a pattern
// that only grew. 1.0 (rebuilt from the used pairs at every growth) and 1.05 were within a few
// per cent of it either way (1.0: 122 / 336 ms at 30 × 30, 116 dynamic at 20 × 20 against 122,
// with 80–92 analyses per 100 static steps against 54–56), and 1.3 kept most of the growth
// (dynamic 20 × 20: 148 ms against 152 and 122 at 1.1).
constexpr double kPatternSlack = 1.1;

// How many of a step's touching contacts (closed at its start, or within the gap tolerance of
// touching) may lie outside the sparse pattern before it grows, in a run with inertia: at most
// kDeferredTouching, and at most kDeferredShare of the touching contacts (update_pattern). Each
// costs the CG runs on the kept factorisation up to two iterations (its two springs: H − P of
// rank 2); a growth that adds entries costs a symbolic analysis, 0.3–0.5 of a factorisation, at
// the next factorisation. Open contacts outside the pattern cost nothing unless they close.
// Measured on the DDA code's walls (contact_bench --peer, h = 2 m, 100 steps, one thread,
// 2026-11-28, paired runs), ms per step at 10 / 20 / 30, symbolic analyses in brackets:
//   static, growth at every new pair   4.13 (30)  20.8 (33)  50.8 (27)
//   static, this rule                  3.67 (14)  17.9 (20)  47.2 (20)
//   dynamic, growth at every new pair  8.45 (88)  49.9 (99)  148 (98)
//   dynamic, this rule                 8.05 (44)  50.5 (94)  147 (95)
// ("this rule" also with detection's lengths by sqrt, not std::hypot: 0.1 / 0.4 / 1.0 ms of
// each static step's difference). Counting every contact outside, open or closed, against 20
// or 40 gave fewer analyses (static 5–9, 2–6) and more CG iterations: summed over the three
// walls, static steps 5–7 % slower than with 5 contacts closed at the start (this rule's first
// form), dynamic ones 2 % faster and 3 % slower. The share keeps a scene of a few contacts (a
// block on an incline) growing its pattern at once; without inertia it always grows (the
// contacts' springs are what makes the matrix positive definite there).
constexpr int kDeferredTouching = 5;
constexpr double kDeferredShare = 0.01;
}  // namespace

TimeStepper::MeshBound::MeshBound(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name,
                                  std::size_t cracks)
    : model(mesh, scene, scene_name), form(model),
      // A run that can crack also ties covers of next to no support that its cracks cut
      // (cover_unknowns.cpp): corners cut off at nodes, clamped between stiff crack faces.
      space(mesh, scene.solver.cover_order, scene.solver.sliver_cover_weight, Fracture::kLeastCoverSupport,
            static_cast<std::int32_t>(scene.joints.size() - cracks)),
      config(mesh, &space),
      indicator(mesh, scene, space), momentum(mesh, space, indicator.group_mass()), contacts(model),
      problem(contacts, space), bolts(model, space) {
  problem.set_elastic_predictor(!model.step_inertia());
}

TimeStepper::TimeStepper(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name)
    : mesh_(&mesh), scene_(&scene), scene_name_(scene_name),
      b_(std::make_unique<MeshBound>(mesh, scene, scene_name)), fracture_(scene),
      control_(scene.solver, b_->model.w0(), scene.solver.time_step) {
  // Higher-order coefficients may be linearly dependent (cover_space.h, system_matrix.h).
  if (b_->space.order() > 0) system_.set_regularised(b_->space.higher_order_unknowns(), kRegularisation);
  // Contacts change the pattern every few steps: each analysis orders by AMD alone.
  system_.set_amd_only(b_->contacts.active());
  s_ = initial_state(b_->model, b_->space);
  excavate(scene.excavate);
  // Fixed points and loads couple only the covers of their element: the element pattern holds
  // until contacts couple pairs of elements (update_pattern); bolts couple theirs from the start.
  place_bolts({});
  set_threads(0);
}

void TimeStepper::place_bolts(const std::vector<BoltState>& previous) {
  s_.bolts = bolts_for_run(scene(), mesh(), s_, previous, scene_name_);
  b_->bolts.number(s_.bolts, b_->space.unknowns());
  build_pattern_with_pairs();
  rhs_.resize(system_unknowns());
}

void TimeStepper::set_threads(int threads) {
  threads_ = set_solver_threads(threads > 0 ? threads : default_solver_threads(b_->space.unknowns()));
}



Outcome TimeStepper::compute_frames() {
  const std::int64_t e = b_->config.place(s_.cover_xy);
  if (e >= 0)
    return stop(StopCode::element_folded, "element " + std::to_string(e) + ": its triangle has folded over at t = " +
                                              std::to_string(s_.time) +
                                              " s (displacements too large for the time step)");
  return {};
}

Outcome TimeStepper::stop(StopCode code, std::string reason) const {
  return Outcome::stop(code, std::move(reason), s_.time);
}

void TimeStepper::update_pattern() {
  // Elements, then one coupling group per pair of elements with a contact (open or closed: all
  // the step's contacts can close within it). Pairs that part keep their (zero) entries, so the
  // pattern — and with it CHOLMOD's symbolic analysis — changes only when a contact reaches a
  // pair the pattern lacks, and, in a run with inertia, not even then while only a few touching
  // contacts lie outside it (kDeferredTouching): their springs are left to CG (H − P of small
  // rank) instead of a symbolic analysis at the next factorisation. Then it grows by the new
  // pairs, unless it already holds more than kPatternSlack times the pairs this step's and the
  // last accepted step's contacts use: then it is built from those alone. A pattern that only
  // grew kept every pair a contact had ever touched, and its factor's fill grew faster than its
  // entries (a dynamic 20 × 20 wall: +5 % entries, +24 % factor nonzeros, +46 % flops over 100
  // steps). (Pairs merely within the search distance are not added in advance: that margin
  // doubled to tripled the factorisation's flops on brick walls, docs/contact.md "Sparse
  // pattern".) The rule reads only what a checkpoint restores (the pattern's pairs, the accepted
  // contacts and the step's own contacts detected from them), so a restarted run rebuilds the
  // same patterns.
  const int first = first_pair_group();
  const auto now = b_->contacts.element_pairs();
  const auto& had = s_.pattern_pairs;
  const bool holds = std::includes(had.begin(), had.end(), now.begin(), now.end());
  // The groups in the present pattern: final if it holds every pair, else what the deferral counts.
  if (holds || step_inertia()) b_->problem.assign_groups(had, first);
  if (holds) return;
  if (step_inertia()) {
    const double outside = static_cast<double>(b_->problem.outside_pattern().touching);
    const double touching = static_cast<double>(b_->contacts.touching_at_start());
    if (outside <= std::min(static_cast<double>(kDeferredTouching), kDeferredShare * touching)) return;
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  std::set_union(had.begin(), had.end(), now.begin(), now.end(), std::back_inserter(pairs));
  const auto last = b_->contacts.element_pairs(true);
  std::vector<std::pair<std::int32_t, std::int32_t>> used;
  std::set_union(now.begin(), now.end(), last.begin(), last.end(), std::back_inserter(used));
  if (static_cast<double>(pairs.size()) > kPatternSlack * static_cast<double>(used.size())) pairs = std::move(used);
  s_.pattern_pairs = std::move(pairs);
  build_pattern_with_pairs();
  b_->problem.assign_groups(s_.pattern_pairs, first);
}

void TimeStepper::build_pattern_with_pairs() {
  const auto& pairs = s_.pattern_pairs;
  std::vector<int> offsets{0}, dofs;
  const int m = b_->space.element_dofs();
  for (std::size_t e = 0; e < mesh().element_count(); ++e) {
    dofs.insert(dofs.end(), b_->space.element_unknowns(e), b_->space.element_unknowns(e) + m);
    offsets.push_back(static_cast<int>(dofs.size()));
  }
  b_->bolts.add_groups(offsets, dofs);
  for (const auto& [a, b] : pairs) {
    dofs.insert(dofs.end(), b_->space.element_unknowns(a), b_->space.element_unknowns(a) + m);
    dofs.insert(dofs.end(), b_->space.element_unknowns(b), b_->space.element_unknowns(b) + m);
    offsets.push_back(static_cast<int>(dofs.size()));
  }
  system_.build_pattern(system_unknowns(), offsets, dofs);
}

StepContext TimeStepper::step_context(double dt) const {
  return make_step_context(b_->model, b_->config, s_, removed_elem_, dt);
}

Outcome TimeStepper::attempt_once(double dt) {
  // Where no two faces can touch (an opening excavated from one unjointed block), the plain
  // solve: no contact detection, no contact problem.
  const bool contact = b_->contacts.active() && b_->model.contacts_can_arise();
  if (!step_inertia() && !contact)
    if (std::string why = unheld_block(b_->model, s_); !why.empty()) return stop(StopCode::unconstrained, std::move(why));
  Stopwatch watch;
  if (Outcome folded = compute_frames(); !folded.ok()) return folded;
  timings_.assembly += watch.seconds();
  if (contact) {
    b_->contacts.begin_step(s_.loop_xy, control_.search_distance() + b_->contacts.max_dilation(),
                         kContactTolerances.new_depth * mesh().mesh_size, b_->model.w0());
    b_->problem.build(s_.loop_xy, b_->config, b_->model.w0());
    update_pattern();
  }
  timings_.contact_detection = b_->contacts.detection_stats().seconds;
  const StepContext context = step_context(dt);  // the attempt's one context (step_context.h)
  if (absorbing_reaction_due(scene(), s_)) take_absorbing_reaction(contact);
  b_->bolts.begin_step(b_->config, s_, removed_elem_);

  // Without contact: one factorisation and solve. With contact: the step's convex contact
  // problem (contact_solve.cpp), Newton iterations on a reused factorisation. Bolts whose springs
  // yield, slip or break at the solution solve the step again from there (bolt_system.h).
  Eigen::VectorXd d, residual;
  bool iterated = false;  // the contact solve took a Newton direction
  for (int round = 0;; ++round) {
    watch.restart();
    b_->form.assemble(context, system_, rhs_);
    b_->bolts.assemble(system_, rhs_, mesh().element_count());
    // The blocks' share of the last step's out-of-balance force (block_momentum.h); not in a
    // static step (a restart may switch a dynamic run to static), whose balance starts afresh.
    if (!s_.block_force.empty() && handed_on_share() > 0) b_->momentum.add_forces(s_.block_force, s_.cover_xy, rhs_);
    if (contact) {
      system_.save();
      rhs_base_ = rhs_;
    }
    timings_.assembly += watch.seconds();
    if (Outcome solved = solve_step(contact, round > 0, d, residual, iterated); !solved.ok()) return solved;
    if (!b_->bolts.judge(d)) break;
    if (round + 1 >= BoltSystem::kMaxRounds)
      return stop(StopCode::bolts_not_settled, "the bolts' springs were still switching between elastic and "
                                               "yielding or slipping after " +
                                                   std::to_string(BoltSystem::kMaxRounds) + " solves of the step");
  }
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (!std::isfinite(d[i]))
      return stop(StopCode::displacement_not_finite,
                  (i < b_->space.unknowns() ? "the displacement of cover " +
                                                  std::to_string(b_->space.cover_of_unknown(static_cast<int>(i)))
                                            : b_->bolts.describe_unknown(static_cast<int>(i))) +
                      " is not a finite number at t = " + std::to_string(s_.time) + " s");
  // The covers' motion: a cable's slip (its own unknowns, after them) is no block moving.
  const Eigen::VectorXd covers_d = d.head(b_->space.unknowns());
  if (contact) {
    const ContactSet::Totals totals = b_->contacts.totals();
    Outcome rejected = control_.rejection(covers_d.cwiseAbs().maxCoeff(),
                                          b_->contacts.judged_penetration(control_.penetration_limit()), step_inertia());
    if (!rejected.ok()) trace_rejected_step(covers_d, totals.max_penetration);
    if (!rejected.ok()) return stop(rejected.code, std::move(rejected.reason));
    b_->contacts.end_step(b_->problem);
    // Handed on with the velocity the step carries over (block_momentum.h); a step in balance at
    // its start hands nothing on, and a direct solve leaves nothing to hand on.
    if (handed_on_share() > 0 && iterated)
      b_->momentum.net_forces(residual, handed_on_share(), s_.cover_xy, s_.block_force);
    else
      s_.block_force.clear();
    s_.max_penetration = std::max(s_.max_penetration, totals.max_penetration);
    s_.max_capped = std::max(s_.max_capped, totals.capped);
  }
  if (!contact) s_.block_force.clear();
  watch.restart();
  measure_balance(d, context, contact);
  if (!scene().absorbing.empty()) {
    const AbsorbingWork w = absorbing_work(b_->model, context, d);
    s_.absorbed_work += w.absorbed;
    s_.absorbing_load_work += w.loads;
  }
  b_->bolts.commit(d, b_->config, s_.bolts);
  update_state(b_->model, context, covers_d, s_);
  timings_.geometry_update += watch.seconds();
  s_.time += dt;
  ++s_.step;
  return {};
}

void TimeStepper::trace_rejected_step(const Eigen::VectorXd& covers_d, double max_penetration) const {
  // NMM_TRACE_PEN: the cover a rejected step moved most (its node and support) and the contacts it
  // found deepest (which vertex, which edge, how deep at the start and the end), on stderr: for
  // finding why a run cuts its step (docs/fracture.md).
  static const bool trace = std::getenv("NMM_TRACE_PEN") != nullptr;
  if (!trace) return;
  Eigen::Index worst = 0;
  const double moved = covers_d.cwiseAbs().maxCoeff(&worst);
  const int cover = b_->space.cover_of_unknown(static_cast<int>(worst));
  const std::int32_t node = mesh().cover_node[static_cast<std::size_t>(cover)];
  int elements = 0;
  const double support = cover_support(mesh(), cover, elements);
  std::fprintf(stderr, "moved most: cover %d (node %d at %.9g %.9g) by %.3g m; %d elements, support %.3g m2\n", cover,
               node, mesh().node_xy[2 * node], mesh().node_xy[2 * node + 1], moved, elements, support);
  for (const Contact& c : b_->contacts.contacts())
    if (-c.gap > 0.5 * max_penetration)
      std::fprintf(stderr, "pen: v %d (elem %d blk %d, at %.9g %.9g) edge %d (elem %d blk %d) gap0 %.3g gap %.3g state0 %d len %.3g\n",
                   c.at.vertex, c.at.elem_a, mesh().element_block[c.at.elem_a], s_.loop_xy[2 * c.at.vertex],
                   s_.loop_xy[2 * c.at.vertex + 1], c.at.edge, c.at.elem_b, mesh().element_block[c.at.elem_b], c.at.gap,
                   c.gap, static_cast<int>(c.start_state), c.length);
}

Outcome TimeStepper::solve_step(bool contact, bool again, Eigen::VectorXd& d, Eigen::VectorXd& residual,
                                bool& iterated) {
  auto not_positive_definite = [&]() {
    const int u = system_.failed_unknown();
    if (u >= b_->space.unknowns())
      return "the system matrix is not positive definite at " + b_->bolts.describe_unknown(u) + ": a cable held by nothing";
    return not_positive_definite_message(mesh(), b_->space, u);
  };
  Stopwatch watch;
  if (!contact) {
    const bool ok = system_.factorize();
    ++timings_.factorisations;
    timings_.factorisation += watch.seconds();
    if (!ok) return stop(StopCode::unconstrained, not_positive_definite());
    watch.restart();
    d = system_.solve(rhs_);
    ++timings_.solves_count;
    timings_.solves += watch.seconds();
    return {};
  }
  const ContactSolveStats before = solve_stats_;
  const double tau = scene().solver.contact_tolerance;
  const auto solve = [&](bool warm) {
    return solve_contact_step(system_, b_->problem, rhs_base_, tau,
                              b_->contacts.softening() ? displacement_tolerance(tau, b_->model.w0()) : 0.0, d,
                              solve_stats_, handed_on_share() > 0 ? &residual : nullptr, warm);
  };
  Outcome outcome = solve(again);
  // Bonds and cohesion break only at a solution of the step, and the step is solved again with
  // them broken until no unbroken contact is beyond its peak (contact_problem.h break_at_peak). Each
  // round breaks at least one contact, so this ends.
  for (bool resolved = false; outcome.ok();) {
    if (!b_->problem.break_at_peak().resolve) break;
    if (!resolved) ++solve_stats_.steps_resolved_for_breaks;
    resolved = true;
    ++solve_stats_.break_resolves;
    outcome = solve(true);  // from the solution before the breaks
  }
  if (outcome.ok()) b_->problem.settle_states();
  iterated = iterated || solve_stats_.newton > before.newton;
  timings_.factorisations += solve_stats_.factorisations - before.factorisations;
  timings_.factorisation += solve_stats_.factorisation_seconds - before.factorisation_seconds;
  timings_.solves_count += solve_stats_.cg_iterations - before.cg_iterations +
                           (solve_stats_.factorisations - before.factorisations);
  timings_.solves += solve_stats_.cg_seconds - before.cg_seconds +
                     solve_stats_.line_search_seconds - before.line_search_seconds;
  s_.iterations += static_cast<std::uint64_t>(solve_stats_.newton - before.newton);
  s_.friction_unsettled += static_cast<std::uint64_t>(solve_stats_.unsettled - before.unsettled);
  if (outcome.code == StopCode::unconstrained) return stop(StopCode::unconstrained, not_positive_definite());
  if (!outcome.ok()) return stop(outcome.code, std::move(outcome.reason));
  return {};
}

void TimeStepper::take_absorbing_reaction(bool contact) {
  // The state's out-of-balance force with d = 0 and no inertia: the step's form at the state's
  // own time with zero inertia coefficients (no mass term, no dashpots: absorbing_boundary.h),
  // the bolts' start forces and, with contact, the contacts' forces at d = 0.
  s_.absorbing_key.clear();
  s_.absorbing_reaction.clear();
  StepContext rest = step_context(0.0);
  rest.dt = 0;
  rest.t_end = s_.time;
  rest.body_force = body_force_per_mass(scene(), s_.time);
  rest.inertia = InertiaCoefficients{};
  b_->bolts.begin_step(b_->config, s_, removed_elem_);
  b_->form.assemble(rest, system_, rhs_);
  b_->bolts.assemble(system_, rhs_, mesh().element_count());
  if (contact) {
    b_->problem.start_strengths();
    b_->problem.forces_at(Eigen::VectorXd::Zero(rhs_.size()), rhs_);
  }
  s_.absorbing_reaction = absorbing_reaction_of(b_->model, b_->config, rhs_, b_->space.unknowns());
  s_.absorbing_key = absorbing_key(scene());
}

Outcome TimeStepper::attempt(double dt) {
  if (!fracture_.active()) return attempt_once(dt);
  // Intact rock that breaks (fracture.h): the rock breaks where the step's solution exceeds its
  // strength, and the step is taken again from its start on the cracked mesh, until its solution
  // breaks nothing more — as contacts' bonds break (contact_problem.h break_at_peak). A cascade
  // is bounded: past kMaxRecutsPerStep re-cuts the step is cut (a shorter step loads the rock
  // less, so fewer elements break at its solution) and tried again on the cracked mesh; the run
  // goes on.
  // The step's start is kept in buffers that live from step to step (step_start.h): a quiet
  // step copies it into memory already there and allocates nothing.
  for (int recuts = 0;; ++recuts) {
    if (recuts >= kMaxRecutsPerStep)
      return stop(StopCode::fracture_cascade, "cracks were still growing after " + std::to_string(kMaxRecutsPerStep) +
                                                  " re-cuts of the mesh within one step");
    Stopwatch watch;
    step_start_.keep(s_, b_->contacts.history());
    timings_.fracture += watch.seconds();
    const Outcome o = attempt_once(dt);
    if (!o.ok()) return o;
    watch.restart();
    std::vector<CrackSegment> segments = fracture_.find(mesh(), scene(), s_, removed_elem_);
    if (segments.empty()) {
      timings_.fracture += watch.seconds();
      return o;
    }
    step_start_.restore(s_);  // with the diagnostics of this solve: they count both
    break_rock(segments, step_start_.take_history());
    fracture_.count_resolve();
    timings_.fracture += watch.seconds();
  }
}

void TimeStepper::break_rock(const std::vector<CrackSegment>& segments, std::vector<ContactHistory> history) {
  auto cracked = std::make_unique<SceneDef>(scene());
  const std::size_t first = cracked->joints.size();
  for (const CrackSegment& c : segments) cracked->joints.push_back({cracked->fracture.crack_set, {c.a, c.b}});
  pre::RecutMap map;
  auto mesh = std::make_unique<Mesh>(pre::recut(this->mesh(), *cracked, first, scene_name_, map));
  // The check mode (docs/fracture.md "Re-cutting"): a re-cut that is not the full cut is a
  // defect of the re-cut, not of the run's physics: it ends the run with the difference.
  if (recut_check_enabled())
    if (const std::string diff = recut_difference(this->mesh(), *mesh, *cracked, scene_name_); !diff.empty())
      throw RunError("NMM_CHECK_RECUT: at t = " + std::to_string(s_.time) + " s the re-cut of " +
                     std::to_string(segments.size()) + " crack segment(s) is not the full cut: " + diff);
  transfer_state(this->mesh(), *mesh, map, b_->space.dofs_per_cover(), s_);
  history = transfer_history(history, this->mesh(), *mesh, map, first);
  fracture_.cut(segments, *mesh, map);
  // Composed with the step's earlier re-cuts: the observers last saw the mesh of the last
  // accepted step, not the one this cut started from.
  if (recut_step_ == s_.step && recut_.element_parent.size() == this->mesh().element_count()) {
    recut_ = compose(map, recut_);
  } else {
    recut_ = std::move(map);
    recut_from_ = topology_;
    recut_step_ = s_.step;
  }
  ++topology_;
  replace_mesh(std::move(mesh), std::move(cracked), std::move(history));
  apply_removed();
  recut_start_ = s_;
}

void TimeStepper::replace_mesh(std::unique_ptr<Mesh> mesh, std::unique_ptr<SceneDef> scene,
                               std::vector<ContactHistory> history) {
  auto bound = std::make_unique<MeshBound>(*mesh, *scene, scene_name_, fracture_.segments().size());
  bound->contacts.restore(std::move(history), {});
  bound->contacts.continue_from(b_->contacts);
  b_ = std::move(bound);  // before the mesh and scene it referred to go
  own_mesh_ = std::move(mesh);
  own_scene_ = std::move(scene);
  mesh_ = own_mesh_.get();
  scene_ = own_scene_.get();
  // A new pattern of the elements (the contacts grow it again) and no factorisation to reuse.
  // (A scene with fracturing has no bolts: scene.cpp refuses the two together.)
  b_->bolts.number(s_.bolts, b_->space.unknowns());
  build_pattern_with_pairs();
  system_.drop_factor();
  rhs_.resize(system_unknowns());
}

void TimeStepper::measure_balance(const Eigen::VectorXd& d, const StepContext& step, bool contact) {
  // The same body force, β and loads as the step's assembly, at the step's end.
  const double t_end = step.t_end;
  const auto [bx, by] = step.body_force;
  StepBalance b;
  b.d = &d;
  b.v0 = &s_.velocity;
  b.a0 = &s_.accel;
  b.dt = step.dt;
  b.beta = step.beta;
  Eigen::VectorXd kd;
  if (!step_inertia()) {
    // No mass: the force the solve balanced, K·d (with contacts: the saved matrix, K without
    // the contact springs; without: K·d = the right-hand side itself).
    if (contact) system_.saved_times(d, kd);
    b.balance = contact ? &kd : &rhs_;
  }
  b.applied_sum = applied_force_sum(scene(), s_, t_end, std::hypot(bx, by),
                                    b_->indicator.active_mass(s_.body_removed), b_->model.traction_edges(),
                                    b_->model.interface_edges(), removed_elem_);
  b.stress = &s_.stress;
  b.stress_terms = stress_terms();
  balance_ = b_->indicator.measure(b, s_.body_removed);
}

void TimeStepper::step(double dt) {
  const Outcome o = attempt(dt);
  if (!o.ok()) throw RunError(o.reason);
}

Outcome TimeStepper::run_until(double t_end, const std::function<void(std::int64_t)>& on_step,
                               std::int64_t max_steps) {
  // Attempts under Shi's step control (step_control.h): without contact nothing is rejected and
  // every step has the full length time_step. What a shorter step may cure is cut and tried
  // again; anything else stops the run at once.
  const SolverDef& sv = scene().solver;
  control_ = StepControl(sv, b_->model.w0(), s_.dt);
  std::int64_t done = 0;
  stopped_at_ratio_ = false;
  while (!control_.done(s_.time, t_end)) {
    // Between steps only, so an interrupted run stops in a consistent state.
    if (stop_check_ && stop_check_()) return stop(StopCode::interrupted, "interrupted");
    const double h = control_.next(s_.time, t_end);
    const Outcome o = attempt(h);
    if (!o.ok()) {
      if (!cured_by_shorter_step(o.code)) return o;
      static const bool trace = std::getenv("NMM_TRACE_CUTS") != nullptr;
      if (trace) std::fprintf(stderr, "cut at t = %.9g: %s\n", s_.time, o.reason.c_str());
      ++s_.cuts;
      if (!control_.cut(h)) {
        std::ostringstream os;
        os << "time step cut below its floor (" << control_.floor() << " s) at t = " << s_.time
           << " s because " << o.reason;
        return stop(o.code, os.str());
      }
      continue;
    }
    control_.accept();
    s_.dt = control_.dt();
    // UDEC's `solve ratio`: the run has reached equilibrium (equilibrium_indicator.cpp).
    stopped_at_ratio_ = sv.stop_at_ratio > 0 && balance_.max_ratio < sv.stop_at_ratio &&
                        (!sv.dynamic || balance_.max_velocity < RestCriterion::kVelocity);
    on_step(++done);
    if (stopped_at_ratio_ || done == max_steps) break;
  }
  return stop(StopCode::ok, "");
}

void TimeStepper::restart_from(const std::string& path) {
  std::string history, factor;
  const CheckpointSections sections = read_checkpoint_file(path);
  // A cracked run: its mesh and cracks come with the state.
  const auto section = [&](const char* tag) {
    const auto it = std::find_if(sections.begin(), sections.end(), [&](const auto& s) { return s.first == tag; });
    return it == sections.end() ? nullptr : &it->second;
  };
  if (const std::string* mesh_bytes = section("MESH")) {
    if (!scene().fracture.present || !section("FRACTURE"))
      throw InputError(path, "section MESH", "a cracked run's checkpoint: the scene needs its fracture block");
    auto cracked_mesh = std::make_unique<Mesh>(mesh_from_bytes(*mesh_bytes, path + " section MESH"));
    if (cracked_mesh->scene_sha256 != mesh().scene_sha256)
      throw InputError(path, "section MESH", "the cracked mesh of another scene");
    fracture_.load(*section("FRACTURE"), *cracked_mesh, path);
    auto cracked = std::make_unique<SceneDef>(scene());
    for (const CrackSegment& c : fracture_.segments()) cracked->joints.push_back({cracked->fracture.crack_set, {c.a, c.b}});
    s_.pattern_pairs.clear();  // of the mesh before; the checkpoint's own follow in restore
    replace_mesh(std::move(cracked_mesh), std::move(cracked), {});
  }
  const RunState st = state_from_sections(sections, mesh(), path, history, b_->space.dofs_per_cover(),
                                          b_->space.terms(), &factor);
  restore(st, history, path);
  // Bolts installed at this restart change the system's size: its first step factorises anew.
  if (!factor.empty() && b_->contacts.active() && !bolts_renumbered_ && !system_.factor_from_source(factor))
    throw InputError(path, "section FACTOR", "not the matrix of a factorisation of this run's size");
}

void TimeStepper::restore(const RunState& st, const std::string& history, const std::string& name) {
  s_ = restarted_state(st, s_, scene().bodies.size(), name);
  load_contact_history(b_->contacts, history, mesh(), name);
  apply_removed();
  excavate(scene().excavate);
  // Absorbing boundaries: the checkpoint's carried reaction where its scene had the same
  // polylines, else it is taken again at the first step (absorbing_boundary.h).
  if (!s_.absorbing_key.empty() && s_.absorbing_key == absorbing_key(scene()) &&
      s_.absorbing_reaction.size() != static_cast<std::size_t>(b_->space.unknowns()))
    throw InputError(name, "section ABSORB", "the carried reaction has " + std::to_string(s_.absorbing_reaction.size()) +
                                                 " unknowns, the run " + std::to_string(b_->space.unknowns()));
  if (scene().absorbing.empty()) s_.absorbing_key.clear(), s_.absorbing_reaction.clear(), s_.absorbed_work = 0,
                                 s_.absorbing_load_work = 0;
  // Bolts: the checkpoint's where the scene still has them, the others installed now
  // (bolt_layout.h); then the same pattern as the run that wrote the checkpoint (its pairs, and
  // the bolts' groups): the same symbolic analysis, the same round-off.
  const std::vector<BoltState> carried = s_.bolts;
  place_bolts(carried);
  bolts_renumbered_ = s_.bolts.size() != carried.size() ||
                      !std::equal(carried.begin(), carried.end(), s_.bolts.begin(), [](const BoltState& a, const BoltState& b) {
                        return a.type == b.type && a.ax == b.ax && a.ay == b.ay && a.bx == b.bx && a.by == b.by &&
                               a.installed_step == b.installed_step;
                      });
  if (!s_.pattern_pairs.empty()) b_->problem.assign_groups(s_.pattern_pairs, first_pair_group());
}

void TimeStepper::excavate(const std::vector<int>& bodies) {
  excavate_bodies(bodies, mesh(), stress_terms(), s_);
  apply_removed();
}

void TimeStepper::apply_removed() {
  removed_elem_ = removed_elements(mesh(), s_);
  // Debris the cracks cut off leaves the model like an excavated body (fracture.h).
  const std::vector<std::uint8_t>& debris = fracture_.debris();
  for (std::size_t e = 0; e < debris.size(); ++e) removed_elem_[e] = removed_elem_[e] || debris[e];
  const bool any = std::any_of(removed_elem_.begin(), removed_elem_.end(),
                               [](std::uint8_t r) { return r != 0; });
  b_->contacts.set_removed_elements(any ? removed_elem_ : std::vector<std::uint8_t>{});
  hold_removed_covers(mesh(), b_->space.dofs_per_cover(), removed_elem_, s_);
}

}  // namespace nmm::solve
