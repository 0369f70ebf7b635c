// nmm-report OUTDIR [--frame STEP] [--mesh MESH.nmm] [--picture-field F] [--exaggerate F]: remakes the report of
// a finished or stopped nmm-solve run from the files in its folder: result.svg redrawn from the
// last frame (or the frame of step STEP) with the mesh summary.json names (result_redraw.h),
// then history.svg, run_history.svg (solver effort and energy), index.html, PNGs when rsvg-convert is available
// (run_report.h). Without --frame/--mesh, a result.svg that cannot be redrawn (the mesh file has
// moved) is left as it is, with a warning; with them it is an error.
// Exit status: 0 done, 2 the folder is not a run folder or the frame cannot be drawn (one line
// on stderr).
#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <string>

#include "common/command_line.h"
#include "common/error.h"
#include "nmm_version.h"
#include "report/result_redraw.h"
#include "report/run_report.h"

int main(int argc, char** argv) {
  CLI::App app{"nmm-report: pictures and index.html of a finished nmm-solve run"};
  std::string dir;
  bool quiet = false;
  app.add_option("outdir", dir, "output folder of nmm-solve")->required();
  app.add_flag("-q,--quiet", quiet, "do not list the files written");
  nmm::report::RedrawOptions redraw;
  app.add_option("--frame", redraw.frame_step,
                 "draw result.svg from the frame of this step (frames/frame_<step>.vtu); default: the last")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--mesh", redraw.mesh_path,
                 "the run's mesh file, if summary.json's inputs.mesh no longer finds it");
  app.add_option("--picture-field", redraw.field,
                 "what colours result.svg: displacement, sxx, syy, sxy or pressure (default: the run's)");
  app.add_option("--exaggerate", redraw.exaggerate,
                 "draw result.svg's displacements F times larger (1: true scale); default: the "
                 "run's --exaggerate, else automatic below 1 % of the model size")
      ->check(CLI::PositiveNumber);
  app.set_version_flag("--version", std::string("nmm-report ") + NMM_VERSION);
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-report"); status >= 0)
    return status;
  try {
    const bool must_draw = redraw.frame_step >= 0 || !redraw.mesh_path.empty() ||
                           !redraw.field.empty() || redraw.exaggerate > 0;
    std::string drawn;
    // Not a run folder at all: make_run_report says so in its one line.
    if (std::filesystem::exists(std::filesystem::path(dir) / "summary.json") || must_draw) {
      try {
        const nmm::report::RedrawInfo info = nmm::report::redraw_result(dir, redraw);
        drawn = "result.svg (step " + std::to_string(info.step) + ", " +
                std::to_string(info.polygons) + " elements, " + std::to_string(info.contacts) +
                " closed contacts)";
      } catch (const nmm::InputError& e) {
        if (must_draw) throw;
        std::cerr << "nmm-report: warning: result.svg not redrawn: " << e.what() << "\n";
      }
    }
    const nmm::report::ReportFiles files = nmm::report::make_run_report(dir);
    if (!quiet) {
      std::cout << "nmm-report: wrote";
      if (!drawn.empty()) std::cout << ' ' << drawn;
      for (const std::string& f : files.written) std::cout << ' ' << f;
      std::cout << " in " << dir << "\n";
    }
  } catch (...) {
    return nmm::exit_status_of_current_exception("nmm-report");
  }
  return nmm::kExitOk;
}
