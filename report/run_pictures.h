// The pictures of a run held in memory, at its current state: result.svg (result_picture.h) and
// the run's report from its folder (run_report.h: history.svg, run_history.svg, index.html, PNG
// copies). nmm-solve --pictures and the Python module (nmm.Solver.pictures, nmm.solve(...,
// pictures=True)) draw through it.
#pragma once

#include <string>

#include "common/outcome.h"
#include "common/scene.h"
#include "report/result_picture.h"
#include "report/run_report.h"
#include "solver/stepping/run_view.h"

namespace nmm::report {

/// Draws result.svg of the run's current state into `dir` (the run's output folder, where its
/// history.csv and summary.json are) and makes the run's report there. `outcome`: how the run
/// ended (a stopped run's reason goes under the picture); `exaggerate` 0: automatic.
ReportFiles write_run_pictures(const solve::RunView& run, const SceneDef& scene, const Outcome& outcome,
                               const std::string& dir, double exaggerate, PictureField field);

}  // namespace nmm::report
