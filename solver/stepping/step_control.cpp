// Shi's step control: see step_control.h for the rules and their constants.
#include "solver/stepping/step_control.h"

#include <algorithm>
#include <utility>

#include "common/number_format.h"

namespace nmm::solve {

StepControl::StepControl(const SolverDef& solver, double w0, double dt)
    : time_step_(solver.time_step),
      ratio_(solver.max_displacement_ratio),
      w0_(w0),
      g2w0_(solver.max_displacement_ratio * w0),
      floor_(kFloor * solver.time_step),
      dt_(std::min(dt, solver.time_step)) {}

double StepControl::next(double t, double t_end) const {
  const double left = t_end - t;
  return left < dt_ * (1 - kRoundOff) ? left : dt_;
}

Outcome StepControl::rejection(double dmax, const StepPenetration& penetration, bool inertia) const {
  // The reason names w0 in words: users coming from UDEC do not know DDA's symbol. The value and
  // its limit get the digits that tell them apart (6e-06 against 6e-06 would puzzle).
  const double limit = g2w0_;
  const std::string ratio = format_rough(ratio_, 3);
  const std::string w0 = format_rough(w0_, 3) + " m";
  auto apart = [](double value, double bound) {
    int digits = 3;
    while (digits < 9 && format_rough(value, digits) == format_rough(bound, digits)) ++digits;
    return std::make_pair(format_rough(value, digits), format_rough(bound, digits));
  };
  if (inertia && dmax > kMaxMove * limit) {
    const auto [moved, allowed] = apart(dmax, kMaxMove * limit);
    return {StopCode::step_displacement, "one step moved a cover by " + moved + " m, more than the " + allowed +
           " m a step may move (2 × max_displacement_ratio " + ratio + " × w0 " + w0 +
           ", w0 being half the model size as in DDA)"};
  }
  if (penetration.added > limit) {
    const auto [added, allowed] = apart(penetration.added, limit);
    return {StopCode::penetration, "one step made a contact " + added + " m deeper, more than the " + allowed +
           " m a step may add (max_displacement_ratio " + ratio + " × w0 " + w0 +
           ", w0 being half the model size as in DDA)"};
  }
  const PenetrationAllowance allow = allowance();
  const double p0 = penetration.worst_start, p = penetration.worst_end;
  if (p > allow.deepest(p0)) {
    if (allow.deepest(p0) > allow.cap) {
      const auto [sank, allowed] = apart(p - p0, allow.sink);
      return {StopCode::penetration, "a contact that started the step " + format_rough(p0, 6) +
             " m deep, at or past the " + format_rough(allow.cap, 3) + " m cap, sank " + sank +
             " m in it, more than the " + allowed + " m allowed (" + format_rough(kSink, 3) +
             " × max_displacement_ratio " + ratio + " × w0 " + w0 + ", w0 being half the model size as in DDA)"};
    }
    const auto [depth, allowed] = apart(p, allow.cap);
    return {StopCode::penetration, "a contact penetrated " + depth + " m, more than the " + allowed +
           " m allowed (2 × max_displacement_ratio " + ratio + " × w0 " + w0 +
           ", w0 being half the model size as in DDA)"};
  }
  // However slowly a contact sinks past the cap, contact detection loses it at its search
  // distance: a run whose contact gets there stops (no cut keeps what it has already sunk).
  if (penetration.deepest > search_distance()) {
    const auto [depth, allowed] = apart(penetration.deepest, search_distance());
    return {StopCode::penetration, "a contact penetrated " + depth + " m, past the " + allowed +
           " m contact detection follows a contact to (2.5 × max_displacement_ratio " + ratio + " × w0 " + w0 +
           ", w0 being half the model size as in DDA)"};
  }
  return {};
}

Outcome StepControl::folding(std::int64_t element) const {
  return {StopCode::element_folded, "the step would fold element " + std::to_string(element) +
                                        "'s triangle over (its covers' nodes moved past one another)"};
}

bool StepControl::cut(double h) {
  dt_ = kCut * h;
  return !(dt_ < floor_);
}

void StepControl::accept() { dt_ = std::min(kGrowth * dt_, time_step_); }

}  // namespace nmm::solve
