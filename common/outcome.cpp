// The typed outcome: see outcome.h.
#include "common/outcome.h"

#include <utility>

namespace nmm {

namespace {
struct Named {
  StopCode code;
  const char* name;
};
constexpr Named kNames[] = {
    {StopCode::ok, "ok"},
    {StopCode::interrupted, "interrupted"},
    {StopCode::step_displacement, "step_displacement"},
    {StopCode::penetration, "penetration"},
    {StopCode::contact_not_converged, "contact_not_converged"},
    {StopCode::direction_not_finite, "direction_not_finite"},
    {StopCode::bolts_not_settled, "bolts_not_settled"},
    {StopCode::fracture_cascade, "fracture_cascade"},
    {StopCode::flow_not_converged, "flow_not_converged"},
    {StopCode::element_folded, "element_folded"},
    {StopCode::unconstrained, "unconstrained"},
    {StopCode::displacement_not_finite, "displacement_not_finite"},
    {StopCode::output_failed, "output_failed"},
    {StopCode::failed, "failed"},
};
}  // namespace

const char* stop_code_name(StopCode code) {
  for (const Named& n : kNames)
    if (n.code == code) return n.name;
  return "failed";
}

bool stop_code_from_name(std::string_view name, StopCode& code) {
  for (const Named& n : kNames)
    if (name == n.name) {
      code = n.code;
      return true;
    }
  return false;
}

bool cured_by_shorter_step(StopCode code) {
  switch (code) {
    case StopCode::step_displacement:
    case StopCode::penetration:
    case StopCode::contact_not_converged:
    case StopCode::direction_not_finite:
    case StopCode::bolts_not_settled:
    case StopCode::fracture_cascade:
    case StopCode::flow_not_converged:
    case StopCode::element_folded: return true;
    default: return false;
  }
}

std::string Outcome::status() const {
  if (code == StopCode::ok) return "ok";
  if (code == StopCode::interrupted) return "interrupted";
  return reason;
}

std::ostream& operator<<(std::ostream& os, const Outcome& o) {
  os << stop_code_name(o.code);
  if (!o.reason.empty() && o.code != StopCode::ok) os << ": " << o.reason;
  return os;
}

}  // namespace nmm
