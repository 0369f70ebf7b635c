// The contacts as an effect of the step: see contact_effect.h. The step's contact problem is
// solved by contact_solve.cpp; this file is what the step does around it — detection, the sparse
// pattern's growth, breaking at the peak, step control's penetration, the commit.
#include "solver/contact/contact_effect.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <limits>

#include <nlohmann/json.hpp>

#include "common/memory_marks.h"
#include "solver/contact/contact_readout.h"
#include "solver/contact/contact_tolerances.h"
#include "solver/discretisation/static_support.h"

namespace nmm::solve {

namespace {
// J/m, the energy a closed contact's springs hold: ½ N·closure + ½ |T·s_el| (docs/energy.md).
double springs_energy(const Contact& c) {
  return 0.5 * std::max(0.0, c.normal_force * -c.gap) + 0.5 * std::abs(c.shear_force * c.shear_el);
}

// How many times the pairs the contacts use (this step's and the last accepted step's) the
// sparse pattern may hold before a growth rebuilds it from those alone (ContactEffect::update_pattern).
// Measured on the DDA code's walls (contact_bench --peer, 100 steps, one thread): at 1.1 the
// 30 × 30 wall took 117 ms per static step and 332 dynamic against 132 and 423 with a pattern
// that only grew. 1.0 (rebuilt from the used pairs at every growth) and 1.05 were within a few
// per cent of it either way (1.0: 122 / 336 ms at 30 × 30, 116 dynamic at 20 × 20 against 122,
// with 80–92 analyses per 100 static steps against 54–56), and 1.3 kept most of the growth
// (dynamic 20 × 20: 148 ms against 152 and 122 at 1.1).
constexpr double kPatternSlack = 1.1;

// How many of a step's touching contacts (closed at its start, or within the gap tolerance of
// touching) may lie outside the sparse pattern before it grows, in a run with inertia: at most
// kDeferredTouching, and at most kDeferredShare of the touching contacts (ContactEffect::update_pattern). Each
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

// The old loop vertex that loop vertex v of element e (mesh `now`, a piece of old element
// `parent`) continues, given `was`, the map's vertex_parent: the first vertex of the parent's loop
// at v's point. A crack that ends inside an element (a slit) has the element's loop pass each
// point of it twice, once along each face (A → P → tip, tip → P′ → A′, P′ at P's point): the map
// names P for the new vertex of either face, and P′ has none. Of the old vertices at v's point
// this takes the one whose loop leaves it (else reaches it) the way v's loop does — a face's new
// edges lie along its old ones, so only its own side's agrees. Without it the re-cut dropped the
// closed contact of every P′ the step ended with: its end force missing from the cut step's start
// and its release or reloading unbooked (uniaxial h 0.1 m, dynamic, fast, Prescott: R 995 → 171
// J/m, docs/energy.md "Cracking runs"). Kept for the contacts' bookkeeping alone: the map itself,
// which state_transfer and transfer_history read too, is left as it is (the run's path with it).
std::int32_t old_vertex_on_its_side(const Mesh& old, const Mesh& now, std::int32_t parent, std::int32_t e,
                                    std::int32_t v, std::int32_t was) {
  if (parent < 0) return was;
  const std::int32_t pb = old.element_loop_offset[static_cast<std::size_t>(parent)];
  const std::int32_t pe = old.element_loop_offset[static_cast<std::size_t>(parent) + 1];
  const std::int32_t nb = now.element_loop_offset[static_cast<std::size_t>(e)];
  const std::int32_t ne = now.element_loop_offset[static_cast<std::size_t>(e) + 1];
  const auto xy = [](const Mesh& m, std::int32_t i, int k) { return m.loop_xy[2 * static_cast<std::size_t>(i) + static_cast<std::size_t>(k)]; };
  const auto same_point = [&](std::int32_t w) { return xy(old, w, 0) == xy(now, v, 0) && xy(old, w, 1) == xy(now, v, 1); };
  int at_point = 0;
  for (std::int32_t w = pb; w < pe; ++w) at_point += same_point(w) ? 1 : 0;
  if (at_point < 2) return was;
  // Directions from a vertex to the next (+1) or the previous (−1) of its loop.
  const auto step = [&](const Mesh& m, std::int32_t b, std::int32_t end, std::int32_t i, int dir) {
    const std::int32_t j = dir > 0 ? (i + 1 < end ? i + 1 : b) : (i > b ? i - 1 : end - 1);
    return std::array<double, 2>{xy(m, j, 0) - xy(m, i, 0), xy(m, j, 1) - xy(m, i, 1)};
  };
  const auto along = [](const std::array<double, 2>& a, const std::array<double, 2>& b) {
    const double cross = a[0] * b[1] - a[1] * b[0], dot = a[0] * b[0] + a[1] * b[1];
    return dot > 0 && std::abs(cross) <= 1e-9 * std::hypot(a[0], a[1]) * std::hypot(b[0], b[1]);
  };
  for (const int dir : {1, -1}) {
    const std::array<double, 2> mine = step(now, nb, ne, v, dir);
    for (std::int32_t w = pb; w < pe; ++w)
      if (same_point(w) && along(mine, step(old, pb, pe, w, dir))) return w;
  }
  return was;
}

// The loop vertex of the mesh now that continues old loop vertex w where the map has none: the
// map ties a piece's vertex to an old one at exactly its point, and a crack whose tip lies on an
// old vertex (a crack grown from an earlier one's end) meets it at the exactly cut point rounded
// to double, an ulp or two off the old vertex's own rounding, so the cut's vertices there have
// no parent. Of the vertices of w's element's pieces (`piece` .. `end`) that the map leaves
// without one, those within round-off of w's point (1e-12 of the coordinates' size) are
// candidates; the one whose loop leaves it (else reaches it) along w's own edge is taken, as
// old_vertex_on_its_side takes a face's, else the nearest. -1: none. Without it the re-cut
// dropped such a vertex's closed contact, its end force missing from the cut step's start
// (uniaxial h 0.1 m, static, fast, Haswell: step 89, one of 1,018).
std::int32_t vertex_off_the_map(const Mesh& old, const Mesh& now, const std::vector<std::int32_t>& vertex_parent,
                                const std::int32_t* piece, const std::int32_t* end, std::int32_t w) {
  const auto xy = [](const Mesh& m, std::int32_t i, int k) { return m.loop_xy[2 * static_cast<std::size_t>(i) + static_cast<std::size_t>(k)]; };
  const auto loop_of = [](const Mesh& m, std::int32_t v) {
    const auto& off = m.element_loop_offset;
    const auto e = static_cast<std::size_t>(std::upper_bound(off.begin(), off.end(), v) - off.begin()) - 1;
    return std::array<std::int32_t, 2>{off[e], off[e + 1]};
  };
  const auto step = [&](const Mesh& m, std::int32_t i, int dir) {
    const auto [b, e] = loop_of(m, i);
    const std::int32_t j = dir > 0 ? (i + 1 < e ? i + 1 : b) : (i > b ? i - 1 : e - 1);
    return std::array<double, 2>{xy(m, j, 0) - xy(m, i, 0), xy(m, j, 1) - xy(m, i, 1)};
  };
  const auto along = [](const std::array<double, 2>& a, const std::array<double, 2>& b) {
    const double cross = a[0] * b[1] - a[1] * b[0], dot = a[0] * b[0] + a[1] * b[1];
    return dot > 0 && std::abs(cross) <= 1e-9 * std::hypot(a[0], a[1]) * std::hypot(b[0], b[1]);
  };
  const double wx = xy(old, w, 0), wy = xy(old, w, 1);
  const double tol = 1e-12 * (std::abs(wx) + std::abs(wy) + old.mesh_size);
  std::vector<std::int32_t> near;
  std::int32_t nearest = -1;
  double best = tol;
  for (; piece != end; ++piece) {
    const std::int32_t b = now.element_loop_offset[static_cast<std::size_t>(*piece)];
    const std::int32_t e = now.element_loop_offset[static_cast<std::size_t>(*piece) + 1];
    for (std::int32_t v = b; v < e; ++v) {
      if (static_cast<std::size_t>(v) < vertex_parent.size() && vertex_parent[static_cast<std::size_t>(v)] >= 0) continue;
      const double dist = std::hypot(xy(now, v, 0) - wx, xy(now, v, 1) - wy);
      if (dist > tol) continue;
      near.push_back(v);
      if (dist <= best) best = dist, nearest = v;
    }
  }
  for (const int dir : {1, -1})
    for (const std::int32_t v : near)
      if (along(step(now, v, dir), step(old, w, dir))) return v;
  return nearest;
}
}  // namespace

ContactEffect::ContactEffect(const Model& model, const CoverSpace& space)
    : model_(model), space_(space), contacts_(model), problem_(contacts_, space) {
  problem_.set_elastic_predictor(!model.step_inertia());
}

void ContactEffect::number(const RunState& s, int /*first_unknown*/, std::size_t first_group) {
  first_group_ = static_cast<int>(first_group);
  // A restarted run: the groups of the checkpoint's pattern, as the run that wrote it had them.
  if (!s.pattern_pairs.empty()) problem_.assign_groups(s.pattern_pairs, first_group_);
}

void ContactEffect::add_groups(const RunState& s, std::vector<int>& offsets, std::vector<int>& dofs) const {
  // One coupling group per pair of elements the pattern holds: their unknowns together.
  const int m = space_.element_dofs();
  for (const auto& [a, b] : s.pattern_pairs) {
    dofs.insert(dofs.end(), space_.element_unknowns(a), space_.element_unknowns(a) + m);
    dofs.insert(dofs.end(), space_.element_unknowns(b), space_.element_unknowns(b) + m);
    offsets.push_back(static_cast<int>(dofs.size()));
  }
}

Outcome ContactEffect::begin_step(EffectStep& step) {
  RunState& s = step.s;
  memory_mark("step begun");
  // Shi's search distance (plus a joint's dilation, a softening crack's reach) bounds how deep a
  // closed contact is followed; open ones are looked for only the stepper's reach far, where it
  // checks the step's motion against it (time_stepper.cpp). Not where an open contact carries
  // history (contact_set.h open_history: a joint's memory, a crack's damage, a broken bond)
  // while detection keeps it: leaving the set sooner would lose it sooner.
  const double extra = contacts_.max_dilation() + contacts_.cohesive_reach();
  const bool narrow = step.reach > 0 && step.reach < step.search_distance && !contacts_.open_history();
  contacts_.begin_step(s.loop_xy, step.search_distance + extra,
                       kContactTolerances.new_depth * model_.mesh().mesh_size, model_.w0(),
                       narrow ? step.reach + extra : -1.0);
  if (narrow) step.checked_reach = step.reach;
  memory_mark("contacts detected");
  problem_.build(s.loop_xy, step.context.config, model_.w0());
  memory_mark("contact rows");
  step.pattern_changed = update_pattern(s);
  step.timings.contact_detection = contacts_.detection_stats().seconds;
  return {};
}

void ContactEffect::add_at_rest(EffectStep& rest) {
  // The contacts' forces at d = 0: their start forces, at their strengths of the step's start.
  problem_.start_strengths();
  problem_.forces_at(Eigen::VectorXd::Zero(rest.rhs.size()), rest.rhs);
}

Outcome ContactEffect::solve(EffectStep& step, bool again, StepSolution& x) {
  // The step's convex contact problem (contact_solve.cpp): Newton iterations on a factorisation
  // of the saved matrix without contacts, reused from step to step.
  step.system.save();
  rhs_base_ = step.rhs;
  const ContactSolveStats before = stats_;
  const SolverDef& sv = model_.scene().solver;
  const double tau = sv.contact_tolerance;
  // A dynamic run hands the blocks' share of the residual on to the next step (block_momentum.h).
  const bool hand_on = sv.dynamic && sv.dynamic_factor > 0;
  const auto solve = [&](ContactStart start) {
    return solve_contact_step(step.system, problem_, rhs_base_, tau,
                              contacts_.softening() ? displacement_tolerance(tau, model_.w0()) : 0.0, x.d, stats_,
                              hand_on ? &x.residual : nullptr, start);
  };
  // A re-solve on a re-cut mesh starts from the solution on the mesh before (x.guess), which
  // differs from it by the new cracks' opening only.
  const bool guess = !again && x.guess && x.d.size() == rhs_base_.size();
  x.guess = false;
  Outcome outcome = solve(again ? ContactStart::warm : guess ? ContactStart::guess : ContactStart::zero);
  // Bonds and cohesion break only at a solution of the step, and the step is solved again with
  // them broken until no unbroken contact is beyond its peak (contact_problem.h break_at_peak). Each
  // round breaks at least one contact, so this ends.
  for (bool resolved = false; outcome.ok();) {
    if (!problem_.break_at_peak().resolve) break;
    if (!resolved) ++stats_.steps_resolved_for_breaks;
    resolved = true;
    ++stats_.break_resolves;
    outcome = solve(ContactStart::warm);  // from the solution before the breaks
  }
  // Softening crack faces (cohesive_law.h): where the static path snaps back — the crack would
  // release more energy than it can take — the step's Newton iterations find no balance and
  // the step is cut; with more inertia the run follows the snap dynamically. Counted
  // (summary.json fracture.snap_back_cuts) where a face was softening at the attempt's end.
  if (outcome.code == StopCode::contact_not_converged && problem_.softening_faces() > 0) ++stats_.cohesive_unsettled;
  if (outcome.ok()) problem_.settle_states();
  x.iterated = x.iterated || stats_.newton > before.newton;
  StepTimings& t = step.timings;
  t.factorisations += stats_.factorisations - before.factorisations;
  t.factorisation += stats_.factorisation_seconds - before.factorisation_seconds;
  t.solves_count += stats_.cg_iterations - before.cg_iterations + (stats_.factorisations - before.factorisations);
  t.solves += stats_.cg_seconds - before.cg_seconds + stats_.line_search_seconds - before.line_search_seconds;
  step.s.iterations += static_cast<std::uint64_t>(stats_.newton - before.newton);
  step.s.friction_unsettled += static_cast<std::uint64_t>(stats_.unsettled - before.unsettled);
  return outcome;
}

StepPenetration ContactEffect::penetration(EffectStep& step) const { return contacts_.deepening(step.allowance); }

void ContactEffect::rejected(const EffectStep& step, const Eigen::VectorXd& covers_d) const {
  trace_rejected_step(step.s, covers_d);
}

void ContactEffect::commit(EffectStep& step, const Eigen::VectorXd& d) {
  // The contacts the last accepted step ended closed with and this one started without (its
  // vertex found open, or not at all, and no mirror of it closed): their end forces were gone
  // at its start, and the step released ½ (0 − c_end)·d of them (contact_effect.h) — also where
  // the step re-cut the mesh (ended_ carried onto it: end_unknowns_ −2).
  released_work_ = 0;
  released_.clear();
  // (vertex, edge) pairs sorted for binary searches: detection lists its contacts, and so the
  // ended ones, in that order already, which the check finds in one pass instead of a sort.
  const auto sort_pairs = [](std::vector<std::pair<std::int32_t, std::int32_t>>& p) {
    if (!std::is_sorted(p.begin(), p.end())) std::sort(p.begin(), p.end());
  };
  std::vector<std::pair<std::int32_t, std::int32_t>>& pairs = commit_pairs_;
  if ((end_unknowns_ == d.size() || end_unknowns_ == -2) && !ended_.empty()) {
    // The vertices closed at this step's start (with their mirrors), marked by vertex.
    std::vector<std::uint8_t>& closed = commit_closed_;
    closed.assign(model_.mesh().loop_vertex_count(), 0);
    pairs.clear();  // (vertex, edge) of this step's contacts found open that their law holds
    const std::vector<Contact>& found = contacts_.contacts();
    for (std::size_t k = 0; k < found.size(); ++k) {
      const Contact& c = found[k];
      if (c.start_state != ContactState::open) {
        for (const std::int32_t v : {c.at.vertex, c.mirror})
          if (v >= 0 && static_cast<std::size_t>(v) < closed.size()) closed[static_cast<std::size_t>(v)] = 1;
      } else if (held_open(k)) {
        pairs.emplace_back(c.at.vertex, c.at.edge);
      }
    }
    sort_pairs(pairs);
    const auto has = [&](std::int32_t v) { return v >= 0 && static_cast<std::size_t>(v) < closed.size() && closed[static_cast<std::size_t>(v)] != 0; };
    const int nd = space_.element_dofs();
    commit_released_.assign(ended_.size(), 0);
    for (std::size_t i = 0; i < ended_.size(); ++i) {
      const EndedContact& e = ended_[i];
      // Still closed, or found open on the same edge where its law still holds it (held_open: a
      // joint that dilated apart, which the step solves on from the dilation it carries), is not
      // released.
      if (has(e.vertex) || has(e.mirror) || std::binary_search(pairs.begin(), pairs.end(), std::make_pair(e.vertex, e.edge)))
        continue;
      released_work_ += released_energy(e, d, nd);
      released_.push_back(e.vertex);
      commit_released_[i] = 1;
    }
    std::sort(released_.begin(), released_.end());
  } else {
    commit_released_.assign(ended_.size(), 0);
  }
  // The contacts this step found sunk with no force carried (open at its start, no force at the
  // last step's end on the same vertex and edge: a vertex that chattered — released in a step,
  // found again at depth in this one — or one a re-cut's detection finds deep): the step starts
  // with their springs at N0 = N(gap0) > 0, ½ N0·closure0 that entered S from no work, and out of
  // balance by their force c0 = N0·cn, whose motion takes ½ c0·d = ½ N0·Δg of it (as a released
  // contact's, above, with the sign turned). Both go to `damped`: the step's start as the
  // detection made it, not its physics. A contact the step opens (Δg > closure0: the notched
  // beam's halves, found sunk where they struck, bounce apart) ends with no force: the step,
  // which sees the forces at its end, neither spent nor kept the start energy, which S never
  // held, and ½ N0·Δg would count the start force over a motion it did not push through (the
  // beam at h 0.02 m, dynamic, fast: 81 of the 123 contacts found sunk in its step 73 opened;
  // R −2.07 J/m, 2.2 % of the work, booked so).
  static const bool trace = std::getenv("NMM_TRACE_ENERGY") != nullptr;
  if (trace) trace_sunk_.assign(problem_.contacts().size(), 0.0);
  {
    // The ended contacts by (vertex, edge); had(): those this step did not release — a released
    // one found open on its edge starts the step with no force, as any other found open (the
    // rules below).
    ended_pairs_.reset(model_.mesh().loop_vertex_count());
    if (end_unknowns_ == d.size() || end_unknowns_ == -2)
      for (std::size_t i = 0; i < ended_.size(); ++i) ended_pairs_.add(ended_[i].vertex, ended_[i].edge, i);
    // The shear force each contact starts the step with in its balance (energy_step's T0): the
    // history's where it starts closed; where it starts open, the end force of a contact the
    // last step ended closed on the same vertex and edge (a Barton–Bandis joint that dilated
    // apart between the steps: the step's start is in balance with that force, which the
    // release above leaves to it), else none (of two such ended contacts, the lower force).
    const std::vector<Contact>& cs = problem_.contacts();
    start_shear_.assign(cs.size(), 0.0);
    for (std::size_t k = 0; k < cs.size(); ++k) {
      const Contact& c = cs[k];
      if (c.start_state != ContactState::open) {
        start_shear_[k] = c.start_shear_force;
        continue;
      }
      bool found = false;
      ended_pairs_.for_each(c.at.vertex, c.at.edge, [&](std::size_t i) {
        if (!found || ended_[i].shear_force < start_shear_[k]) start_shear_[k] = ended_[i].shear_force;
        found = true;
      });
    }
    for (std::size_t k = 0; k < cs.size(); ++k) {
      const Contact& c = cs[k];
      if (c.start_state != ContactState::open || had(c)) continue;
      const double n0 = problem_.normal_force_at_rest(k);
      const double gap0 = problem_.work(k).gap0;  // m
      if (n0 <= 0 && gap0 > 0 && c.state != ContactState::open) {
        // Closes from open within the step (contact_effect.h): its end force N1 acts over the
        // step's whole motion, −½ c1·d = ½ N1·(gap0 + closure1), of which its spring keeps
        // ½ N1·closure1; ½ N1·gap0 is what the implicit step took out of the motion before the
        // faces touched (an impact the scheme damps).
        released_work_ += 0.5 * std::max(0.0, c.normal_force) * gap0;
        continue;
      }
      if (n0 <= 0) continue;
      const double dg = gap_change(k, d);  // m, the step's change of its gap
      // Its start force's work stops where the gap closes: ½ N0·min(Δg, closure0) − ½ N0·closure0,
      // = −½ N0·max(closure1, 0): 0 for a contact the step opens.
      const double closure0 = -problem_.work(k).gap0;
      const double sunk = 0.5 * n0 * std::min(dg, closure0) - 0.5 * n0 * closure0;
      released_work_ += sunk;
      if (trace) trace_sunk_[k] = sunk;
    }
    if (end_unknowns_ == d.size() || end_unknowns_ == -2) released_work_ += moved_on_work(d) + open_on_edge_work(d);
    released_work_ += reloaded_work(d);
  }
  for (std::size_t k = 0; k < problem_.contacts().size(); ++k) {
    const double opened = opened_work(k, d);
    released_work_ += opened;
    if (trace) trace_sunk_[k] += opened;
  }
  if (trace) trace_d_ = d;
  // Kept for a re-cut that throws this attempt away (continue_from).
  start_ended_.swap(ended_);
  start_end_unknowns_ = end_unknowns_;
  // This step's closed contacts' end forces, Σ N·cn − T·cs on its rows, for the next step,
  // written over the list two steps old (its entries' force arrays reused, not allocated anew
  // for each of the step's hundreds of closed contacts).
  std::size_t kept = 0;
  end_unknowns_ = d.size();
  const Mesh& mesh = model_.mesh();
  std::vector<std::size_t>& ended_index = commit_ended_index_;
  ended_index.clear();
  for (std::size_t k = 0; k < problem_.contacts().size(); ++k) {
    const Contact& c = problem_.contacts()[k];
    if (c.state == ContactState::open || (c.normal_force == 0 && c.shear_force == 0)) continue;
    ended_index.push_back(k);
    const ContactProblem::Row r = problem_.row(k);
    // The edge's point at ω in the reference coordinates (the mesh's, which a re-cut keeps).
    const auto q2 = static_cast<std::size_t>(c.at.edge);
    const auto q3 = static_cast<std::size_t>(contacts_.topology().next[q2]);
    const double bx = mesh.loop_xy[2 * q2] + c.at.omega * (mesh.loop_xy[2 * q3] - mesh.loop_xy[2 * q2]);
    const double by = mesh.loop_xy[2 * q2 + 1] + c.at.omega * (mesh.loop_xy[2 * q3 + 1] - mesh.loop_xy[2 * q2 + 1]);
    if (kept == ended_.size()) ended_.emplace_back();
    EndedContact& e = ended_[kept++];
    e.vertex = c.at.vertex;
    e.mirror = c.mirror;
    e.edge = c.at.edge;
    e.elem_a = c.at.elem_a;
    e.elem_b = c.at.elem_b;
    e.bx = bx;
    e.by = by;
    e.force.resize(static_cast<std::size_t>(r.size));
    e.shear_force = c.shear_force;
    e.stored = 0.0;
    for (int i = 0; i < r.size; ++i) e.force[static_cast<std::size_t>(i)] = c.normal_force * r.cn(i) - c.shear_force * r.cs(i);
  }
  ended_.resize(kept);
  const ContactSet::Totals totals = contacts_.totals();
  contacts_.end_step(problem_);
  for (std::size_t i = 0; i < ended_index.size(); ++i) {
    const Contact& c = contacts_.contacts()[ended_index[i]];
    ended_[i].stored = springs_energy(c);
  }
  // A face that softened through a quarter of w_c in one step: the static path snapped back
  // (summary.json fracture.snap_back_steps).
  if (problem_.max_damage_jump() >= 0.25) ++stats_.snap_back_steps;
  step.s.max_penetration = std::max(step.s.max_penetration, totals.max_penetration);
  step.s.max_capped = std::max(step.s.max_capped, totals.capped);
}

double ContactEffect::gap_change(std::size_t k, const Eigen::VectorXd& d) const {
  const ContactProblem::Row r = problem_.row(k);
  double dg = 0;
  for (int i = 0; i < r.size; ++i)
    if (r.dofs[i] >= 0 && r.dofs[i] < d.size()) dg += r.cn(i) * d[r.dofs[i]];
  return dg;
}

std::pair<double, double> ContactEffect::row_motion(std::size_t k, const Eigen::VectorXd& d) const {
  const ContactProblem::Row r = problem_.row(k);
  double dg = 0, ds = 0;
  for (int i = 0; i < r.size; ++i)
    if (r.dofs[i] >= 0 && r.dofs[i] < d.size()) {
      dg += r.cn(i) * d[r.dofs[i]];
      ds += r.cs(i) * d[r.dofs[i]];
    }
  return {dg, ds};
}

double ContactEffect::opened_work(std::size_t k, const Eigen::VectorXd& d) const {
  // A contact that starts a dynamic step closed under the normal force N0 it carries (the last
  // accepted step's end force, in the step's start balance M·a1,prev) and ends it open: the
  // time scheme's identity takes its start force linear over the step's whole motion,
  // ½ N0·Δg (energy.cpp (1)), but the force pushed the faces apart only until the gap opened,
  // ½ N0·closure0 — what its springs held, which S gives up. The rest, ½ N0·(Δg − closure0),
  // the contact never did: `damped` gives it back. (Its shear start force stays on the
  // trapezoid, which friction books: ½ T0·s, book_contact.) Uniaxial compression h 0.0625 m,
  // dynamic, fast: 58 contacts that slid into the first crack's step and open in it left
  // −515 J/m in R without it (docs/energy.md `damped`). Not in static steps, whose balance
  // is their own (not measured there).
  if (!model_.scene().solver.dynamic) return 0;
  const Contact& c = problem_.contacts()[k];
  if (c.start_state == ContactState::open || c.state != ContactState::open || c.cohesive.on) return 0;
  // N: the carried force, or the one its springs were set afresh at (reloaded_work)
  const double n0 = k < reloaded_n0_.size() && !std::isnan(reloaded_n0_[k]) ? reloaded_n0_[k] : problem_.work(k).start_normal_force;
  const double closure0 = std::max(0.0, -problem_.work(k).gap0);  // m
  if (!(n0 > 0)) return 0;
  return -0.5 * n0 * std::max(0.0, gap_change(k, d) - closure0);
}

void ContactEffect::continue_from(const ContactEffect& before, std::vector<ContactHistory> history,
                                  const MeshPieces* from) {
  contacts_.restore(std::move(history), {});
  contacts_.continue_from(before.contacts_);
  stats_ = before.stats_;
  // A re-cut follows an attempt that `before` committed and the step throws away: the contacts
  // the last accepted step ended with are what `before` held before that commit.
  if (from && before.start_end_unknowns_ != -1) {
    ended_ = carry_ended(before.start_ended_, *from);
    end_unknowns_ = -2;
  }
}

std::vector<ContactEffect::EndedShear> ContactEffect::ended_shear(bool started) const {
  std::vector<EndedShear> out;
  for (const EndedContact& e : started ? start_ended_ : ended_) out.push_back({e.bx, e.by, e.shear_force, e.stored});
  return out;
}

bool ContactEffect::had(const Contact& c) const {
  bool found = false;
  ended_pairs_.for_each(c.at.vertex, c.at.edge, [&](std::size_t i) { found = found || commit_released_[i] == 0; });
  return found;
}

double ContactEffect::moved_on_work(const Eigen::VectorXd& d) {
  // The moved-on rule (contact_effect.h). Contact history is kept per vertex and block
  // (contact_set.cpp begin_step), so a vertex that ended the last step closed on edge e1 of a
  // block and starts this one on another edge e2 of it (past a corner, or onto the next element's
  // edge of a straight face) starts closed with its state and shear, while its normal spring is
  // loaded afresh from its gap to e2: N0 = N(gap0) along e2's normal, on e2's row. The old spring
  // is gone with its pair. The step started in balance with the old end force c_prev and solves
  // from the new start force c0 = N0·cn − T0·cs, a jump c0 − c_prev the detection applied at once,
  // and the springs' energy went from S_prev (½ N·closure + ½ |T·s_el| on e1) to S0 (the same on
  // e2) with no work. Booked as the found-sunk and released rules book theirs (a new spring
  // loaded, an old one released): ½ (c0 − c_prev)·d + S_prev − S0 in `damped`, the step's motion
  // against the jump and the springs' change the detection made. Where the force goes on across
  // the corner (a straight face: the same point, normal and closure) both terms vanish; a corner
  // of angle θ turns c0 by θ and sets closure0 by the vertex's place past the corner.
  // Matched by vertex, mirrors included (the other face's vertex at the same point hands its
  // history on: contact_set.cpp), summed per vertex: a vertex may end on two edges at a corner.
  double booked = 0;
  const std::vector<Contact>& cs = problem_.contacts();
  PairIndex& now = step_pairs_;  // this step's contacts by (vertex, edge)
  now.reset(model_.mesh().loop_vertex_count());
  for (std::size_t k = 0; k < cs.size(); ++k) now.add(cs[k].at.vertex, cs[k].at.edge, k);
  std::vector<std::int32_t>& group = moved_group_;  // by loop vertex: the group of its ended contacts, −1 none
  group.assign(model_.mesh().loop_vertex_count(), -1);
  const auto group_of = [&](std::int32_t v) { return v >= 0 && static_cast<std::size_t>(v) < group.size() ? group[static_cast<std::size_t>(v)] : -1; };
  std::vector<double>& old_part = moved_old_;  // J/m per group: Σ ½ c_prev·d − S_prev
  std::vector<double>& new_part = moved_new_;  // J/m per group: Σ ½ c0·d − S0 (NaN: none)
  old_part.clear();
  new_part.clear();
  const int nd = space_.element_dofs();
  for (const EndedContact& e : ended_) {
    // Released (commit: closed nowhere now) or on the same pair now: the other rules'.
    if (std::binary_search(released_.begin(), released_.end(), e.vertex) || now.contains(e.vertex, e.edge)) continue;
    std::int32_t g = group_of(e.vertex);
    if (g < 0) g = group_of(e.mirror);
    if (g < 0) {
      g = static_cast<std::int32_t>(old_part.size());
      old_part.push_back(0.0);
      new_part.push_back(std::numeric_limits<double>::quiet_NaN());
    }
    for (const std::int32_t v : {e.vertex, e.mirror})
      if (v >= 0 && static_cast<std::size_t>(v) < group.size()) group[static_cast<std::size_t>(v)] = g;
    old_part[static_cast<std::size_t>(g)] += 0.5 * ended_work(e, d, nd) - e.stored;
  }
  if (old_part.empty()) return 0.0;
  static const bool trace = std::getenv("NMM_TRACE_ENERGY") != nullptr;
  std::vector<std::size_t> first(old_part.size(), cs.size());  // the group's first new contact (trace)
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const Contact& c = cs[k];
    if (c.start_state == ContactState::open || had(c)) continue;
    std::int32_t g = group_of(c.at.vertex);
    if (g < 0) g = group_of(c.mirror);
    if (g < 0) continue;
    const auto [dg, ds] = row_motion(k, d);  // m, the step's change of its gap and shear
    const ContactWork& w = problem_.work(k);
    const double n0 = problem_.normal_force_at_rest(k);  // N, its spring at the gap it starts with
    const double t0 = k < start_shear_.size() ? start_shear_[k] : c.start_shear_force;  // N, T0
    const double s0 = 0.5 * std::max(0.0, n0 * -w.gap0) + 0.5 * std::abs(t0 * w.shear0);  // J/m
    double& part = new_part[static_cast<std::size_t>(g)];
    part = (std::isnan(part) ? 0.0 : part) + 0.5 * (n0 * dg - t0 * ds) - s0;
    if (first[static_cast<std::size_t>(g)] == cs.size()) first[static_cast<std::size_t>(g)] = k;
  }
  for (std::size_t g = 0; g < old_part.size(); ++g) {
    if (std::isnan(new_part[g])) continue;  // no contact of its vertex starts on another edge
    const double b = new_part[g] - old_part[g];
    booked += b;
    if (trace && first[g] < trace_sunk_.size()) trace_sunk_[first[g]] += b;
  }
  return booked;
}

double ContactEffect::reloaded_work(const Eigen::VectorXd& d) {
  // The reloaded rule (contact_effect.h). A contact that starts the step closed on the vertex and
  // edge it ended the last accepted step on carries its end force c_prev into the step's start
  // balance (the scheme's M·a1,prev; across a re-cut, B of crack_release.h, which holds the end
  // forces carry_ended put on the cut mesh): the trapezoid of the step's work takes c_prev at its
  // start. But the step solves from its springs set afresh by the detection, c0 = N0·cn − T0·cs,
  // N0 = N(gap0) and T0 = T(s_el,0) on its tributary length now, whose energy is S0 = ½ N0·
  // closure0 + ½ |T0·s_el,0|: a jump c0 − c_prev the detection applied at once, and S_prev → S0
  // with no work. As the moved-on rule books its jump, ½ (c0 − c_prev)·d + S_prev − S0 goes to
  // `damped`. Where a re-cut ends a crack on the contact's face (the crack's mouth under a
  // platen) its tributary length falls at the same closure and elastic shear, and with it its
  // force and energy: uniaxial compression h 0.1 m, dynamic, slow (Haswell), the mouth's two
  // vertices carried 1.02 and 0.79 MN/m into step 169 and 0.63 MN/m into step 174, whose
  // springs started them at 0.37, 0.32 and 0.44 of that: 136, 100 and 106 J/m left in R without
  // it (docs/energy.md). Between two steps on one mesh c0 and c_prev differ by the geometry's update
  // and the length's drift as the faces slide.
  reloaded_n0_.assign(problem_.contacts().size(), std::numeric_limits<double>::quiet_NaN());
  if (end_unknowns_ != d.size() && end_unknowns_ != -2) return 0.0;  // no ended contacts on this mesh
  static const bool trace = std::getenv("NMM_TRACE_ENERGY") != nullptr;
  const int nd = space_.element_dofs();
  const std::vector<Contact>& cs = problem_.contacts();
  double booked = 0;
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const Contact& c = cs[k];
    if (c.start_state == ContactState::open || problem_.work(k).cohesive || !had(c)) continue;
    // Linear springs only: a Bandis–Barton or hyperbolic joint starts from the memory it carries
    // (closure, dilation, travel), its law's own path, not springs set afresh (with it the
    // Barton–Bandis shear box of tests/test_barton_bandis.cpp booked −4.5 kJ/m in `damped`, R 9.8 %).
    const ContactLaw& law = contacts_.laws()[static_cast<std::size_t>(c.law)];
    if (law.normal != NormalModel::constant && law.normal != NormalModel::penalty) continue;
    if (law.shear != ShearModel::constant && law.shear != ShearModel::penalty) continue;
    std::size_t first = ended_.size();  // the first ended contact on its (vertex, edge)
    ended_pairs_.for_each(c.at.vertex, c.at.edge, [&](std::size_t i) { first = std::min(first, i); });
    const EndedContact& e = ended_[first];
    const auto [dg, ds] = row_motion(k, d);  // m, the step's change of its gap and shear
    const ContactWork& w = problem_.work(k);
    const double n0 = problem_.normal_force_at_rest(k), t0 = problem_.shear_force_at_rest(k);  // N
    const double s0 = 0.5 * std::max(0.0, n0 * -w.gap0) + 0.5 * std::abs(t0 * w.shear0);     // J/m
    const double b = 0.5 * (n0 * dg - t0 * ds) - s0 - (0.5 * ended_work(e, d, nd) - e.stored);
    booked += b;
    // The step's forces start from c0 now: friction's trapezoid takes T0 from it (book_contact),
    // and opened_work N0 (both took the carried force, and booked the jump twice: uniaxial h
    // 0.125 m, static, fast, step 77, three contacts cut to 1 mm of face that slid into the step
    // and open in it, 54, 64 and 17 J/m too much).
    start_shear_[k] = t0;
    reloaded_n0_[k] = n0;
    if (trace && k < trace_sunk_.size()) trace_sunk_[k] += b;
  }
  return booked;
}

double ContactEffect::open_on_edge_work(const Eigen::VectorXd& d) {
  // A contact the last accepted step ended closed with (c_end, its springs S_end) that this step
  // finds open on the very edge, where its law gives it no force at rest (not held_open), while
  // its vertex or its mirror starts closed elsewhere: commit does not release it (a vertex closed
  // somewhere may have handed its force on), and moved_on_work leaves its pair alone (found on it
  // again). Its spring is gone all the same: the step starts with no force there, c0 = 0 and
  // S0 = 0, so the moved-on rule's ½ (c0 − c_end)·d + S_end − S0 is the release's
  // ½ (0 − c_end)·d + S_end (released_energy). Whatever its vertex's other contacts start with is
  // theirs (the trapezoid where their pair goes on, moved_on_work where it moved on). Biaxial
  // compression h 0.1 m, dynamic, slow (Haswell), the step after the first crack: vertex 407, at
  // a junction of three blocks, ended closed on two edges of two blocks under 3.6 MN/m on one of
  // them; the step finds it 132 µm open on that edge while the other block's vertex at its point
  // starts closed: 2727 J/m (½ (0 − c_end)·d 2165, S_end 562), 2793 J/m of the step's residual.
  const std::vector<Contact>& cs = contacts_.contacts();
  std::vector<std::pair<std::pair<std::int32_t, std::int32_t>, std::size_t>>& open = open_pairs_;  // ((vertex, edge), contact)
  open.clear();
  for (std::size_t k = 0; k < cs.size(); ++k)
    if (cs[k].start_state == ContactState::open && !held_open(k)) open.push_back({{cs[k].at.vertex, cs[k].at.edge}, k});
  if (open.empty()) return 0.0;
  if (!std::is_sorted(open.begin(), open.end())) std::sort(open.begin(), open.end());
  double booked = 0;
  const int nd = space_.element_dofs();
  for (std::size_t i = 0; i < ended_.size(); ++i) {
    if (i < commit_released_.size() && commit_released_[i] != 0) continue;  // released: commit's
    const EndedContact& e = ended_[i];
    const auto at = std::lower_bound(open.begin(), open.end(), std::make_pair(std::make_pair(e.vertex, e.edge), std::size_t{0}));
    if (at == open.end() || at->first != std::make_pair(e.vertex, e.edge)) continue;
    const double b = released_energy(e, d, nd);
    booked += b;
    if (at->second < trace_sunk_.size()) trace_sunk_[at->second] += b;
  }
  return booked;
}

bool ContactEffect::held_open(std::size_t k) const {
  // A contact found open that its law still holds at the step's start: a Barton–Bandis joint
  // whose faces dilated apart (its gap less the dilation it carries is closed: a force at rest),
  // or a softening crack face within its cohesive opening (a traction at rest). One found open on the edge it ended
  // closed on with neither lost its end force at the step's start as a vertex found closed
  // nowhere did (its start has no force there): in biaxial compression h 0.1 m, dynamic, slow
  // (Haswell), the step after the first crack finds vertex 407 132 µm open on the edge it ended
  // closed on under 3.6 MN/m, and ½ (0 − c_end)·d with its springs' 562 J/m, 2727 J/m, was left
  // in R (3.0 % of the work; docs/energy.md) — which this does not release either: the other
  // block's vertex at its point starts closed elsewhere (open_on_edge_work books it).
  // A Barton–Bandis joint is its law's own whatever its force at rest: the step solves on from
  // the dilation and travel it carries (released, the shear box of tests/test_barton_bandis.cpp
  // books 3.7 kJ/m more in `damped`, R −6.7 % of the support's work).
  const Contact& c = contacts_.contacts()[k];
  if (contacts_.laws()[static_cast<std::size_t>(c.law)].shear == ShearModel::barton_bandis) return true;
  return problem_.law_force_at_rest(k) != 0;
}

double ContactEffect::released_energy(const EndedContact& e, const Eigen::VectorXd& d, int nd) const {
  // J/m, what `damped` books for a contact the last accepted step ended closed with and this
  // step started without (commit): the motion's work against the end force the step's start
  // lost, ½ (0 − c_end)·d, and the energy its springs held at that end, ½ N·closure + ½ |T·s_el|
  // (e.stored), which leaves S at the step's start with no work — the step's start has no
  // spring there, so its balance never sees it (the converse of a contact found sunk, whose
  // springs' start energy enters S from no work: below). Without it R keeps e.stored
  // (tests/test_energy.cpp `AContactReleasedBetweenStepsBooksTheEnergyItsSpringsHeld`).
  return -0.5 * ended_work(e, d, nd) + e.stored;
}

double ContactEffect::ended_work(const EndedContact& e, const Eigen::VectorXd& d, int nd) const {
  // J/m: c_end·d, each side's values on its element's local unknowns.
  double w = 0;
  const int* ga = space_.element_unknowns(static_cast<std::size_t>(e.elem_a));
  const int* gb = space_.element_unknowns(static_cast<std::size_t>(e.elem_b));
  for (int i = 0; i < nd; ++i)
    if (ga[i] >= 0 && ga[i] < d.size()) w += e.force[static_cast<std::size_t>(i)] * d[ga[i]];
  for (int i = 0; i < nd; ++i)
    if (gb[i] >= 0 && gb[i] < d.size()) w += e.force[static_cast<std::size_t>(nd + i)] * d[gb[i]];
  return w;
}

void ContactEffect::add_ended_forces(Eigen::VectorXd& f) const {
  if (end_unknowns_ != -2 && end_unknowns_ != f.size()) return;
  const int nd = space_.element_dofs();
  for (const EndedContact& e : ended_) {
    const int* ga = space_.element_unknowns(static_cast<std::size_t>(e.elem_a));
    const int* gb = space_.element_unknowns(static_cast<std::size_t>(e.elem_b));
    for (int i = 0; i < nd; ++i) {
      if (ga[i] >= 0 && ga[i] < f.size()) f[ga[i]] += e.force[static_cast<std::size_t>(i)];
      if (gb[i] >= 0 && gb[i] < f.size()) f[gb[i]] += e.force[static_cast<std::size_t>(nd + i)];
    }
  }
}

Eigen::VectorXd ContactEffect::started_end_forces(Eigen::Index n, bool released) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  const int nd = space_.element_dofs();
  for (const EndedContact& e : start_ended_) {
    if (std::binary_search(released_.begin(), released_.end(), e.vertex) != released) continue;
    const int* ga = space_.element_unknowns(static_cast<std::size_t>(e.elem_a));
    const int* gb = space_.element_unknowns(static_cast<std::size_t>(e.elem_b));
    for (int i = 0; i < nd; ++i) {
      if (ga[i] >= 0 && ga[i] < n) f[ga[i]] += e.force[static_cast<std::size_t>(i)];
      if (gb[i] >= 0 && gb[i] < n) f[gb[i]] += e.force[static_cast<std::size_t>(nd + i)];
    }
  }
  return f;
}

std::vector<ContactEffect::EndedContact> ContactEffect::carry_ended(const std::vector<EndedContact>& ended,
                                                                  const MeshPieces& from) const {
  const Mesh& now = model_.mesh();
  const Mesh& old = from.old;
  // The vertex now of each old one (the first, as transfer_history takes it; of a crack's two
  // faces, its own side's: old_vertex_on_its_side), and the element of each vertex now.
  const auto element_of = [&](std::int32_t v) {
    const auto& off = now.element_loop_offset;
    return static_cast<std::int32_t>(std::upper_bound(off.begin(), off.end(), v) - off.begin()) - 1;
  };
  std::vector<std::int32_t> vertex_now(old.loop_vertex_count(), -1);
  for (std::size_t v = 0; v < now.loop_vertex_count() && v < from.vertex_parent.size(); ++v) {
    std::int32_t was = from.vertex_parent[v];
    if (was < 0) continue;
    const std::int32_t e = element_of(static_cast<std::int32_t>(v));
    if (e >= 0) was = old_vertex_on_its_side(old, now, from.element_parent[static_cast<std::size_t>(e)], e,
                                             static_cast<std::int32_t>(v), was);
    if (vertex_now[static_cast<std::size_t>(was)] < 0) vertex_now[static_cast<std::size_t>(was)] = static_cast<std::int32_t>(v);
  }
  // The pieces of each old element (CSR).
  std::vector<std::int32_t> first(old.element_count() + 1, 0), pieces(now.element_count());
  for (const std::int32_t p : from.element_parent) ++first[static_cast<std::size_t>(p) + 1];
  for (std::size_t i = 1; i < first.size(); ++i) first[i] += first[i - 1];
  std::vector<std::int32_t> at(first.begin(), first.end() - 1);
  for (std::size_t e = 0; e < now.element_count(); ++e)
    pieces[static_cast<std::size_t>(at[static_cast<std::size_t>(from.element_parent[e])]++)] = static_cast<std::int32_t>(e);
  // The vertex now of old vertex w: the map's, else one the cut made (no parent) at w's point but
  // for round-off, on w's side (vertex_off_the_map).
  const auto now_of = [&](std::int32_t w) {
    const std::int32_t v = vertex_now[static_cast<std::size_t>(w)];
    if (v >= 0) return v;
    const auto& off = old.element_loop_offset;
    const auto oe = static_cast<std::size_t>(std::upper_bound(off.begin(), off.end(), w) - off.begin()) - 1;
    return vertex_off_the_map(old, now, from.vertex_parent, pieces.data() + first[oe], pieces.data() + first[oe + 1], w);
  };
  std::vector<EndedContact> out;
  out.reserve(ended.size());
  for (const EndedContact& c : ended) {
    const std::int32_t va = now_of(c.vertex);
    if (va < 0) continue;
    const std::int32_t ea = element_of(va);
    if (ea < 0 || from.element_parent[static_cast<std::size_t>(ea)] != c.elem_a) continue;
    // The edge now: of the pieces of the old edge's element, the loop edge nearest its point (on
    // it but for round-off; the old edge itself, or the part of it a new crack's vertex split off).
    std::int32_t eb = -1, edge = -1;
    double best = std::numeric_limits<double>::infinity();
    for (std::int32_t i = first[static_cast<std::size_t>(c.elem_b)]; i < first[static_cast<std::size_t>(c.elem_b) + 1]; ++i) {
      const auto e = static_cast<std::size_t>(pieces[static_cast<std::size_t>(i)]);
      const std::int32_t b = now.element_loop_offset[e], end = now.element_loop_offset[e + 1];
      for (std::int32_t v = b; v < end; ++v) {
        const std::int32_t w = v + 1 < end ? v + 1 : b;
        const double ax = now.loop_xy[2 * static_cast<std::size_t>(v)], ay = now.loop_xy[2 * static_cast<std::size_t>(v) + 1];
        const double dx = now.loop_xy[2 * static_cast<std::size_t>(w)] - ax, dy = now.loop_xy[2 * static_cast<std::size_t>(w) + 1] - ay;
        const double l2 = dx * dx + dy * dy;
        const double t = l2 > 0 ? std::clamp(((c.bx - ax) * dx + (c.by - ay) * dy) / l2, 0.0, 1.0) : 0.0;
        const double dist = std::hypot(ax + t * dx - c.bx, ay + t * dy - c.by);
        if (dist < best) best = dist, eb = static_cast<std::int32_t>(e), edge = v;
      }
    }
    if (eb < 0) continue;
    const std::int32_t mirror = c.mirror >= 0 ? now_of(c.mirror) : -1;
    // Its end shear force and springs' energy with it: T0 of a contact found open on its edge
    // (commit's start_shear_) and the trace's start energy are the same across the re-cut.
    out.push_back({va, mirror, edge, ea, eb, c.bx, c.by, c.force, c.shear_force, c.stored});
  }
  return out;
}

bool ContactEffect::update_pattern(RunState& s) {
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
  const int first = first_group_;
  const auto& had = s.pattern_pairs;
  // The groups in the present pattern: final if it holds every pair, else what the deferral counts.
  const bool holds = problem_.assign_groups(had, first) == 0;
  if (holds) return false;
  if (model_.step_inertia()) {
    const double outside = static_cast<double>(problem_.outside_pattern().touching);
    const double touching = static_cast<double>(contacts_.touching_at_start());
    if (outside <= std::min(static_cast<double>(kDeferredTouching), kDeferredShare * touching)) return false;
  }
  const auto now = contacts_.element_pairs();
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  std::set_union(had.begin(), had.end(), now.begin(), now.end(), std::back_inserter(pairs));
  const auto last = contacts_.element_pairs(true);
  std::vector<std::pair<std::int32_t, std::int32_t>> used;
  std::set_union(now.begin(), now.end(), last.begin(), last.end(), std::back_inserter(used));
  if (static_cast<double>(pairs.size()) > kPatternSlack * static_cast<double>(used.size())) pairs = std::move(used);
  s.pattern_pairs = std::move(pairs);
  // The stepper builds the pattern again (EffectStep::pattern_changed).
  problem_.assign_groups(s.pattern_pairs, first);
  return true;
}

void ContactEffect::trace_rejected_step(const RunState& s, const Eigen::VectorXd& covers_d) const {
  // NMM_TRACE_PEN: the cover a rejected step moved most (its node and support) and the contacts it
  // found deepest (which vertex, which edge, how deep at the start and the end), on stderr: for
  // finding why a run cuts its step (docs/fracture.md).
  static const bool trace = std::getenv("NMM_TRACE_PEN") != nullptr;
  if (!trace) return;
  const Mesh& mesh = model_.mesh();
  const double max_penetration = contacts_.totals().max_penetration;
  Eigen::Index worst = 0;
  const double moved = covers_d.cwiseAbs().maxCoeff(&worst);
  const int cover = space_.cover_of_unknown(static_cast<int>(worst));
  const std::int32_t node = mesh.cover_node[static_cast<std::size_t>(cover)];
  int elements = 0;
  const double support = cover_support(mesh, cover, elements);
  std::fprintf(stderr, "moved most: cover %d (node %d at %.9g %.9g) by %.3g m; %d elements, support %.3g m2\n", cover,
               node, mesh.node_xy[2 * node], mesh.node_xy[2 * node + 1], moved, elements, support);
  for (const Contact& c : contacts_.contacts())
    if (-c.gap > 0.5 * max_penetration)
      std::fprintf(stderr, "pen: v %d (elem %d blk %d, at %.9g %.9g) edge %d (elem %d blk %d) gap0 %.3g gap %.3g state0 %d len %.3g\n",
                   c.at.vertex, c.at.elem_a, mesh.element_block[c.at.elem_a], s.loop_xy[2 * c.at.vertex],
                   s.loop_xy[2 * c.at.vertex + 1], c.at.edge, c.at.elem_b, mesh.element_block[c.at.elem_b], c.at.gap,
                   c.gap, static_cast<int>(c.start_state), c.length);
}

void ContactEffect::write_outputs(OutputStep& out) const {
  if (!contacts_.active()) return;
  // The joint's stresses in Pa are the forces over the contact's tributary length; the springs
  // carry the effective stress, so it repeats the normal stress by name beside the water's.
  OutputTable& t = out.tables.table(
      "contacts.csv",
      "step,time,contact,x,y,state,set,closure,shear,normal_force,shear_force,kn,ks,length,vertex,edge,"
      "normal_stress,shear_stress,pressure,effective_normal_stress,jrc_mob,dilation");
  const std::vector<ContactSample> rows = contact_samples(contacts_, model_, out.state);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ContactSample& c = rows[i];
    t.row(out.step, out.time);
    t.add_index(static_cast<std::int64_t>(i));
    t.add(c.x);
    t.add(c.y);
    t.add_index(c.state);
    t.add_index(c.law);
    for (double v : {c.closure, c.shear, c.normal_force, c.shear_force, c.kn, c.ks, c.length}) t.add(v);
    t.add_index(c.vertex);
    t.add_index(c.edge);
    for (double v : {c.normal_force / c.length, c.shear_force / c.length, c.pressure, c.normal_force / c.length,
                     c.jrc_mob, c.dilation})
      t.add(v);
    t.end_row();
  }
}

void ContactEffect::loaded_faces(const RunState& s, std::vector<std::uint8_t>& loaded) const {
  const Mesh& mesh = model_.mesh();
  const std::size_t stride = mesh.element_count() > 0 ? s.stress.size() / mesh.element_count() : 0;
  for (const Contact& c : contacts_.contacts()) {
    if (c.state == ContactState::open) continue;
    // The tips' integral takes the element's σ·n for the face's traction: a face counts where its
    // element presses it (σ_nn < 0). One in tension across is open in the rock's physics whatever
    // holds it: the faces next to a tip share the tip's covers and stay tied at a gap of
    // round-off; counted with their element's tensile σ·n, the tip of a semi-circular bend
    // specimen read K_II one fifth of the free faces' (−33 against −160 kPa·√m) and would kink
    // 30° where the test's path starts at 50–60° (docs/crack-tips.md "A curved path").
    if (stride >= 3) {
      const std::int32_t v = c.at.vertex;
      const std::int32_t g0 = mesh.element_loop_offset[static_cast<std::size_t>(c.at.elem_a)];
      const std::int32_t g1 = mesh.element_loop_offset[static_cast<std::size_t>(c.at.elem_a) + 1];
      const std::int32_t w = v + 1 < g1 ? v + 1 : g0;
      const double dx = mesh.loop_xy[2 * static_cast<std::size_t>(w)] - mesh.loop_xy[2 * static_cast<std::size_t>(v)];
      const double dy = mesh.loop_xy[2 * static_cast<std::size_t>(w) + 1] - mesh.loop_xy[2 * static_cast<std::size_t>(v) + 1];
      const double len = std::hypot(dx, dy);
      if (len > 0) {
        const double nx = dy / len, ny = -dx / len;  // outward: the loop runs counter-clockwise
        const double* sg = &s.stress[stride * static_cast<std::size_t>(c.at.elem_a)];
        if (sg[0] * nx * nx + sg[1] * ny * ny + 2 * sg[2] * nx * ny >= 0) continue;  // Pa, σ_nn
      }
    }
    loaded[static_cast<std::size_t>(c.at.edge)] = 1;
    const std::int32_t f0 = mesh.element_loop_offset[static_cast<std::size_t>(c.at.elem_a)];
    const std::int32_t f1 = mesh.element_loop_offset[static_cast<std::size_t>(c.at.elem_a) + 1];
    loaded[static_cast<std::size_t>(c.at.vertex)] = 1;
    loaded[static_cast<std::size_t>(c.at.vertex == f0 ? f1 - 1 : c.at.vertex - 1)] = 1;
  }
}

void ContactEffect::summarise(const RunState& s, nlohmann::json& summary) const {
  summary["max_contacts_at_closure_cap"] = s.max_capped;
  // Where new cracks soften (cohesive_law.h; their faces are contacts), what the contact solve
  // measured of it goes to summary.json's fracture block (docs/fracture.md "Snap-back"): accepted
  // steps in which a face's damage grew by w_c/4 or more at once (the static path could not
  // follow the softening), and attempts cut because a softening crack found no balance.
  if (contacts_.cohesive()) {
    summary["fracture"]["snap_back_steps"] = stats_.snap_back_steps;
    summary["fracture"]["snap_back_cuts"] = stats_.cohesive_unsettled;
  }
  const ContactSet::Events& ev = contacts_.events;
  const ContactSet::Totals joint = contacts_.totals();
  summary["contacts"] = {{"at_end", contacts_.contacts().size()},
                         {"closed_at_end", joint.closed},
                         // The joint at the end: closed length (m), largest stresses (Pa).
                         {"closed_length_at_end", joint.closed_length},
                         {"max_normal_stress_at_end", joint.max_normal_stress},
                         {"max_shear_stress_at_end", joint.max_shear_stress},
                         {"pairs_tested", contacts_.detection_stats().pairs_tested},
                         // Detection's Verlet list: built anew this many times, reused otherwise.
                         {"candidate_list_builds", contacts_.detection_stats().list_builds},
                         // State changes in all iterations (attempts that were cut included):
                         // many "settled" ones mean contacts chattering at zero gap or slip.
                         {"closings", ev.closed},
                         {"openings", ev.opened},
                         {"slips", ev.slid},
                         {"sticks", ev.stuck},
                         // Bonds and cohesions broken on accepted steps only (contact.h
                         // break_at_peak), each where its force reached its peak.
                         {"bonds_broken", ev.broken}};
  summary["contact_solve"] = {{"newton_iterations", stats_.newton},
                              {"cg_iterations", stats_.cg_iterations},
                              {"cg_runs_over_budget", stats_.cg_aborted},
                              {"factorisations", stats_.factorisations},
                              {"friction_updates", stats_.strength_updates},
                              // Attempts solved again because contacts broke at their solution,
                              // and the extra solves (docs/contact.md "Cohesion and tensile bonds").
                              {"steps_resolved_for_breaks", stats_.steps_resolved_for_breaks},
                              {"break_resolves", stats_.break_resolves},
                              // What the tolerance allows (contact_solve.cpp, docs/contact.md).
                              {"tolerance", model_.scene().solver.contact_tolerance},
                              {"max_force_tolerance_N", stats_.max_force_tolerance},
                              {"max_gap_error_m", stats_.max_gap_error},
                              {"displacement_tolerance_m",
                               contacts_.softening() ? displacement_tolerance(model_.scene().solver.contact_tolerance, model_.w0())
                                                       : 0.0},
                              {"max_displacement_error_m", stats_.max_displacement_error},
                              {"displacement_checks", stats_.displacement_checks},
                              {"displacement_refusals", stats_.displacement_refusals}};
}

void ContactEffect::effect_names(const RunState& /*s*/, std::vector<std::string>& names) const {
  for (std::string& n : contacts_.effects()) names.push_back(std::move(n));
}

void ContactEffect::energy_state(const EnergyState& /*e*/, EnergyTerms& t) const {
  for (const Contact& c : contacts_.contacts())
    if (c.state != ContactState::open)
      t.stored += springs_energy(c);
}

void ContactEffect::energy_step(const EnergyStep& e, EnergyTerms& t) const {
  for (std::size_t k = 0; k < contacts_.contacts().size(); ++k) book_contact(e, k, t);
  t.damped += released_work_;
  trace_energy_step(e, t);
}

void ContactEffect::book_contact(const EnergyStep& e, std::size_t k, EnergyTerms& t) const {
  const std::vector<std::int32_t>& joint = e.model.mesh().loop_edge_joint;
  {
    const Contact& c = contacts_.contacts()[k];
    const double t0 = k < start_shear_.size() ? start_shear_[k] : 0.0;  // N, T0 (commit)
    if (c.state == ContactState::sliding) {
      // The step's slip (trial elastic shear less what the spring keeps) under the shear force,
      // taken linear over the step from T0, the force the contact starts it with (the last
      // accepted step's end force, carried across a re-cut; 0 where it starts open with none:
      // commit), to T at its end, as the step takes every force of the balance (the supports'
      // ē, the strain energy's ½(σ0 + σ1)): ½(|T0| + |T|)·slip. That is what a static step's balance gives the contact
      // exactly, W − ΔU − ½ dᵀ(2M/Δt²)d = −½ (c0 + c1)·d, its springs taking the rest, whether it
      // slid on, started to slide from sticking, or closed from open within the step; so a face
      // sliding while its normal force falls books ∫N·tanφ ds, and one that closes and slides
      // from no force half its end force (booked at its end force, the compression cells'
      // contacts that close and slide in the steps after a crack left R at −500 J/m a step:
      // docs/energy.md `friction`). Cohesive faces book the end force (their cohesion's share
      // of it is taken out: cohesion_slip_work, cohesive_law.h), as do a contact that turns and
      // the two below that start at no force and give half of it back where the energy came from.
      const double slip = std::abs(c.shear - c.shear_el);
      const double end_work = std::abs(c.shear_force) * slip;
      const auto edge = static_cast<std::size_t>(c.at.edge);
      if (c.cohesive.on) {
        t.friction += end_work;
      } else if (e.changed_start && edge < joint.size() && joint[edge] >= static_cast<std::int32_t>(e.joints_before)) {
        // A new crack's face (it starts closed at gap 0 with no force, state_transfer.h) that
        // slides within the step that cut it: the static step took its shear force from 0 to
        // T along the slip, ½|T|·slip, and friction books |T|·slip — the other half is what
        // the crack's release gave its faces' contacts beyond their springs (crack_release.h),
        // so the fracture column gives it back.
        t.friction += end_work;
        t.fracture -= 0.5 * end_work;
      } else if (c.start_state == ContactState::open &&
                 std::binary_search(released_.begin(), released_.end(), c.at.vertex)) {
        // A released contact (commit; across a re-cut too) that closes again within the step
        // and slides: it started at no force, the step took its shear force from 0 to T along
        // the slip, and of the release ½ (0 − c_end)·d it spent ½|T|·slip on that beyond the
        // linear path, which friction books at its end force: the motion took the rest.
        t.friction += end_work;
        t.damped -= 0.5 * end_work;
      } else if (t0 * c.shear_force >= 0) {
        t.friction += 0.5 * (std::abs(t0) + std::abs(c.shear_force)) * slip;
      } else {
        // Turned (T0 against T): the end force. (The balance's ½(T − |T0|)·slip, or 0 where the
        // start force was the larger, left the Barton–Bandis shear box's reversal at R = 208
        // against 115 J/m: its dilation and secant springs are not the linear step's.)
        t.friction += end_work;
      }
    } else if (c.state == ContactState::open && c.start_state == ContactState::sliding && !c.cohesive.on) {
      // A contact that slid into the step and opens within it: the same trapezoid, from T0 to
      // no force, over the shear its spring lets go of as the faces part, the trial shear s
      // (the start's elastic shear plus the step's shear motion): ½ T0·s, where the faces
      // slid on the way T0 pushed (what the balance gives it less the ½|T0·s_el| its spring
      // held, within its normal spring's −½ N0·gap: measured on uniaxial compression h 0.125 m,
      // static, slow, 164.8 of 158.1 J/m over its run; docs/energy.md `friction`).
      t.friction += std::max(0.0, 0.5 * t0 * c.shear);
    }
    t.friction -= c.normal_force * c.dilation_step;  // the asperities' opening (0 but Barton–Bandis)
    t.fracture += c.cohesive_step;
    t.friction -= c.cohesion_slip_work;
  }
}

void ContactEffect::trace_energy_step(const EnergyStep& e, const EnergyTerms& t) const {
  // NMM_TRACE_ENERGY: each contact's share of the step's energy on stderr — the work the
  // static step's balance gives it exactly, −½ (c_prev + c_end)·d (c_prev the end force the last
  // accepted step ended with on the same vertex and edge, carried across a re-cut), against what
  // the meter books for it: its springs' change and its friction. For finding which rule leaves
  // a residual (docs/energy.md).
  static const bool trace = std::getenv("NMM_TRACE_ENERGY") != nullptr;
  if (!trace || trace_d_.size() == 0) return;
  const Eigen::VectorXd& d = trace_d_;
  const int nd = space_.element_dofs();
  const bool have_prev = start_end_unknowns_ == d.size() || start_end_unknowns_ == -2;
  std::vector<char> used(start_ended_.size(), 0);
  const std::vector<Contact>& cs = contacts_.contacts();
  double sum_exact = 0, sum_booked = 0;
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const Contact& c = cs[k];
    const auto [dg, ds] = row_motion(k, d);  // m
    const double end_work = c.state == ContactState::open ? 0.0 : c.normal_force * dg - c.shear_force * ds;
    double prev_work = 0, prev_stored = 0;
    int matched = -1;
    if (have_prev)
      for (std::size_t j = 0; j < start_ended_.size(); ++j)
        if (!used[j] && start_ended_[j].vertex == c.at.vertex && start_ended_[j].edge == c.at.edge) {
          used[j] = 1;
          matched = static_cast<int>(j);
          prev_work = ended_work(start_ended_[j], d, nd);
          prev_stored = start_ended_[j].stored;
          break;
        }
    if (matched < 0 && have_prev)  // the vertex's end force on another edge (it moved on along its face)
      for (std::size_t j = 0; j < start_ended_.size(); ++j)
        if (!used[j] && (start_ended_[j].vertex == c.at.vertex || (c.mirror >= 0 && start_ended_[j].vertex == c.mirror))) {
          used[j] = 1;
          matched = -2 - static_cast<int>(j);
          prev_work = ended_work(start_ended_[j], d, nd);
          prev_stored = start_ended_[j].stored;
          break;
        }
    const double exact = -0.5 * (prev_work + end_work);
    const double stored = c.state == ContactState::open
                              ? 0.0
                              : springs_energy(c);
    const double slip = c.state == ContactState::sliding ? std::abs(c.shear - c.shear_el) : 0.0;
    if (prev_work == 0 && end_work == 0 && prev_stored == 0 && stored == 0) continue;
    const bool rel = std::binary_search(released_.begin(), released_.end(), c.at.vertex);
    const std::vector<std::int32_t>& joint = e.model.mesh().loop_edge_joint;
    const auto edge = static_cast<std::size_t>(c.at.edge);
    const bool new_face = e.changed_start && edge < joint.size() && joint[edge] >= static_cast<std::int32_t>(e.joints_before);
    sum_exact += exact;
    sum_booked += stored - prev_stored;
    EnergyTerms b;  // what the meter books for it besides its springs
    book_contact(e, k, b);
    const double sunk = k < trace_sunk_.size() ? trace_sunk_[k] : 0.0;
    std::fprintf(stderr,
                 "ec %lld v %d e %d m %d rel %d nf %d s0 %d s1 %d N0 %.6g g0 %.6g g1 %.6g sh %.6g N1 %.6g T0 %.6g T1 %.6g dg %.6g ds %.6g slip %.6g exact %.6g dS %.6g len %.6g "
                 "t0 %.6g fr %.6g fx %.6g dp %.6g sunk %.6g left %.6g\n",
                 static_cast<long long>(e.s.step), c.at.vertex, c.at.edge, matched, rel ? 1 : 0, new_face ? 1 : 0, static_cast<int>(c.start_state),
                 static_cast<int>(c.state), problem_.work(k).start_normal_force, problem_.work(k).gap0, c.gap, c.shear,
                 c.normal_force, c.start_shear_force, c.shear_force, dg, ds, slip, exact,
                 stored - prev_stored, c.length, k < start_shear_.size() ? start_shear_[k] : 0.0, b.friction, b.fracture,
                 b.damped, sunk, exact - (stored - prev_stored) - b.friction - b.fracture - b.damped - sunk);
  }
  double released = 0, released_stored = 0;
  for (std::size_t j = 0; j < start_ended_.size() && have_prev; ++j)
    if (!used[j]) {
      released += -0.5 * ended_work(start_ended_[j], d, nd);
      released_stored += start_ended_[j].stored;
    }
  std::fprintf(stderr, "es %lld exact %.6g dS %.6g released %.6g released_stored %.6g friction %.6g damped %.6g cut %d booked_released %.6g\n",
               static_cast<long long>(e.s.step), sum_exact, sum_booked, released, released_stored, t.friction, t.damped,
               e.changed_start ? 1 : 0, released_work_);
}

}  // namespace nmm::solve
