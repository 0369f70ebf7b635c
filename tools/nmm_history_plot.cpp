// nmm-history-plot OUT.svg RUNDIR... [--title TEXT]
//
// Plots the measure points' displacements (ux, uy, mm) against time from the history.csv of one
// or more runs — the stages of a staged analysis, each continuing from the last one's
// checkpoint, so their times follow on — as one SVG (common/svg_plot.h). Used for the pictures
// in docs/staged-analysis.md. Bad input (a missing or malformed history.csv): exit status 2.
#include <CLI/CLI.hpp>

#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/command_line.h"
#include "common/error.h"
#include "common/scene.h"
#include "common/svg_plot.h"
#include "common/whole_file.h"

namespace {

struct Sample {
  double t, ux, uy;
};

/// point → samples, read from DIR/history.csv (columns step,time,point,x,y,ux,uy,...).
void read_history(const std::string& dir, std::map<int, std::vector<Sample>>& out) {
  const std::string path = dir + "/history.csv";
  const std::string text = nmm::read_text_file(path);
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no == 1) {
      if (line.rfind("step,time,point,x,y,ux,uy", 0) != 0)
        throw nmm::InputError(path, "line 1", "expected the header step,time,point,x,y,ux,uy");
      continue;
    }
    if (line.empty()) continue;
    std::vector<double> v;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',') && v.size() < 7) {
      char* end = nullptr;
      v.push_back(std::strtod(cell.c_str(), &end));
      if (end == cell.c_str()) throw nmm::InputError(path, "line " + std::to_string(line_no), "not a number: " + cell);
    }
    if (v.size() < 7) throw nmm::InputError(path, "line " + std::to_string(line_no), "expected 7 columns");
    out[static_cast<int>(v[2])].push_back({v[1], 1e3 * v[5], 1e3 * v[6]});
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nmm-history-plot: measure-point displacements against time, over one or more runs"};
  std::string out, title = "measure points";
  std::vector<std::string> dirs;
  app.add_option("output", out, "SVG file to write")->required();
  app.add_option("runs", dirs, "run folders (OUTDIR of nmm-solve), in order")->required();
  app.add_option("--title", title, "plot title");
  if (const int status = nmm::parse_command_line(app, argc, argv, "nmm-history-plot"); status >= 0)
    return status;
  try {
    std::map<int, std::vector<Sample>> points;
    for (const std::string& d : dirs) read_history(d, points);
    static const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
    nmm::PlotSpec spec;
    spec.title = title;
    spec.xlabel = "time (s)";
    spec.ylabel = "displacement (mm)";
    for (const auto& [p, samples] : points) {
      nmm::PlotSeries ux, uy;
      ux.name = "point " + std::to_string(p) + " ux";
      uy.name = "point " + std::to_string(p) + " uy";
      ux.colour = uy.colour = kColours[static_cast<std::size_t>(p) % 6];
      uy.markers = true;
      for (const Sample& s : samples) {
        ux.x.push_back(s.t);
        ux.y.push_back(s.ux);
        uy.x.push_back(s.t);
        uy.y.push_back(s.uy);
      }
      spec.series.push_back(ux);
      spec.series.push_back(uy);
    }
    nmm::write_svg_plot(spec, out);
  } catch (const nmm::InputError& e) {
    std::cerr << e.what() << "\n";
    return nmm::kExitBadInput;
  }
  return nmm::kExitOk;
}
