// sweep.svg: see sweep_picture.h.
#include "studies/sweep_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "common/svg_plot.h"

namespace nmm::studies {

namespace {

const char* const kColours[] = {"#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
                                "#17becf", "#e377c2", "#7f7f7f", "#bcbd22"};

bool to_number(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(v);
}

// Short names for titles and legends (the axis labels keep the full ones): a parameter's last
// path component ("joint_sets.interface.friction_deg" → "friction_deg"), an output without
// its source ("summary.max_penetration" → "max_penetration", "history.ux.p0" → "ux of
// point 0").
std::string short_parameter(const std::string& name) {
  const std::size_t dot = name.rfind('.');
  return dot == std::string::npos ? name : name.substr(dot + 1);
}

std::string short_output(const std::string& name) {
  if (name.rfind("summary.", 0) == 0) return name.substr(8);
  if (name.rfind("history.", 0) == 0) {
    const std::string rest = name.substr(8);
    const std::size_t dot = rest.rfind(".p");
    if (dot != std::string::npos) return rest.substr(0, dot) + " of point " + rest.substr(dot + 2);
    return rest;
  }
  return name;
}

}  // namespace

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else out.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else if (c != '\r') {
      out.back() += c;
    }
  }
  return out;
}

std::string sweep_svg(const Sweep& sweep, const std::string& csv, std::size_t* panels) {
  if (panels != nullptr) *panels = 0;
  std::istringstream in(csv);
  std::string line;
  if (!std::getline(in, line)) return "";
  const std::vector<std::string> header = split_csv_line(line);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line))
    if (!line.empty()) rows.push_back(split_csv_line(line));
  auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : static_cast<int>(it - header.begin());
  };
  auto cell = [&](const std::vector<std::string>& r, int c) {
    return c >= 0 && static_cast<std::size_t>(c) < r.size() ? r[static_cast<std::size_t>(c)] : "";
  };

  // Parameters: their columns, and whether every value is a number.
  struct Parameter {
    std::string name;
    int col;
    bool numeric = true;
    std::vector<std::string> levels;  // distinct values, first-seen order
  };
  std::vector<Parameter> params;
  for (const std::string& p : sweep.parameters) {
    Parameter par{p, column(p), true, {}};
    if (par.col < 0) continue;
    for (const auto& r : rows) {
      const std::string v = cell(r, par.col);
      double x;
      par.numeric = par.numeric && to_number(v, x);
      if (std::find(par.levels.begin(), par.levels.end(), v) == par.levels.end())
        par.levels.push_back(v);
    }
    params.push_back(par);
  }
  // Outputs: the summary and history columns with a number in some run.
  std::vector<std::pair<std::string, int>> outputs;
  const int status_col = column("run_status");
  for (std::size_t c = 0; c < header.size(); ++c) {
    const std::string& h = header[c];
    if (h.rfind("summary.", 0) != 0 && h.rfind("history.", 0) != 0) continue;
    bool any = false;
    double v;
    for (const auto& r : rows) any = any || to_number(cell(r, static_cast<int>(c)), v);
    if (any) outputs.emplace_back(h, static_cast<int>(c));
  }
  if (params.empty() || outputs.empty()) return "";

  auto x_of = [](const Parameter& p, const std::string& v) {
    double x = 0;
    if (p.numeric && to_number(v, x)) return x;
    return static_cast<double>(std::find(p.levels.begin(), p.levels.end(), v) - p.levels.begin() + 1);
  };
  std::vector<std::string> docs;
  for (const auto& [out_name, out_col] : outputs)
    for (std::size_t pi = 0; pi < params.size(); ++pi) {
      const Parameter& p = params[pi];
      // One series per combination of the other parameters' values.
      std::map<std::string, nmm::PlotSeries> by_rest;
      std::vector<std::string> order;
      nmm::PlotSeries stopped{"stopped runs", {}, {}, "#d62728", false, true};
      for (const auto& r : rows) {
        double y;
        if (!to_number(cell(r, out_col), y)) continue;
        const double x = x_of(p, cell(r, p.col));
        if (status_col >= 0 && cell(r, status_col) != "ok") {
          stopped.x.push_back(x), stopped.y.push_back(y);
          continue;
        }
        std::string rest;
        for (std::size_t qi = 0; qi < params.size(); ++qi)
          if (qi != pi)
            rest += (rest.empty() ? "" : ", ") + short_parameter(params[qi].name) + " " +
                    cell(r, params[qi].col);
        if (!by_rest.count(rest)) order.push_back(rest);
        nmm::PlotSeries& s = by_rest[rest];
        s.x.push_back(x), s.y.push_back(y);
      }
      nmm::PlotSpec spec;
      spec.title = short_output(out_name) + " against " + short_parameter(p.name);
      spec.xlabel = p.name;
      if (!p.numeric) spec.x_categories = p.levels;
      spec.ylabel = out_name;
      for (std::size_t k = 0; k < order.size(); ++k) {
        nmm::PlotSeries s = by_rest[order[k]];
        // Sorted by x, so the line runs along the parameter.
        std::vector<std::size_t> idx(s.x.size());
        for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
        std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return s.x[a] < s.x[b]; });
        nmm::PlotSeries sorted{order[k].empty() ? "runs" : order[k], {}, {}, kColours[k % 9],
                               s.x.size() > 1, true};
        for (std::size_t i : idx) sorted.x.push_back(s.x[i]), sorted.y.push_back(s.y[i]);
        spec.series.push_back(std::move(sorted));
      }
      if (!stopped.x.empty()) spec.series.push_back(stopped);
      docs.push_back(nmm::svg_plot(spec, 480));
    }
  if (panels != nullptr) *panels = docs.size();
  return nmm::svg_grid(docs, params.size());
}

}  // namespace nmm::studies
