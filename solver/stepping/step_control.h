// Shi's step control (DDA, Shi 1988 ch. 6; docs/contact.md "Step control"): how long the next
// attempt is, whether a solved attempt may be accepted, and how far contact detection looks.
// The attempt itself (assembly, solve, update) is TimeStepper's; this decides around it.
//
// With g2 = solver.max_displacement_ratio and w0 half the model size (model.h):
//   search distance   d0 = 2.5·g2·w0 (+ the largest joint dilation, contact.h)
//   reach             r = min(d0, 0.05·h): how far apart open faces are looked for, where no
//                     open contact carries history (contact_set.h open_history); an attempt in
//                     which a loop vertex moves m > r/2 is redone with r = min(d0, 4·m), the
//                     same Δt (time_stepper.cpp)
//   accept a step     max_i |d_i| ≤ 2·g2·w0   (runs with the inertia term: dynamic, DDA static)
//                     max_c (p_c − max(p0_c, 0)) ≤ g2·w0        what the step adds to a depth
//                     p_c ≤ max(2·g2·w0, p0_c + 0.01·g2·w0)      the cap on a contact it deepens
//                     max_c {p_c : p_c > p0_c} ≤ 2.5·g2·w0     detection's reach, whatever the start
//                     no element's triangle folded:  2·A_e(x_c + d_c) > 0 for every element e
//                     (every run, contact or not: Configuration::folded_by)
//   after a rejection Δt ← 0.3·Δt; the run stops when Δt < 1e-3·time_step
//   after acceptance  Δt ← min(1.3·Δt, time_step)
// Without contact every step that folds no element has the full length time_step.
//
// The penetration rule, with p_c a contact's depth at the attempt's end and p0_c at its start (m,
// positive inside; p0 < 0: it started open). Shi's rule bounds the depth itself, p_c ≤ g2·w0, and
// a shorter step is its cure: what a step adds shrinks with Δt. A contact that starts the step
// near the limit (carried over a re-cut at the depth it sank to under load, or cut within
// round-off by a crack) has nothing left to add, and then no cut cures it: the run stopped at
// the floor with "a contact penetrated 0.001001 m, more than the 0.001 m allowed" (uniaxial and
// biaxial compression, h 0.0625 m, dynamic: docs/notes/2026-11-fracture-robustness.md). So a
// step is judged by what it adds, p_c − max(p0_c, 0) ≤ g2·w0 — a contact new in the step, or
// open at its start, is judged by its whole depth as before. Step by step a depth could then grow
// without bound, a vertex passing through the edge it is held by; the cap 2·g2·w0 on any contact
// the step deepens catches that, below contact detection's reach d0 = 2.5·g2·w0 (an accepted step
// leaves no contact deeper than detection can follow). A contact that starts at or within
// 0.01·g2·w0 of the cap (carried over a re-cut, cut so by a crack, or sunk there) may end the
// step 0.01·g2·w0 below its start: judged by its depth alone, a contact that sank past the cap by
// round-off could be cured by no cut. One that sinks in earnest has its steps cut to that much
// sinking each, and at the reach d0 the run stops at the floor: detection would lose it.
//
// The reach: d0 follows w0, the model's half width, so on a wide model detection looked far past
// what a step moves (the 316 × 316 brick wall at h = 2 m: d0 = 0.40 m, steps moving µm to mm)
// and its candidates grew with the width, not the blocks (docs/performance.md (h)). Two faces
// come at most 2·m nearer in an attempt whose loop vertices each move at most m (a vertex and
// the segment's ends), so a contact open wider than r at the start cannot close in an attempt
// with 2·m ≤ r: leaving it out changes no contact that closes. An attempt that moves more is
// solved again from its start with every contact it could have closed, Δt unchanged (a
// redo, not a cut: no physics asked for a shorter step); with r = d0, Shi's rule alone.
//
// A folding element is judged on the solved step, before it is accepted: the step is rejected and
// cut like one that moved too far (a shorter step moves the covers less), and the run stops only
// at the floor. Found at the next attempt's start instead, the fold was already in the accepted
// state, and no shorter step could undo it: the run stopped there (step_path_slope h2 dynamic
// slow, element 932 of 2.6e-13 m², docs/fracture.md "Robustness matrix").
#pragma once

#include "common/outcome.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include "common/scene.h"
#include "solver/discretisation/effect.h"

namespace nmm::solve {

class StepControl {
 public:
  /// –, a rejected step is redone this much shorter: short enough that one or two cuts cure a
  /// contact the step overshot, not so short that a run crawls after a single bad step.
  static constexpr double kCut = 0.3;
  /// –, an accepted step's successor is at most this much longer (back towards time_step): the
  /// cut's inverse would grow back in one step and likely fail again; 1.3 takes 4–5 steps.
  static constexpr double kGrowth = 1.3;
  /// –, the run stops when a cut takes Δt below this fraction of time_step: a step that small
  /// still failing means the time step is not the cause (exit status 3 says why).
  static constexpr double kFloor = 1e-3;
  /// –, contact detection looks 2.5·g2·w0 far: past the 2·g2·w0 a step may move, so no contact
  /// the step makes is missed.
  static constexpr double kSearch = 2.5;
  /// –, a step may move no cover more than 2·g2·w0 (contacts beyond the search distance would be
  /// missed).
  static constexpr double kMaxMove = 2.0;
  /// –, no step may deepen a contact past 2·g2·w0: twice what one step may add, below the search
  /// distance 2.5·g2·w0 that contact detection follows a closed contact to.
  static constexpr double kDeepest = 2.0;
  /// –, a contact that starts a step at or near the cap may sink this × g2·w0 in it, past the
  /// cap: enough for the round-off a contact at rest sinks by, a hundredth of what a step may add
  /// to a shallower one, so that a contact sinking in earnest has its steps cut.
  static constexpr double kSink = 0.01;
  /// –, relative to time_step: times this close count as equal (the last step of a run is cut
  /// to end at t_end unless it is within round-off of a full step, so 2N steps and N + N from a
  /// checkpoint take the same steps, bitwise).
  static constexpr double kRoundOff = 1e-9;

  /// `dt`: the step length to start with (the checkpoint's, else time_step), s.
  StepControl(const SolverDef& solver, double w0, double dt);

  /// ×h, contact detection looks at most this far for open contacts where the stepper checks
  /// each attempt's motion against it (the reach, above): on the peer brick walls at h = 2 m,
  /// 0.1 m, the d0 of a 78 × 78 wall (about 6,000 blocks); below d0 only on wider ones.
  static constexpr double kReach = 0.05;

  /// m, how far contact detection looks for contacts a step can make (before dilation).
  double search_distance() const { return kSearch * g2w0_; }
  /// m, how far an attempt looks for open contacts (the reach r, at most search_distance) on a
  /// mesh of size h (m).
  double contact_reach(double h) const { return std::min(search_distance(), kReach * h); }
  /// m, the depth a step may add to a contact (g2·w0): rejection() cuts a step that adds more.
  double penetration_limit() const { return g2w0_; }
  /// m, the deepest a step may make a contact it deepens (2·g2·w0), unless it started near it.
  double penetration_cap() const { return kDeepest * g2w0_; }
  /// How deep a step may make a contact it deepens: the cap, or kSink·g2·w0 below its start.
  PenetrationAllowance allowance() const { return {penetration_cap(), kSink * g2w0_}; }
  /// Whether the run has reached t_end (s) within round-off.
  bool done(double t, double t_end) const { return !(t < t_end - kRoundOff * time_step_); }
  /// s, the length of the next attempt from t: Δt, or what is left to t_end.
  double next(double t, double t_end) const;
  /// Why a solved attempt may not be accepted (step_displacement or penetration, with the
  /// reason; ok if it may): the largest cover displacement dmax (m; checked with the inertia
  /// term only: an equilibrium increment does not shrink with Δt) and what the step did to its
  /// contacts' depths (m; the rule above).
  Outcome rejection(double dmax, const StepPenetration& penetration, bool inertia) const;
  /// Why a solved attempt that would fold `element`'s triangle over (Configuration::folded_by)
  /// may not be accepted: element_folded, cured like step_displacement by a shorter step.
  Outcome folding(std::int64_t element) const;
  /// After a rejected attempt of length h (s): false when the cut step is below the floor.
  bool cut(double h);
  /// After an accepted attempt: Δt grows back towards time_step.
  void accept();
  double dt() const { return dt_; }        ///< s, the current step length
  double floor() const { return floor_; }  ///< s, the shortest step allowed

 private:
  double time_step_;  // s, solver.time_step
  double ratio_;      // –, g2 = solver.max_displacement_ratio
  double w0_;         // m
  double g2w0_;       // m
  double floor_;      // s
  double dt_;         // s
};

}  // namespace nmm::solve
