// How a step, a contact solve or a run ended: one typed outcome for the whole project.
//
// The solver returns it (TimeStepper::attempt and run_until, solve_contact_step); code branches
// on its StopCode, never on words. The words (`reason`) are for a person: stderr, summary.json's
// "status" (the contract's text: "ok", "interrupted" or the reason) beside its stable
// "stop_code" (stop_code_name()), and the result picture. Readers of a finished run (nmm-report,
// nmm-fos, nmm-sweep) read "stop_code" back with stop_code_from_name().
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>

namespace nmm {

enum class StopCode : std::uint8_t {
  ok,                       ///< the run reached its end (or solver.stop_at_ratio); a step converged
  interrupted,              ///< SIGINT/SIGTERM between steps: results kept
  // What a shorter step may cure (the run cuts Δt and tries again, cured_by_shorter_step()):
  step_displacement,        ///< a step moved a cover farther than step control allows
  penetration,              ///< a contact penetrated deeper than step control allows
  contact_not_converged,    ///< the contact solve's Newton iterations ran out
  direction_not_finite,     ///< the contact solve's direction was not finite
  bolts_not_settled,        ///< the bolts' springs kept switching between elastic and yielding (or slipping)
  fracture_cascade,         ///< cracks kept growing through more re-cuts than one step may take
  flow_not_converged,       ///< the coupled flow's iterations of a step did not converge (flow_effect.h)
  element_folded,           ///< a step would fold an element's triangle over (step_control.h)
  // What no shorter step cures (the run stops at once):
  unconstrained,            ///< the system is singular: a cover or block held by nothing
  displacement_not_finite,  ///< a solved displacement was not finite
  output_failed,            ///< an output file could not be written (a full disk): the run cannot go on
  failed,                   ///< a stopped run whose summary.json names no stop_code (older files)
};

/// The stable name of summary.json's "stop_code": "ok", "interrupted", "penetration", ...
const char* stop_code_name(StopCode code);
/// The code of a stop_code name; false for a name that is none.
bool stop_code_from_name(std::string_view name, StopCode& code);
/// Whether a shorter time step may cure it (the step is cut and tried again).
bool cured_by_shorter_step(StopCode code);

struct Outcome {
  StopCode code = StopCode::ok;
  std::string reason;  ///< in words, for a person (empty when ok)
  double time = 0;     ///< s, simulated time of the state the step or run stopped at

  bool ok() const { return code == StopCode::ok; }
  /// A run that stopped on a failure (not ok, not interrupted).
  bool failed() const { return code != StopCode::ok && code != StopCode::interrupted; }
  /// summary.json's "status": "ok", "interrupted" or the reason.
  std::string status() const;

  static Outcome stop(StopCode code, std::string reason, double time) { return {code, std::move(reason), time}; }
};

/// "ok", or the code's name and the reason ("penetration: a contact penetrated ..."): for logs
/// and test messages.
std::ostream& operator<<(std::ostream& os, const Outcome& o);

}  // namespace nmm
