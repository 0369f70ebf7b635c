// nmm-report OUTDIR: remakes the report of a finished or stopped nmm-solve run from the files in
// its folder (run_report.h): history.svg, run_history.svg, index.html, PNGs when rsvg-convert is
// available. result.svg (the picture of the blocks) is drawn by nmm-solve --pictures, which has
// the mesh and the final state; the report shows it when present.
// Exit status: 0 done, 2 the folder is not a run folder (one line on stderr).
#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "command_line.h"
#include "error.h"
#include "nmm_version.h"
#include "run_report.h"

int main(int argc, char** argv) {
  CLI::App app{"nmm-report: pictures and index.html of a finished nmm-solve run"};
  std::string dir;
  bool quiet = false;
  app.add_option("outdir", dir, "output folder of nmm-solve")->required();
  app.add_flag("-q,--quiet", quiet, "do not list the files written");
  app.set_version_flag("--version", std::string("nmm-report ") + NMM_VERSION);
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-report"); status >= 0)
    return status;
  try {
    const nmm::solve::ReportFiles files = nmm::solve::make_run_report(dir);
    if (!quiet) {
      std::cout << "nmm-report: wrote";
      for (const std::string& f : files.written) std::cout << ' ' << f;
      std::cout << " in " << dir << "\n";
    }
  } catch (const nmm::InputError& e) {
    std::cerr << e.what() << "\n";
    return nmm::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "nmm-report: internal error: " << e.what() << "\n";
    return 1;
  }
  return nmm::kExitOk;
}
