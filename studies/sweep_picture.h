// sweep.svg: what a sweep found, at a glance. A grid of small plots, one per (varied parameter,
// measured output) pair — a column per parameter, a row per output — each the output of every
// run against that parameter's value. Runs that differ only in that parameter are joined by a
// line (one colour per combination of the other parameters, named in the legend), so a trend
// reads along a line and the other parameters' effect across lines. Runs that stopped (status
// other than "ok") are red dots in a series of their own, "stopped runs": their outputs are
// those of the state they stopped in, not of the end.
//
// Parameter values that are not numbers (variant names) are categories on the x axis, in the
// order they first appear. Titles and legends use short names (the parameter's last path
// component, "ux of point 0"); the axis labels the full column names of sweep.csv. Outputs are the sweep's summary and
// history columns that hold a number in at least one run (status text is left out).
#pragma once

#include <string>
#include <vector>

#include "studies/sweep.h"

namespace nmm::studies {

/// A CSV line split into fields (RFC 4180 quotes, as sweep_csv writes them).
std::vector<std::string> split_csv_line(const std::string& line);

/// The picture of `csv` (sweep_csv's text for `sweep`); "" when the sweep varies no parameter
/// or measured no numeric output. `panels`, when given, receives the number of plots.
std::string sweep_svg(const Sweep& sweep, const std::string& csv, std::size_t* panels = nullptr);

}  // namespace nmm::studies
