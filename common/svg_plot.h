// Line and scatter plots as SVG (studies, accuracy–time pictures): axes with 1-2-5 ticks,
// optional log axes, a legend. Built on SvgWriter, so the pictures need no plotting library.
#pragma once

#include <string>
#include <vector>

namespace nmm {

struct PlotSeries {
  std::string name;          ///< legend text
  std::vector<double> x, y;  ///< data, same length
  std::string colour = "#1f77b4";
  bool line = true;          ///< join the points
  bool markers = false;      ///< draw a dot at each point
};

struct PlotSpec {
  std::string title, xlabel, ylabel;
  bool log_x = false, log_y = false;  ///< logarithmic axes (non-positive values are skipped)
  std::vector<PlotSeries> series;
};

/// The plot as an SVG document.
std::string svg_plot(const PlotSpec& spec);

/// Writes svg_plot(spec) to `path` atomically (InputError naming the file on failure).
void write_svg_plot(const PlotSpec& spec, const std::string& path);

}  // namespace nmm
