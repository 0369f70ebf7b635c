// Report of a run folder: see run_report.h.
#include "report/run_report.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "report/failure_cause.h"
#include "common/gzip_text.h"
#include "common/number_format.h"
#include "common/png_copy.h"
#include "report/result_redraw.h"
#include "common/svg_plot.h"
#include "common/atomic_file.h"
#include "common/xml_text.h"

namespace nmm::report {
namespace fs = std::filesystem;
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot read (is this a finished nmm-solve output folder?)");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Units of summary.json's numbers, by key (the leaf's name; timings.* are all seconds).
std::string summary_unit(const std::string& parent, const std::string& key) {
  static const std::map<std::string, std::string> kUnits = {
      {"simulated_time", "s"},   {"wall_seconds", "s"},          {"time_step", "s"},
      {"max_penetration", "m"},  {"max_step_displacement", "m"}, {"fixed_point_stiffness", "N/m"},
      {"support_stiffness", "N/m"}};
  if (parent == "timings") return "s";
  const auto it = kUnits.find(key);
  if (it != kUnits.end()) return it->second;
  if (key.size() > 8 && key.compare(key.size() - 8, 8, "_seconds") == 0) return "s";
  return "";
}

// One summary value as (text, numeric?): counts with digit groups, other numbers in
// engineering notation with their unit, lists joined, null as a dash.
std::pair<std::string, bool> summary_cell(const nlohmann::json& v, const std::string& unit) {
  if (v.is_number_integer() || v.is_number_unsigned()) {
    std::string digits = v.dump(), grouped;
    const std::size_t sign = digits[0] == '-' ? 1 : 0;
    for (std::size_t i = 0; i < digits.size(); ++i) {
      if (i > sign && (digits.size() - i) % 3 == 0) grouped += "\u202f";  // narrow no-break space
      grouped += digits[i];
    }
    return {grouped + (unit.empty() ? "" : " " + unit), true};
  }
  if (v.is_number()) return {format_engineering(v.get<double>(), unit), true};
  if (v.is_boolean()) return {v.get<bool>() ? "yes" : "no", false};
  if (v.is_null()) return {"—", false};
  if (v.is_string()) return {v.get<std::string>(), false};
  if (v.is_array()) {
    if (v.empty()) return {"none", false};
    std::string out;
    for (const auto& item : v) {
      if (!out.empty()) out += item.is_object() ? "; " : ", ";
      if (item.is_object()) {
        std::string parts;
        for (auto it = item.begin(); it != item.end(); ++it)
          parts += (parts.empty() ? "" : " ") + it.key() + " " + summary_cell(it.value(), "").first;
        out += parts;
      } else {
        out += summary_cell(item, unit).first;
      }
    }
    return {out, false};
  }
  return {v.dump(), false};
}

// summary.json as table rows: a heading row per object, its members indented below it.
std::string summary_rows(const nlohmann::json& j, const std::string& parent, int depth) {
  std::string rows;
  for (auto it = j.begin(); it != j.end(); ++it) {
    std::string name = it.key();
    std::replace(name.begin(), name.end(), '_', ' ');
    const std::string th = depth > 0 ? "<th class=\"sub\">" : "<th>";
    if (it.value().is_object() && !it.value().empty()) {
      rows += "<tr><th class=\"group\" colspan=\"2\">" + xml_escape(name) + "</th></tr>\n";
      rows += summary_rows(it.value(), it.key(), depth + 1);
      continue;
    }
    const auto [text, numeric] = summary_cell(it.value(), summary_unit(parent, it.key()));
    rows += "<tr>" + th + xml_escape(name) + "</th><td" + (numeric ? " class=\"n\"" : "") + ">" +
            xml_escape(text) + "</td></tr>\n";
  }
  return rows;
}

const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

}  // namespace

int NumberTable::column(const std::string& n) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == n) return static_cast<int>(i);
  return -1;
}

NumberTable read_number_csv(const std::string& path) {
  std::string text = read_text(path);
  if (is_gzip(text)) text = gzip_decompress(text, path);  // contacts.csv.gz
  std::istringstream in(text);
  NumberTable t;
  std::string line;
  if (!std::getline(in, line)) throw InputError(path, "byte 0", "empty file, expected a header");
  std::stringstream h(line);
  for (std::string n; std::getline(h, n, ',');) t.names.push_back(n);
  std::size_t line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream r(line);
    for (std::string cell; std::getline(r, cell, ',');) {
      char* end = nullptr;
      row.push_back(std::strtod(cell.c_str(), &end));
      if (end == cell.c_str())
        throw InputError(path, "line " + std::to_string(line_no), "not a number: '" + cell + "'");
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

ReportFiles make_run_report(const std::string& dir) {
  ReportFiles files;
  const nlohmann::json summary = read_run_summary(dir);

  // Measure points' histories, mm.
  const std::string history_path = (fs::path(dir) / "history.csv").string();
  const NumberTable h = read_number_csv(history_path);
  const int ct = h.column("time"), cp = h.column("point"), cux = h.column("ux"), cuy = h.column("uy");
  if (ct < 0 || cp < 0 || cux < 0 || cuy < 0)
    throw InputError(history_path, "line 1", "header lacks time, point, ux or uy");
  std::map<int, std::pair<PlotSeries, PlotSeries>> points;
  for (const auto& r : h.rows) {
    if (r.size() < h.names.size()) continue;
    auto& [sx, sy] = points[static_cast<int>(r[cp])];
    sx.x.push_back(r[ct]), sx.y.push_back(1e3 * r[cux]);
    sy.x.push_back(r[ct]), sy.y.push_back(1e3 * r[cuy]);
  }
  if (!points.empty()) {
    PlotSpec spec{"measure points: displacement against time", "time (s)", "displacement (mm)",
                  false, false, {}};
    for (auto& [i, s] : points) {
      const std::string colour = kColours[i % 6];
      s.first.name = "m" + std::to_string(i) + " ux";
      s.first.colour = colour;
      s.second.name = "m" + std::to_string(i) + " uy";
      s.second.colour = colour;
      s.second.markers = true;
      spec.series.push_back(s.first);
      spec.series.push_back(s.second);
    }
    write_svg_plot(spec, (fs::path(dir) / "history.svg").string());
    files.written.push_back("history.svg");
  }

  // Solver effort per step (top panel) and the energy terms (bottom panel, energy.csv).
  std::vector<std::string> panels;
  const std::string rh_path = (fs::path(dir) / "run_history.csv").string();
  if (fs::exists(rh_path)) {
    const NumberTable r = read_number_csv(rh_path);
    const int t = r.column("time"), it = r.column("iterations"), dt = r.column("dt");
    if (t >= 0 && it >= 0 && dt >= 0 && !r.rows.empty()) {
      PlotSeries iters{"open–close iterations per step", {}, {}, "#1f77b4", true, false};
      PlotSeries steps{"step length (ms)", {}, {}, "#d62728", true, false};
      for (const auto& row : r.rows) {
        if (row.size() < r.names.size()) continue;
        iters.x.push_back(row[t]), iters.y.push_back(row[it]);
        steps.x.push_back(row[t]), steps.y.push_back(1e3 * row[dt]);
      }
      panels.push_back(svg_plot({"solver effort per step", "time (s)",
                                 "iterations / step length (ms)", false, false, {iters, steps}}));
    }
    // Equilibrium indicators (equilibrium_indicator.h), log scale: UDEC's ratio limit 1e-5 drawn.
    const int rmax = r.column("max_unbalanced_ratio"), rmean = r.column("mean_unbalanced_ratio"),
              vmax = r.column("max_velocity");
    if (t >= 0 && rmax >= 0 && rmean >= 0 && vmax >= 0 && !r.rows.empty()) {
      PlotSeries mx{"max unbalanced force ratio", {}, {}, "#d62728", true, false};
      PlotSeries mn{"mean unbalanced force ratio", {}, {}, "#ff7f0e", true, false};
      PlotSeries v{"largest velocity (m/s)", {}, {}, "#1f77b4", true, false};
      PlotSeries limit{"ratio 1e-5 (at rest below)", {}, {}, "#777777", true, false};
      for (const auto& row : r.rows) {
        if (row.size() < r.names.size()) continue;
        mx.x.push_back(row[t]), mx.y.push_back(row[rmax]);
        mn.x.push_back(row[t]), mn.y.push_back(row[rmean]);
        v.x.push_back(row[t]), v.y.push_back(row[vmax]);
      }
      if (!mx.x.empty()) {
        limit.x = {mx.x.front(), mx.x.back()};
        limit.y = {1e-5, 1e-5};
      }
      panels.push_back(svg_plot({"equilibrium: unbalanced force ratio and velocity", "time (s)",
                                 "ratio (–) / velocity (m/s)", false, true, {mx, mn, v, limit}}));
    }
  }
  const std::string energy_path = (fs::path(dir) / "energy.csv").string();
  if (fs::exists(energy_path)) {
    const NumberTable e = read_number_csv(energy_path);
    const int t = e.column("time");
    static const char* const kTerms[][3] = {
        {"kinetic", "kinetic K", "#1f77b4"},       {"strain", "strain U", "#2ca02c"},
        {"gravity", "gravity potential V", "#8c564b"}, {"springs", "penalty springs S", "#9467bd"},
        {"load_work", "work of loads W", "#17becf"}, {"friction", "friction work D", "#ff7f0e"},
        {"residual", "residual W − D − ΔE", "#d62728"}};
    PlotSpec spec{"energy (J per m of thickness)", "time (s)", "energy (J/m)", false, false, {}};
    for (const auto& term : kTerms) {
      const int c = e.column(term[0]);
      if (t < 0 || c < 0) continue;
      PlotSeries series{term[1], {}, {}, term[2], true, false};
      for (const auto& row : e.rows)
        if (row.size() >= e.names.size()) series.x.push_back(row[t]), series.y.push_back(row[c]);
      spec.series.push_back(std::move(series));
    }
    if (!spec.series.empty() && !spec.series[0].x.empty()) panels.push_back(svg_plot(spec));
  }
  if (!panels.empty()) {
    write_file_atomically((fs::path(dir) / "run_history.svg").string(), svg_grid(panels, 1));
    files.written.push_back("run_history.svg");
  }

  // A rock test's curve: each moving support's load against its travel (reactions.csv; the
  // direction of each support's velocity from summary.json "supports", solver/output/reactions.h).
  const std::string reactions_path = (fs::path(dir) / "reactions.csv").string();
  if (fs::exists(reactions_path) && summary.contains("supports") && summary["supports"].is_array()) {
    const NumberTable r = read_number_csv(reactions_path);
    const int cs = r.column("support"), cfx = r.column("fx"), cfy = r.column("fy"), ctr = r.column("travel");
    PlotSpec spec{"moving supports: load against travel", "travel (mm)", "load (kN per m)", false, false, {}};
    for (const nlohmann::json& sup : summary["supports"]) {
      const nlohmann::json dir_json = sup.value("direction", nlohmann::json::array());
      if (!sup.contains("support") || !dir_json.is_array() || dir_json.size() != 2) continue;
      const double dx = dir_json[0].get<double>(), dy = dir_json[1].get<double>();
      if (dx == 0 && dy == 0) continue;  // a held support has no travel
      const int k = sup["support"].get<int>();
      PlotSeries s{"support " + std::to_string(k), {}, {}, kColours[k % 6], true, false};
      if (cs < 0 || cfx < 0 || cfy < 0 || ctr < 0) break;
      for (const auto& row : r.rows)
        if (row.size() >= r.names.size() && static_cast<int>(row[cs]) == k) {
          s.x.push_back(1e3 * row[ctr]);
          s.y.push_back(1e-3 * (row[cfx] * dx + row[cfy] * dy));  // the force along its velocity
        }
      if (!s.x.empty()) spec.series.push_back(std::move(s));
    }
    if (!spec.series.empty()) {
      write_svg_plot(spec, (fs::path(dir) / "load_travel.svg").string());
      files.written.push_back("load_travel.svg");
    }
  }

  const bool has_result = fs::exists(fs::path(dir) / "result.svg");
  if (png_converter_available()) {
    files.png = true;
    std::vector<std::string> svgs = files.written;
    if (has_result) svgs.push_back("result.svg");
    for (const std::string& s : svgs)
      if (!write_png_copy((fs::path(dir) / s).string()).empty())
        files.written.push_back(s.substr(0, s.size() - 4) + ".png");
  }

  // index.html: pictures first (users look at pictures before numbers), then the summary. The
  // page is never wider than the window: a max-width column, pictures scaled to it (each a link
  // to itself at full size), long words (paths, hashes) broken anywhere.
  std::string html =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
      "<title>nmm run report</title>\n"
      "<style>body{font-family:sans-serif;max-width:70em;margin:1.5em auto;"
      "padding:0 1em;background:#fff;color:#111;overflow-wrap:anywhere}"
      "img{display:block;max-width:100%;height:auto;border:1px solid #ccc;margin:.5em 0}"
      "table{border-collapse:collapse;max-width:100%}"
      "td,th{border:1px solid #ccc;padding:2px 8px;text-align:left;vertical-align:top}"
      "td.n{text-align:right;white-space:nowrap}th.group{background:#eee}th.sub{padding-left:1.5em}"
      ".bad{color:#b00;font-weight:bold}.ok{color:#070;font-weight:bold}</style></head><body>\n";
  const std::string status = summary.value("status", std::string("unknown"));
  const Outcome outcome = run_outcome(summary);
  const bool finished = outcome.ok();
  auto number_at = [&](const char* key) {
    const auto it = summary.find(key);
    return it != summary.end() && it->is_number() ? it->get<double>() : 0.0;
  };
  html += "<h1>nmm run report</h1>\n<p>status: <span class=\"" +
          std::string(finished ? "ok" : "bad") + "\">" +
          (outcome.failed() ? std::string("stopped") : xml_escape(status)) +
          "</span>, simulated time " + format_engineering(number_at("simulated_time"), "s") +
          " in " + summary_cell(summary.value("steps_completed", nlohmann::json(0)), "").first +
          " steps, wall " + format_engineering(number_at("wall_seconds"), "s") + "</p>\n";
  // The equilibrium verdict beside the status, with the figure it was judged by (solver.md,
  // Equilibrium indicators): "ok" says the run reached its end, not that it is at rest.
  if (const auto eq = summary.find("equilibrium"); eq != summary.end() && eq->is_object()) {
    const std::string verdict = eq->value("verdict", std::string());
    const bool by_velocity = eq->value("criterion", std::string()).rfind("max_velocity", 0) == 0;
    const double figure = eq->value(by_velocity ? "max_velocity_m_s" : "max_unbalanced_ratio", 0.0);
    if (!verdict.empty())
      html += "<p>equilibrium: <span class=\"" + std::string(verdict == "at_rest" ? "ok" : "bad") +
              "\">" + (verdict == "at_rest" ? "at rest" : xml_escape(verdict)) + "</span> (" +
              (by_velocity ? "largest velocity " + format_engineering(figure, "m/s")
                           : "max unbalanced force ratio " + format_rough(figure, 2)) +
              ")</p>\n";
  }
  if (outcome.failed()) {
    html += "<p class=\"bad\">" + xml_escape(status) + "</p>\n";
    // The likely cause needs the run's mesh and scene; a folder whose mesh has moved gets the
    // reason alone.
    std::string cause;
    try {
      const RunInputs in = load_run_inputs(dir, "");
      cause = likely_failure_cause(in.mesh, in.scene, outcome.code);
    } catch (const InputError&) {
    }
    if (!cause.empty()) html += "<p>likely cause: " + xml_escape(cause) + "</p>\n";
  }
  if (has_result) html += "<h2>Result</h2>\n<a href=\"result.svg\"><img src=\"result.svg\" alt=\"result picture\"></a>\n";
  if (fs::exists(fs::path(dir) / "history.svg"))
    html += "<h2>Measure points</h2>\n<a href=\"history.svg\"><img src=\"history.svg\" alt=\"measure point history\"></a>\n";
  if (fs::exists(fs::path(dir) / "load_travel.svg"))
    html += "<h2>Load against travel</h2>\n<a href=\"load_travel.svg\"><img src=\"load_travel.svg\" alt=\"moving "
            "supports: load against travel\"></a>\n";
  if (fs::exists(fs::path(dir) / "run_history.svg"))
    html += "<h2>Solver effort and energy</h2>\n<a href=\"run_history.svg\"><img src=\"run_history.svg\" alt=\"solver effort and energy\"></a>\n";
  if (fs::exists(energy_path)) {
    // The energy balance at the end, the numbers a user checks against the plot (energy.md).
    const NumberTable e = read_number_csv(energy_path);
    if (!e.rows.empty() && e.rows.back().size() >= e.names.size()) {
      html += "<h2>Energy at the end (per m of thickness)</h2>\n<table>\n";
      for (std::size_t c = 2; c < e.names.size(); ++c)
        html += "<tr><th>" + xml_escape(e.names[c]) + "</th><td class=\"n\">" +
                xml_escape(format_engineering(e.rows.back()[c], "J/m")) + "</td></tr>\n";
      html += "</table>\n";
    }
  }
  html += "<h2>Summary</h2>\n<table>\n" + summary_rows(summary, "", 0);
  html += "</table>\n<p>Files: history.csv, summary.json, frames.pvd (open in ParaView)";
  if (fs::exists(fs::path(dir) / "contacts.csv")) html += ", contacts.csv";
  if (fs::exists(fs::path(dir) / "contacts.csv.gz")) html += ", contacts.csv.gz (gzip: zcat)";
  if (fs::exists(fs::path(dir) / "energy.csv")) html += ", energy.csv (docs/energy.md)";
  if (fs::exists(reactions_path)) html += ", reactions.csv";
  html += ".</p>\n</body></html>\n";
  write_file_atomically((fs::path(dir) / "index.html").string(), html);
  files.written.push_back("index.html");
  return files;
}

}  // namespace nmm::report
