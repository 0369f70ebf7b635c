// NMM time stepping with Shi's implicit scheme (Shi 1988, 1991; docs/physics.md §2): the
// stepping core. A step of length Δt is one attempt:
//
//   frames      the configuration placed on the covers' positions (configuration.h)
//   begin       each effect with state the scene calls for (effect.h, listed in mesh_bound.h)
//               begins the step: contacts detected within the search distance and the pattern
//               grown by new element pairs, an effect's springs linearised at the step's start
//   assembly    K and F by the scene's form (form.h): the integrators it calls for, one per
//               term (integrators.h: elasticity, initial stress, body force, inertia with
//               newmark.h's coefficients, fixed points, loads, supports, tractions, face
//               pressures, in-situ traction); excavated covers pinned (excavation.h, K += k_pin I); then
//               each effect's terms
//   solve       one factorisation, or the effect that solves the step its own way (the
//               contacts' problem, contact_solve.h); solved again while an effect judges the
//               solution wrong for what it assembled (a spring that yields)
//   acceptance  Shi's step control (step_control.h) on the effects' penetration and on the
//               elements the step would fold: a rejected attempt leaves the state as it was
//               and the caller cuts Δt
//   update      the effects commit, and the state is moved on by d (state_update.h), after the
//               equilibrium indicators (equilibrium_indicator.h) are taken from d, v0 and a0
//   re-cut      an effect that changes the mesh at the solution (mesh_change.h) has the
//               step taken again from its start on the new mesh
//
// Unknowns: the cover functions' coefficients during the step (cover_space.h; a sliver cover
// shares a neighbour's, cover_unknowns.cpp), then the effects' own. All integrals are exact
// simplex integrals over the element polygon (element_integration.cpp). Everything carried from
// step to step is in RunState s_ (run_state.h) and the contact history: a checkpoint of both
// continues a run bitwise exactly (restart.h). Only the effects a scene calls for are computed
// (run_effects.h). The stepper names no effect: docs/code-layout.md "Effects".
#include "solver/stepping/time_stepper.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <sstream>

#include "common/checkpoint_file.h"
#include "common/error.h"
#include "common/stopwatch.h"
#include "solver/discretisation/excavation.h"
#include "solver/discretisation/form.h"
#include "solver/discretisation/integrators.h"
#include "solver/discretisation/newmark.h"
#include "solver/discretisation/solver_threads.h"
#include "solver/discretisation/static_support.h"
#include "solver/fracture/crack_release.h"
#include "solver/fracture/state_transfer.h"
#include "solver/stepping/initial_state.h"
#include "solver/stepping/restart.h"
#include "solver/stepping/state_update.h"

namespace nmm::solve {

TimeStepper::TimeStepper(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name)
    : mesh_(&mesh), scene_(&scene), scene_name_(scene_name),
      b_(std::make_unique<MeshBound>(mesh, scene, scene_name)), changes_(mesh, scene),
      control_(scene.solver, b_->model.w0(), scene.solver.time_step) {
  // Higher-order coefficients may be linearly dependent (cover_space.h, system_matrix.h).
  if (b_->space.order() > 0) system_.set_regularised(b_->space.higher_order_unknowns(), kRegularisation);
  // An effect that solves the steps (contacts) changes the pattern every few steps: each
  // analysis orders by AMD alone.
  system_.set_amd_only(b_->solved_by_effect());
  s_ = initial_state(b_->model, b_->space);
  excavate(scene.excavate);
  // Fixed points and loads couple only the covers of their element: the element pattern holds
  // until an effect couples more (contacts pairs of elements, an effect its elements from the start).
  place_effects(scene_name_);
  set_threads(0);
}

bool TimeStepper::place_effects(const std::string& name) {
  bool fits = true;
  for (Effect* e : b_->effects) fits = e->install(s_, name) && fits;
  number_effects();
  return fits;
}

void TimeStepper::number_effects() {
  // The largest runs with contact order by METIS on the covers (system_matrix.h
  // set_block_ordering): the covers of this mesh, the effects' own unknowns after them.
  system_.set_block_ordering(b_->solved_by_effect() ? b_->space.dofs_per_cover() : 0, b_->space.unknowns());
  // And keep their factor in single precision (system_matrix.h set_single_precision): its solves
  // are most of a CG iteration, and read it at the memory's speed.
  system_.set_single_precision(b_->solved_by_effect() ? kSingleFactorUnknowns : 0);
  rhs_.resize(b_->number(s_));
  build_pattern();
}

void TimeStepper::set_threads(int threads) {
  threads_ = set_solver_threads(threads > 0 ? threads : default_solver_threads(b_->space.unknowns()));
}



Outcome TimeStepper::compute_frames() {
  const std::int64_t e = b_->config.place(s_.cover_xy);
  // NMM_TRACE_FOLD: the folded element's covers (node, where the node is, where the cover has
  // put it, its parent before the step's re-cuts) on stderr: for finding where a fold came from.
  static const bool trace = std::getenv("NMM_TRACE_FOLD") != nullptr;
  if (e >= 0 && trace) {
    const Mesh& m = mesh();
    const std::size_t u = static_cast<std::size_t>(e);
    std::fprintf(stderr, "fold: element %lld (block %d, area %.3g m2) at t %.9g, step re-cut %d\n",
                 static_cast<long long>(e), m.element_block[u], element_area(m, u), s_.time,
                 recut_step_ == s_.step ? 1 : 0);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t c = m.element_covers[3 * u + static_cast<std::size_t>(k)], n = m.cover_node[static_cast<std::size_t>(c)];
      const std::int32_t parent =
          recut_step_ == s_.step && static_cast<std::size_t>(c) < recut_.cover_parent.size() ? recut_.cover_parent[static_cast<std::size_t>(c)] : -1;
      std::fprintf(stderr, "fold:   cover %d node %d at %.9g %.9g, placed %.9g %.9g, parent %d\n", c, n,
                   m.node_xy[2 * static_cast<std::size_t>(n)], m.node_xy[2 * static_cast<std::size_t>(n) + 1],
                   s_.cover_xy[2 * static_cast<std::size_t>(c)], s_.cover_xy[2 * static_cast<std::size_t>(c) + 1], parent);
    }
  }
  if (e >= 0)
    return stop(StopCode::element_folded, "element " + std::to_string(e) + ": its triangle is folded over in the state at t = " +
                                              std::to_string(s_.time) +
                                              " s (a restart or a re-cut carried it; an accepted step folds none)");
  return {};
}

Outcome TimeStepper::stop(StopCode code, std::string reason) const {
  return Outcome::stop(code, std::move(reason), s_.time);
}

void TimeStepper::build_pattern() {
  std::vector<int> offsets{0}, dofs;
  b_->pattern_groups(s_, offsets, dofs);
  system_.build_pattern(static_cast<int>(rhs_.size()), offsets, dofs);
}

EffectStep TimeStepper::effect_step(const StepContext& context) {
  return {context, s_, system_, rhs_, control_.search_distance(), control_.allowance(), timings_, *this};
}

StepContext TimeStepper::step_context(double dt) const {
  return make_step_context(b_->model, b_->config, s_, removed_elem_, dt);
}

Outcome TimeStepper::attempt_once(double dt) {
  // The reach (step_control.h): open contacts looked for r = min(d0, 0.05·h) far; an attempt that
  // moves a loop vertex more than r/2 is taken again looking farther, with the same Δt.
  double reach = control_.contact_reach(mesh().mesh_size);
  for (;;) {
    double redo = 0;
    Outcome o = attempt_reaching(dt, reach, redo);
    if (!(redo > 0)) return o;
    static const bool trace = std::getenv("NMM_TRACE_CUTS") != nullptr;
    if (trace) std::fprintf(stderr, "reach %.6g m redone at %.6g m at t = %.9g\n", reach, redo, s_.time);
    ++timings_.reach_redos;
    reach = redo;
  }
}

Outcome TimeStepper::attempt_reaching(double dt, double reach, double& redo) {
  // The start guess is this attempt's alone: a shorter attempt after it starts from 0.
  std::vector<double> carried;
  carried.swap(carried_);
  // The effects that take part in the run's steps (mesh_bound.h), and the one that solves the
  // step its own way (the contacts' problem); without it one factorisation and solve — where no
  // two faces can touch (an opening excavated from one unjointed block), no contact detection.
  std::vector<Effect*> active;
  Effect* solver = nullptr;
  for (Effect* e : b_->effects)
    if (e->active()) {
      active.push_back(e);
      if (e->solves()) solver = e;
    }
  if (!step_inertia() && !solver)
    if (std::string why = unheld_block(b_->model, s_); !why.empty()) return stop(StopCode::unconstrained, std::move(why));
  Stopwatch watch;
  if (Outcome folded = compute_frames(); !folded.ok()) return folded;
  timings_.assembly += watch.seconds();
  const StepContext context = step_context(dt);  // the attempt's one context (step_context.h)
  EffectStep step = effect_step(context);
  step.reach = reach;
  for (Effect* e : active) {
    if (Outcome o = e->begin_step(step); !o.ok()) return o;
    if (step.pattern_changed) build_pattern();
    step.pattern_changed = false;
  }
  // On a mesh re-cut within this step, what the cut opened of the force its start is out of
  // balance by (crack_release.h), for the energy meter; the assembly below starts afresh.
  const bool recut_in_step = recut_step_ == s_.step;
  if (recut_in_step) {
    // B with the contacts' forces the start was in balance with, each on the piece it acts on
    // (the last accepted step's end forces carried over the re-cuts: contact_effect.h), so that
    // a split cover's pieces share what it was out of balance by, not its contacts' forces.
    Eigen::VectorXd B = force_at_rest_of_loads();
    b_->contact.add_ended_forces(B);
    start_force_ = cut_release_force(b_->model, b_->config, s_, removed_elem_, recut_.cover_parent, B);
  }

  // Assembly and solve; an effect that judges the solution wrong for what it assembled (a
  // spring that yields, slips or breaks) has the step solved again from there.
  StepSolution x;
  // On a mesh a crack re-cut within this step: the iterative solve starts from the solution the
  // step had on the mesh before (carried_, taken by this attempt alone), which differs from this
  // one's by what the new cracks open. From d = 0 each re-solve ran the whole friction fixed
  // point of a sliding, breaking wedge again: 17 factorisations of the 18 a first attempt takes
  // (docs/fracture.md "Robustness matrix"). Covers of removed elements (debris) are held: 0.
  if (!carried.empty() && solver) {
    const std::size_t dpc = static_cast<std::size_t>(b_->space.dofs_per_cover());
    std::vector<std::uint8_t> held(mesh().cover_count(), 0);
    for (std::size_t e = 0; e < mesh().element_count(); ++e)
      if (removed_elem_[e])
        for (int k = 0; k < 3; ++k) held[static_cast<std::size_t>(mesh().element_covers[3 * e + k])] = 1;
    x.d = Eigen::VectorXd::Zero(rhs_.size());
    for (std::size_t c = 0; c < held.size() && dpc * (c + 1) <= carried.size(); ++c) {
      const int u = b_->space.first_unknown(c);
      // A sliver cover shares its neighbour's unknowns: the owner's increment is the one kept.
      if (held[c] || b_->space.cover_of_unknown(u) != static_cast<int>(c)) continue;
      for (std::size_t k = 0; k < dpc; ++k) x.d[u + static_cast<Eigen::Index>(k)] = carried[dpc * c + k];
    }
    x.guess = true;
  }
  for (int round = 0;; ++round) {
    watch.restart();
    b_->form.assemble(context, system_, rhs_);
    for (Effect* e : active) e->assemble(step);
    // The blocks' share of the last step's out-of-balance force (block_momentum.h); not in a
    // static step (a restart may switch a dynamic run to static), whose balance starts afresh.
    if (!s_.block_force.empty() && handed_on_share() > 0) b_->momentum.add_forces(s_.block_force, s_.cover_xy, rhs_);
    timings_.assembly += watch.seconds();
    if (Outcome solved = solve_step(step, solver, round > 0, x); !solved.ok()) return solved;
    Effect* again = nullptr;
    for (Effect* e : active)
      if (e->judge(x.d) && !again) again = e;
    if (!again) break;
    if (round + 1 >= again->max_solves()) return again->not_settled(s_.time);
  }
  const Eigen::VectorXd& d = x.d;
  if (changes_.active()) solved_d_ = d;  // what a re-cut at this solution carries (attempt)
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (!std::isfinite(d[i]))
      return stop(StopCode::displacement_not_finite,
                  (i < b_->space.unknowns() ? "the displacement of cover " +
                                                  std::to_string(b_->space.cover_of_unknown(static_cast<int>(i)))
                                            : b_->describe_unknown(static_cast<int>(i))) +
                      " is not a finite number at t = " + std::to_string(s_.time) + " s");
  // The covers' motion: an effect's own unknowns (a cable's slip) are no block moving.
  const Eigen::VectorXd covers_d = d.head(b_->space.unknowns());
  // The reach check (step_control.h): with its loop vertices moved at most m, no two faces came
  // more than 2·m nearer; past the reach, a contact left out could have closed: the attempt is
  // taken again from its start (the same guess, the same Δt) with every contact within 4·m.
  if (step.checked_reach > 0) {
    const double moved = largest_loop_move(b_->model, context, covers_d, s_);
    if (2 * moved > step.checked_reach) {
      carried_.swap(carried);
      redo = std::min(control_.search_distance(), 4 * moved);
      return {};
    }
  }
  if (recut_in_step) recut_start_work_ = start_force_.dot(covers_d);
  // Shi's step control judges a step whose effects judge its penetration (the contacts').
  StepPenetration penetration;
  for (const Effect* e : active) {
    const StepPenetration p = e->penetration(step);
    penetration.added = std::max(penetration.added, p.added);
    penetration.deepest = std::max(penetration.deepest, p.deepest);
    const PenetrationAllowance allowed = control_.allowance();
    if (p.worst_end - allowed.deepest(p.worst_start) > penetration.worst_end - allowed.deepest(penetration.worst_start)) {
      penetration.worst_start = p.worst_start;
      penetration.worst_end = p.worst_end;
    }
  }
  if (penetration.added >= 0) {
    Outcome rejected = control_.rejection(covers_d.cwiseAbs().maxCoeff(), penetration, step_inertia());
    if (!rejected.ok()) {
      for (const Effect* e : active) e->rejected(step, covers_d);
      return stop(rejected.code, std::move(rejected.reason));
    }
  }
  // A step that folds an element is rejected here, before it is accepted, so a shorter one can
  // be tried (step_control.h); found at the next attempt's start (compute_frames) it could not.
  if (const std::int64_t folded = b_->config.folded_by(covers_d); folded >= 0) {
    for (const Effect* e : active) e->rejected(step, covers_d);
    Outcome rejected = control_.folding(folded);
    return stop(rejected.code, std::move(rejected.reason));
  }
  // Handed on with the velocity the step carries over (block_momentum.h); a step in balance at
  // its start hands nothing on, and a direct solve leaves nothing to hand on.
  if (handed_on_share() > 0 && x.iterated)
    b_->momentum.net_forces(x.residual, handed_on_share(), s_.cover_xy, s_.block_force);
  else
    s_.block_force.clear();
  watch.restart();
  // The equilibrium indicators; without mass, of the force the solve balanced, K·d (solved by an
  // effect: the saved matrix, K without the contacts' springs; else the right-hand side itself).
  Eigen::VectorXd kd;
  if (!step_inertia() && solver) system_.saved_times(d, kd);
  balance_ = b_->indicator.measure_step(b_->model, context, d, step_inertia() ? nullptr : solver ? &kd : &rhs_);
  for (Effect* e : active) e->commit(step, d);
  update_state(b_->model, context, covers_d, s_);
  timings_.geometry_update += watch.seconds();
  s_.time += dt;
  ++s_.step;
  return {};
}

Outcome TimeStepper::solve_step(EffectStep& step, Effect* solver, bool again, StepSolution& x) {
  auto not_positive_definite = [&]() {
    const int u = system_.failed_unknown();
    if (u >= b_->space.unknowns())
      return "the system matrix is not positive definite at " + b_->describe_unknown(u) + ": it is held by nothing";
    return not_positive_definite_message(mesh(), b_->space, u);
  };
  if (solver) {
    Outcome o = solver->solve(step, again, x);
    if (o.code == StopCode::unconstrained) return stop(StopCode::unconstrained, not_positive_definite());
    if (!o.ok()) return stop(o.code, std::move(o.reason));
    return {};
  }
  Stopwatch watch;
  const bool ok = system_.factorize();
  ++timings_.factorisations;
  timings_.factorisation += watch.seconds();
  if (!ok) return stop(StopCode::unconstrained, not_positive_definite());
  watch.restart();
  x.d = system_.solve(rhs_);
  ++timings_.solves_count;
  timings_.solves += watch.seconds();
  return {};
}

const Eigen::VectorXd& TimeStepper::assemble_at_rest(bool with_solver) {
  // The state's out-of-balance force with d = 0 and no inertia: the step's form at the state's
  // own time with zero inertia coefficients (no mass term, no dashpots) and the effects' terms
  // at rest (their springs' start forces, the contacts' forces at d = 0).
  StepContext rest = step_context(0.0);
  rest.dt = 0;
  rest.t_end = s_.time;
  rest.body_force = body_force_per_mass(scene(), s_.time);
  rest.inertia = InertiaCoefficients{};
  b_->form.assemble(rest, system_, rhs_);
  EffectStep step = effect_step(rest);
  for (Effect* e : b_->effects)
    if (e->active() && (with_solver || !e->solves())) e->add_at_rest(step);
  return rhs_;
}

const Eigen::VectorXd& TimeStepper::force_at_rest() { return assemble_at_rest(true); }

Eigen::VectorXd TimeStepper::force_at_rest_of_loads() {
  // Without the effect that solves the step: the contacts' start forces are left out
  // (evaluating them moves their solve's starting point, and with it the step's round-off);
  // a new face's contact starts with none (state_transfer.h).
  return assemble_at_rest(false).head(b_->space.unknowns());
}

Outcome TimeStepper::attempt(double dt) {
  MeshChange* change = changes_.active();
  if (!change) return attempt_once(dt);
  // An effect that changes the mesh at the step's solution (mesh_change.h: the rock breaks where
  // the solution exceeds its strength) has the step taken again from its start on the new mesh,
  // until its solution changes nothing more — as contacts' bonds break (contact_problem.h
  // break_at_peak). A cascade is bounded: past max_per_step() changes the step is cut (a shorter
  // step loads the rock less, so fewer elements break at its solution) and tried again on the
  // new mesh; the run goes on.
  // The step's start is kept in buffers that live from step to step (step_start.h): a quiet
  // step copies it into memory already there and allocates nothing.
  for (int changes = 0;; ++changes) {
    if (changes >= change->max_per_step()) return change->cascade(s_.time);
    Stopwatch watch;
    step_start_.keep(s_, b_->contact_history());
    change->book(watch.seconds(), timings_);
    const Outcome o = attempt_once(dt);
    if (!o.ok()) return o;
    NewMesh m;
    if (!change->change(mesh(), scene(), scene_name_, s_, removed_elem_, b_->space.dofs_per_cover(),
                        step_start_.state(), step_start_.history(), b_->effects, m, timings_))
      return o;
    // The solution just found, each new cover taking its parent's increment: the re-solve's
    // start guess (attempt_once).
    const std::size_t dpc = static_cast<std::size_t>(b_->space.dofs_per_cover());
    std::vector<double> carried(dpc * m.map.cover_parent.size(), 0.0);
    for (std::size_t c = 0; c < m.map.cover_parent.size(); ++c) {
      const std::int32_t p = m.map.cover_parent[c];
      if (p < 0 || static_cast<std::size_t>(p) >= mesh().cover_count()) continue;
      const Eigen::Index u = b_->space.first_unknown(static_cast<std::size_t>(p));
      if (u + static_cast<Eigen::Index>(dpc) > solved_d_.size()) continue;
      for (std::size_t k = 0; k < dpc; ++k) carried[dpc * c + k] = solved_d_[u + static_cast<Eigen::Index>(k)];
    }
    step_start_.restore(s_);  // the start, carried onto the new mesh, with this solve's diagnostics
    watch.restart();
    change_mesh(std::move(m));
    carried_ = std::move(carried);
    change->count_resolve();
    change->book(watch.seconds(), timings_);
  }
}

void TimeStepper::change_mesh(NewMesh m) {
  // Composed with the step's earlier re-cuts: the observers last saw the mesh of the last
  // accepted step, not the one this cut started from.
  const bool again = recut_step_ == s_.step && recut_.element_parent.size() == mesh().element_count();
  replace_mesh(std::move(m.mesh), std::move(m.scene), std::move(m.history), &m.map);
  if (again) {
    recut_ = compose(m.map, recut_);
  } else {
    recut_ = std::move(m.map);
    recut_from_ = topology_;
    recut_step_ = s_.step;
  }
  ++topology_;
  apply_removed();
  recut_start_ = s_;
}

void TimeStepper::replace_mesh(std::unique_ptr<Mesh> mesh, std::unique_ptr<SceneDef> scene,
                               std::vector<ContactHistory> history, const pre::RecutMap* map) {
  auto bound = std::make_unique<MeshBound>(*mesh, *scene, scene_name_, changes_.joints_added());
  bound->continue_from(*b_, std::move(history), map, s_);
  b_ = std::move(bound);  // before the mesh and scene it referred to go
  own_mesh_ = std::move(mesh);
  own_scene_ = std::move(scene);
  mesh_ = own_mesh_.get();
  scene_ = own_scene_.get();
  // A new pattern of the elements (the contacts grow it again) and no factorisation to reuse.
  number_effects();
  system_.drop_factor();
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
  // A run whose mesh an effect changed: the mesh comes with the state.
  for (MeshChange* change : changes_.list) {
    NewMesh m;
    if (!change->restart(sections, mesh(), scene(), path, m)) continue;
    s_.pattern_pairs.clear();  // of the mesh before; the checkpoint's own follow in restore
    replace_mesh(std::move(m.mesh), std::move(m.scene), {});
  }
  RunState st = state_from_sections(sections, mesh(), path, history, b_->space.dofs_per_cover(), b_->space.terms(),
                                    &factor);
  for (const Effect* e : b_->effects) e->restore_sections(sections, mesh(), path, st);  // their own sections
  restore(st, history, path);
  // Unknowns an effect installed at this restart change the system's size: its first
  // step factorises anew.
  if (!factor.empty() && b_->solved_by_effect() && factor_fits_ && !system_.factor_from_source(factor))
    throw InputError(path, "section FACTOR", "not the matrix of a factorisation of this run's size");
}

void TimeStepper::restore(const RunState& st, const std::string& history, const std::string& name) {
  s_ = restarted_state(st, s_, scene().bodies.size(), name);
  b_->restore_contact_history(history, name);
  apply_removed();
  excavate(scene().excavate);
  // Effects: what the checkpoint carries where the scene still has it, the rest installed now
  // (Effect::install); then the same pattern as the run that wrote the
  // checkpoint (its pairs, the effects' groups): the same symbolic analysis, the same round-off.
  factor_fits_ = place_effects(name);
}

void TimeStepper::excavate(const std::vector<int>& bodies) {
  excavate_bodies(bodies, mesh(), stress_terms(), s_);
  apply_removed();
}

void TimeStepper::apply_removed() {
  removed_elem_ = removed_elements(mesh(), s_);
  // What the mesh changes took out (debris: MeshChange::removed) leaves the model like
  // an excavated body.
  for (const MeshChange* change : changes_.list) {
    const std::vector<std::uint8_t>& out = change->removed();
    for (std::size_t e = 0; e < out.size(); ++e) removed_elem_[e] = removed_elem_[e] || out[e];
  }
  b_->set_removed(removed_elem_);
  hold_removed_covers(mesh(), b_->space.dofs_per_cover(), removed_elem_, s_);
}

}  // namespace nmm::solve
