// Sweep expansion and collection (file format in the header).
#include "studies/sweep.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/error.h"

namespace nmm::studies {
namespace fs = std::filesystem;

namespace {

std::string text_of(const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

std::vector<std::string> string_list(const nlohmann::json& j, const std::string& path,
                                     const std::string& file) {
  if (!j.is_array()) throw InputError(file, path, "must be a list of strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_string()) throw InputError(file, path + "/" + std::to_string(i), "must be a string");
    const std::string s = j[i].get<std::string>();
    if (s.find('=') == std::string::npos && path.find("outputs") == std::string::npos)
      throw InputError(file, path + "/" + std::to_string(i), "must be PATH=VALUE");
    out.push_back(s);
  }
  return out;
}

// Product of {parameter: [values]} as lists of (parameter, value-text).
std::vector<std::vector<std::pair<std::string, std::string>>> product(const nlohmann::json& j,
                                                                      const std::string& path,
                                                                      const std::string& file) {
  std::vector<std::vector<std::pair<std::string, std::string>>> out{{}};
  if (j.is_null()) return out;
  if (!j.is_object()) throw InputError(file, path, "must be an object {parameter: [values]}");
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (!it.value().is_array() || it.value().empty())
      throw InputError(file, path + "/" + it.key(), "must be a non-empty list of values");
    std::vector<std::vector<std::pair<std::string, std::string>>> next;
    for (const auto& partial : out)
      for (const auto& v : it.value()) {
        auto p = partial;
        p.emplace_back(it.key(), text_of(v));
        next.push_back(p);
      }
    out = next;
  }
  return out;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

Sweep read_sweep(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the sweep file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in, nullptr, true, true);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path, "byte " + std::to_string(e.byte), "not JSON: " + std::string(e.what()));
  }
  if (!j.is_object()) throw InputError(path, "", "must be a JSON object");
  static const char* known[] = {"mesh", "scene", "config", "set", "variants", "product",
                                "preprocess_product", "outputs", "name", "description"};
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool ok = false;
    for (const char* k : known) ok |= it.key() == k;
    if (!ok) throw InputError(path, "/" + it.key(), "unknown key");
  }
  const fs::path base = fs::absolute(path).parent_path();
  auto file_key = [&](const char* key) -> std::string {
    if (!j.contains(key)) return "";
    if (!j[key].is_string()) throw InputError(path, std::string("/") + key, "must be a file name");
    const fs::path p = base / j[key].get<std::string>();
    if (!fs::is_regular_file(p)) throw InputError(path, std::string("/") + key, "no such file: " + p.string());
    return p.string();
  };
  Sweep s;
  s.mesh = file_key("mesh");
  s.scene = file_key("scene");
  s.config = file_key("config");
  if (s.mesh.empty() == s.scene.empty())
    throw InputError(path, "", "give exactly one of \"mesh\" and \"scene\"");
  const std::vector<std::string> common = j.contains("set") ? string_list(j["set"], "/set", path)
                                                            : std::vector<std::string>{};
  struct Listed {
    std::string name;
    std::vector<std::string> sets, pre;
  };
  std::vector<Listed> listed;
  if (j.contains("variants")) {
    const nlohmann::json& v = j["variants"];
    if (!v.is_array() || v.empty()) throw InputError(path, "/variants", "must be a non-empty list");
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string p = "/variants/" + std::to_string(i);
      if (!v[i].is_object()) throw InputError(path, p, "must be an object");
      Listed l;
      l.name = v[i].value("name", "v" + std::to_string(i));
      if (v[i].contains("set")) l.sets = string_list(v[i]["set"], p + "/set", path);
      if (v[i].contains("preprocess_set"))
        l.pre = string_list(v[i]["preprocess_set"], p + "/preprocess_set", path);
      listed.push_back(l);
    }
  } else {
    listed.push_back({});
  }
  const auto prod = product(j.value("product", nlohmann::json()), "/product", path);
  const auto pre_prod = product(j.value("preprocess_product", nlohmann::json()), "/preprocess_product", path);
  if (j.contains("variants") && listed.size() > 1) s.parameters.push_back("variant");
  if (j.contains("product"))
    for (auto it = j["product"].begin(); it != j["product"].end(); ++it) s.parameters.push_back(it.key());
  if (j.contains("preprocess_product"))
    for (auto it = j["preprocess_product"].begin(); it != j["preprocess_product"].end(); ++it)
      s.parameters.push_back("preprocess:" + it.key());
  int n = 0;
  for (const Listed& l : listed)
    for (const auto& p : prod)
      for (const auto& pp : pre_prod) {
        SweepRun r;
        char id[16];
        std::snprintf(id, sizeof id, "r%04d", ++n);
        r.id = id;
        r.sets = common;
        for (const auto& s2 : l.sets) r.sets.push_back(s2);
        r.preprocess_sets = l.pre;
        std::string name = l.name;
        if (listed.size() > 1) r.values.emplace_back("variant", l.name);
        for (const auto& [k, v] : p) {
          r.sets.push_back(k + "=" + v);
          r.values.emplace_back(k, v);
          name += (name.empty() ? "" : " ") + k + "=" + v;
        }
        for (const auto& [k, v] : pp) {
          r.preprocess_sets.push_back(k + "=" + v);
          r.values.emplace_back("preprocess:" + k, v);
          name += (name.empty() ? "" : " ") + k + "=" + v;
        }
        r.name = name.empty() ? "base" : name;
        if (!r.preprocess_sets.empty() && s.scene.empty())
          throw InputError(path, "/mesh", "runs with preprocess_set need a \"scene\", not a mesh");
        s.runs.push_back(r);
      }
  if (s.runs.size() > 100000) throw InputError(path, "", "more than 100000 runs");
  s.summary_outputs = {"status", "steps_completed", "simulated_time"};
  if (j.contains("outputs")) {
    const nlohmann::json& o = j["outputs"];
    if (!o.is_object()) throw InputError(path, "/outputs", "must be an object");
    if (o.contains("summary")) s.summary_outputs = string_list(o["summary"], "/outputs/summary", path);
    if (o.contains("history")) s.history_outputs = string_list(o["history"], "/outputs/history", path);
  }
  return s;
}

std::vector<Job> sweep_jobs(const Sweep& sweep, const std::string& root, const std::string& base_mesh,
                            const std::string& solve, const std::string& preprocess) {
  std::vector<Job> jobs;
  for (const SweepRun& r : sweep.runs) {
    Job job;
    job.id = r.id;
    const fs::path dir = fs::path(root) / "runs" / r.id;
    std::string mesh = base_mesh;
    if (!r.preprocess_sets.empty()) {
      mesh = (dir / "mesh.nmm").string();
      std::vector<std::string> pre = {preprocess, sweep.scene, "-o", mesh};
      for (const auto& s : r.preprocess_sets) {
        pre.push_back("--set");
        pre.push_back(s);
      }
      job.commands.push_back(pre);
    }
    std::vector<std::string> cmd = {solve, mesh, "-o", (dir / "out").string(), "--quiet"};
    if (!sweep.config.empty()) {
      cmd.push_back("--config");
      cmd.push_back(sweep.config);
    }
    for (const auto& s : r.sets) {
      cmd.push_back("--set");
      cmd.push_back(s);
    }
    job.commands.push_back(cmd);
    jobs.push_back(job);
  }
  return jobs;
}

std::string sweep_csv(const Sweep& sweep, const std::string& root, const std::vector<JobResult>& results) {
  // History: last row per point of the wanted columns; the header names the points seen.
  std::vector<std::map<int, std::map<std::string, std::string>>> last(sweep.runs.size());
  std::vector<int> points;
  for (std::size_t i = 0; i < sweep.runs.size(); ++i) {
    std::ifstream in(fs::path(root) / "runs" / sweep.runs[i].id / "out" / "history.csv");
    std::string line;
    if (!in || !std::getline(in, line)) continue;
    std::vector<std::string> cols;
    {
      std::stringstream ss(line);
      std::string c;
      while (std::getline(ss, c, ',')) cols.push_back(c);
    }
    while (std::getline(in, line)) {
      std::stringstream ss(line);
      std::string c;
      std::map<std::string, std::string> row;
      for (std::size_t k = 0; std::getline(ss, c, ',') && k < cols.size(); ++k) row[cols[k]] = c;
      if (!row.count("point")) continue;
      const int p = std::atoi(row["point"].c_str());
      last[i][p] = row;
      if (std::find(points.begin(), points.end(), p) == points.end()) points.push_back(p);
    }
  }
  std::sort(points.begin(), points.end());
  std::string out = "run,name";
  for (const auto& p : sweep.parameters) out += "," + csv_field(p);
  out += ",exit,run_status,job_wall_seconds";
  for (const auto& k : sweep.summary_outputs) out += "," + csv_field("summary." + k);
  for (int p : points)
    for (const auto& k : sweep.history_outputs) out += ",history." + k + ".p" + std::to_string(p);
  out += "\n";
  for (std::size_t i = 0; i < sweep.runs.size(); ++i) {
    const SweepRun& r = sweep.runs[i];
    out += r.id + "," + csv_field(r.name);
    for (const auto& p : sweep.parameters) {
      std::string v;
      for (const auto& [k, val] : r.values)
        if (k == p) v = val;
      out += "," + csv_field(v);
    }
    nlohmann::json summary;
    {
      std::ifstream in(fs::path(root) / "runs" / r.id / "out" / "summary.json");
      if (in) try {
          summary = nlohmann::json::parse(in);
        } catch (const nlohmann::json::exception&) {
        }
    }
    const int ex = results[i].exit_status;
    std::string status = ex == 0 ? "ok" : ex == 2 ? "bad input" : ex == 3 ? "stopped" : "failed";
    if (summary.is_object() && summary.contains("status")) status = text_of(summary["status"]);
    else if (ex == 2) status = "bad input (see runs/" + r.id + "/log.txt)";
    char wall[32];
    std::snprintf(wall, sizeof wall, "%.3f", results[i].wall_seconds);
    out += "," + std::to_string(ex) + "," + csv_field(status) + "," + wall;
    for (const auto& k : sweep.summary_outputs) {
      std::string v;
      if (summary.is_object()) try {
        const nlohmann::json::json_pointer ptr("/" + [&] {
          std::string s2 = k;
          for (char& c : s2)
            if (c == '.') c = '/';
          return s2;
        }());
        if (summary.contains(ptr)) v = text_of(summary[ptr]);
      } catch (const nlohmann::json::exception&) {
      }
      out += "," + csv_field(v);
    }
    for (int p : points)
      for (const auto& k : sweep.history_outputs) {
        std::string v;
        if (last[i].count(p) && last[i][p].count(k)) v = last[i][p][k];
        out += "," + csv_field(v);
      }
    out += "\n";
  }
  return out;
}

}  // namespace nmm::studies
