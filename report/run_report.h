// The report of a finished (or stopped) run, made from the files in its folder, so that
// `nmm-report OUTDIR` can remake it at any time and nmm-solve --pictures makes it at the end:
//   history.svg      measure points' displacements ux, uy (mm) against time (from history.csv)
//   run_history.svg  panels: open–close iterations per step and step length against time
//                    (from run_history.csv, solver/output/run_history.h); the equilibrium
//                    indicators — maximum and mean unbalanced force ratio and largest
//                    velocity, log scale (run_history.csv,
//                    equilibrium_indicator.h); the energy terms against time (from energy.csv,
//                    energy.h: kinetic, strain, gravity, springs, work of loads, friction, residual)
//   load_travel.svg  each moving support's load (its force on the body along its velocity, kN
//                    per m) against its travel (mm), from reactions.csv and summary.json
//                    "supports" (solver/output/reactions.h): the curve a rock test is read from
//   index.html       the pictures (result.svg when nmm-solve drew it) and summary.json's
//                    status (a stopped run's reason and likely cause, failure_cause.h), times
//                    and counts as a table in engineering notation with units, never wider
//                    than the window
//   *.png            the SVGs converted by rsvg-convert (Debian librsvg2-bin) when it is on PATH
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace nmm::report {

/// A CSV of numbers with a header line (history.csv, contacts.csv, run_history.csv, energy.csv).
struct NumberTable {
  std::vector<std::string> names;         ///< the header's column names
  std::vector<std::vector<double>> rows;  ///< one per data line
  /// Index of the column named n, or -1.
  int column(const std::string& n) const;
};

/// Reads such a CSV, plain or gzip-compressed (contacts.csv.gz). InputError naming the file (and
/// line) when it is missing, damaged or a cell is not a number.
NumberTable read_number_csv(const std::string& path);

/// What make_run_report wrote (file names relative to the folder).
struct ReportFiles {
  std::vector<std::string> written;
  bool png = false;  ///< rsvg-convert was found and made PNGs
};

/// Reads the run folder and writes the report files listed above. InputError naming the file
/// when summary.json or history.csv is missing or unreadable.
ReportFiles make_run_report(const std::string& dir);

}  // namespace nmm::report
