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
  /// Names of x = 1, 2, 3, …: a categorical x axis ticked at those values with these names
  /// (empty: a numeric axis).
  std::vector<std::string> x_categories{};
};

/// Round tick values covering [lo, hi]: steps of 1, 2 or 5 × 10^k, about `target` of them
/// (fewer when the span is short). Shared by the plots and result.svg's axes.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

/// The 1, 2 or 5 × 10^k nearest below v (v > 0): scale bars, exaggeration factors.
double round_down_125(double v);

/// Tick label: "%g", or one significant digit in e-notation far from 1 ("2e-05").
std::string tick_label(double v);

/// The plot as an SVG document, `pixel_width` wide (sweep.svg's panels are smaller).
std::string svg_plot(const PlotSpec& spec, double pixel_width = 900);

/// SVG documents (each with width and height attributes) as one document, in rows of `columns`
/// cells left to right: each becomes a nested <svg> at its cell's offset, the cells as wide as
/// the widest document, each row as high as its highest. run_history.svg's panels (1 column),
/// sweep.svg's grid.
std::string svg_grid(const std::vector<std::string>& docs, std::size_t columns);

/// Writes svg_plot(spec) to `path` atomically (InputError naming the file on failure).
void write_svg_plot(const PlotSpec& spec, const std::string& path);

}  // namespace nmm
