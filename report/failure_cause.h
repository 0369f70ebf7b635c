// Why a run stopped, in words a rock engineer can act on: the likely cause behind summary.json's
// status, drawn under result.svg and added to nmm-solve's last line.
//
// The cause named first is a mesh coarser than a body: mesh size above the body's inradius
// (the estimate 2·area/perimeter of scene_checks.h, the test nmm-preprocess warns with). Such a
// body is one or two stiff elements whose corners jump from step to step, so its contacts
// fail Shi's step control (2 × max_displacement_ratio × w0 per step) or never settle. The
// comparison is stated with the body's width (the smaller side of its bounding box), the
// number a user checks against the scene. Otherwise the cause follows the kind of failure:
// the step control (a block falling or flying off, or a time step too long), an open–close
// iteration that did not converge (contacts changing state), a system that is not positive
// definite (a block held by nothing).
#pragma once

#include <string>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::report {

/// How a run ended, read from its status (summary.json's "status", the stepper's result): the
/// status is text for the files and the user, this is what code branches on.
enum class RunEnd {
  unknown,      ///< no status
  ok,           ///< "ok": reached its end
  interrupted,  ///< "interrupted": Ctrl-C, results kept
  frame,        ///< "step N": a frame before the end (nmm-report --frame)
  failed,       ///< any other status: the failure's reason
};
RunEnd run_end(const std::string& status);

/// False for statuses of runs that did not stop on a failure, true for every other status.
inline bool status_is_failure(const std::string& status) { return run_end(status) == RunEnd::failed; }

/// The likely cause of a stopped run, one or two sentences; "" when the status is no failure.
std::string likely_failure_cause(const Mesh& mesh, const SceneDef& scene, const std::string& status);

}  // namespace nmm::report
