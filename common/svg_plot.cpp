#include "common/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "common/svg_writer.h"
#include "common/atomic_file.h"
#include "common/number_format.h"

namespace nmm {

namespace {

constexpr double kW = 100, kH = 62;  // plot area in drawing units

// Ticks of an axis in its own (possibly log10) units: whole decades on a log axis.
std::vector<double> ticks(double lo, double hi, bool log) {
  if (!log) return nice_ticks(lo, hi, 6);
  std::vector<double> t;
  for (double e = std::floor(lo); e <= std::ceil(hi) + 1e-9; e += 1) t.push_back(e);
  return t;
}

}  // namespace

std::string tick_label(double v) {
  if (std::abs(v) < 1e-12) v = 0;  // a tick at round-off from zero is labelled 0, not -0
  if (v != 0 && (std::abs(v) >= 1e4 || std::abs(v) < 1e-2)) return format_scientific(v, 1);
  return format_rough(v, 6);
}

double round_down_125(double v) {
  if (!(v > 0) || !std::isfinite(v)) return 1;
  const double mag = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * mag <= v * (1 + 1e-12)) return m * mag;
  return mag;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> t;
  const double span = hi - lo;
  if (!(span > 0) || !std::isfinite(span)) return t;
  const double raw = span / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * mag) {
      step = m * mag;
      break;
    }
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step)
    t.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);
  return t;
}

std::string svg_plot(const PlotSpec& spec, double pixel_width) {
  auto tx = [&](double v) { return spec.log_x ? std::log10(v) : v; };
  auto ty = [&](double v) { return spec.log_y ? std::log10(v) : v; };
  auto ok = [](bool log, double v) { return std::isfinite(v) && (!log || v > 0); };
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const PlotSeries& s : spec.series)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!ok(spec.log_x, s.x[i]) || !ok(spec.log_y, s.y[i])) continue;
      x0 = std::min(x0, tx(s.x[i]));
      x1 = std::max(x1, tx(s.x[i]));
      y0 = std::min(y0, ty(s.y[i]));
      y1 = std::max(y1, ty(s.y[i]));
    }
  if (!(x0 <= x1)) x0 = 0, x1 = 1;
  if (!(y0 <= y1)) y0 = 0, y1 = 1;
  if (x1 - x0 < 1e-300) x0 -= 0.5, x1 += 0.5;
  if (y1 - y0 < 1e-300) y0 -= 0.5, y1 += 0.5;
  if (!spec.log_y && y0 > 0 && y0 < 0.3 * y1) y0 = 0;  // start at zero when it is near
  if (!spec.log_x && x0 > 0 && x0 < 0.3 * x1) x0 = 0;
  const double px = 0.04 * (x1 - x0), py = 0.06 * (y1 - y0);
  x0 -= spec.log_x ? 0 : (x0 == 0 ? 0 : px), x1 += px;
  y0 -= spec.log_y ? 0 : (y0 == 0 ? 0 : py), y1 += py;
  if (!spec.x_categories.empty())  // half a slot beside the first and the last category
    x0 = 0.5, x1 = static_cast<double>(spec.x_categories.size()) + 0.5;
  auto X = [&](double v) { return kW * (tx(v) - x0) / (x1 - x0); };
  auto Y = [&](double v) { return kH * (ty(v) - y0) / (y1 - y0); };

  SvgWriter w;
  const SvgStyle axis{"none", "#222222", 0.25, 0, 1}, grid{"none", "#dddddd", 0.12, 0, 1};
  std::vector<double> x_ticks = ticks(x0, x1, spec.log_x);
  if (!spec.x_categories.empty()) {
    x_ticks.clear();
    for (std::size_t k = 1; k <= spec.x_categories.size(); ++k) x_ticks.push_back(static_cast<double>(k));
  }
  for (double t : x_ticks) {
    const double x = kW * (t - x0) / (x1 - x0);
    if (x < -1e-9 || x > kW + 1e-9) continue;
    w.polyline({{x, 0}, {x, kH}}, grid);
    const std::string label = spec.x_categories.empty()
                                  ? tick_label(spec.log_x ? std::pow(10.0, t) : t)
                                  : spec.x_categories[static_cast<std::size_t>(t) - 1];
    w.text({x - 0.5 * SvgWriter::text_width(label, 2.4), -4}, label, 2.4, "#222222");
  }
  for (double t : ticks(y0, y1, spec.log_y)) {
    const double y = kH * (t - y0) / (y1 - y0);
    if (y < -1e-9 || y > kH + 1e-9) continue;
    w.polyline({{0, y}, {kW, y}}, grid);
    w.text({-11, y - 0.8}, tick_label(spec.log_y ? std::pow(10.0, t) : t), 2.4, "#222222");
  }
  w.polyline({{0, kH}, {0, 0}, {kW, 0}}, axis);
  w.text({kW / 2 - spec.xlabel.size() * 0.6, -9}, spec.xlabel, 2.8, "#222222");
  double lx = 0, ly = kH + 3.5;  // legend: rows between the plot area and the title
  for (const PlotSeries& s : spec.series) {
    std::vector<Vec2> pts;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (ok(spec.log_x, s.x[i]) && ok(spec.log_y, s.y[i])) pts.push_back({X(s.x[i]), Y(s.y[i])});
    const SvgStyle st{"none", s.colour, 0.4, 0, 1}, dot{s.colour, "none", 0, 0, 1};
    if (s.line && pts.size() > 1) w.polyline(pts, st);
    if (s.markers)
      for (const Vec2& p : pts) w.circle(p, 0.8, dot);
    const double width = 10 + 1.25 * static_cast<double>(s.name.size());
    if (lx > 0 && lx + width > kW) {  // a new row above
      lx = 0;
      ly += 4;
    }
    if (s.line) w.polyline({{lx, ly + 0.8}, {lx + 5, ly + 0.8}}, st);
    if (s.markers) w.circle({lx + 2.5, ly + 0.8}, 0.8, dot);
    w.text({lx + 6.5, ly}, s.name, 2.4, "#222222");
    lx += width;
  }
  w.text({-11, ly + 4.5}, spec.ylabel, 2.8, "#222222");
  w.text({0, ly + 9.5}, spec.title, 3.4, "#000000");
  return w.str(0.04, pixel_width);
}

std::string svg_grid(const std::vector<std::string>& docs, std::size_t columns) {
  if (columns == 0) columns = 1;
  auto attribute = [](const std::string& doc, const std::string& name) {
    const std::size_t at = doc.find(" " + name + "=\"");
    return at == std::string::npos ? 0.0 : std::strtod(doc.c_str() + at + name.size() + 3, nullptr);
  };
  std::vector<std::string> inner;
  double cell_w = 0;
  for (const std::string& d : docs) {
    const std::size_t open = d.find("<svg ");
    if (open == std::string::npos) continue;
    inner.push_back(d.substr(open));
    cell_w = std::max(cell_w, attribute(inner.back(), "width"));
  }
  std::string body;
  double height = 0, row_h = 0;
  for (std::size_t i = 0; i < inner.size(); ++i) {
    std::string& doc = inner[i];
    const std::size_t col = i % columns;
    if (col == 0 && i > 0) height += row_h, row_h = 0;
    const double h = attribute(doc, "height");
    doc.insert(5, "x=\"" + std::to_string(static_cast<long long>(cell_w * static_cast<double>(col))) +
                      "\" y=\"" + std::to_string(static_cast<long long>(height)) + "\" ");
    body += doc;
    if (body.back() != '\n') body += '\n';
    row_h = std::max(row_h, h);
  }
  height += row_h;
  const double width = cell_w * static_cast<double>(std::min(columns, std::max<std::size_t>(inner.size(), 1)));
  const std::string w = std::to_string(static_cast<long long>(width));
  const std::string h = std::to_string(static_cast<long long>(height));
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + w +
         "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h + "\">\n" + body + "</svg>\n";
}

void write_svg_plot(const PlotSpec& spec, const std::string& path) {
  write_file_atomically(path, svg_plot(spec));
}

}  // namespace nmm
