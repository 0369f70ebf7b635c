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

#include <nlohmann/json.hpp>

#include "common/mesh.h"
#include "common/outcome.h"
#include "common/scene.h"

namespace nmm::report {

/// How a finished run ended, from its summary.json: its "stop_code", with "stop_time" and
/// "status" (an older summary without stop_code: ok and interrupted by their status, any other
/// status failed; no status: failed, "unknown").
Outcome run_outcome(const nlohmann::json& summary);

/// The likely cause of a run stopped by `code`, one or two sentences; "" when the code is no
/// failure or has no likely cause to name.
std::string likely_failure_cause(const Mesh& mesh, const SceneDef& scene, StopCode code);

}  // namespace nmm::report
