// The stable / failing criterion (rules and why in the header).
#include "studies/trial_verdict.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "report/failure_cause.h"
#include "common/error.h"
#include "studies/frame_reader.h"

namespace nmm::studies {
namespace fs = std::filesystem;

namespace {
struct Row {
  double t, x, y;
};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Index of the row whose time is nearest t.
std::size_t nearest(const std::vector<Row>& rows, double t) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (std::abs(rows[i].t - t) < std::abs(rows[best].t - t)) best = i;
  return best;
}

double dist(const Row& a, const Row& b) { return std::hypot(a.x - b.x, a.y - b.y); }

// Measure-point positions from history.csv, by label "point N".
std::map<std::string, std::vector<Row>> point_series(const std::string& out_dir, bool* non_finite) {
  std::map<std::string, std::vector<Row>> series;
  std::ifstream in(fs::path(out_dir) / "history.csv");
  if (!in) throw RunError(out_dir + ": no history.csv (the trial did not run)");
  std::string line;
  std::getline(in, line);  // header: step,time,point,x,y,ux,uy
  while (std::getline(in, line)) {
    long long step = 0;
    int p = 0;
    double t = 0, x = 0, y = 0;
    if (std::sscanf(line.c_str(), "%lld,%lf,%d,%lf,%lf", &step, &t, &p, &x, &y) != 5) continue;
    if (!std::isfinite(x) || !std::isfinite(y)) *non_finite = true;
    series["point " + std::to_string(p)].push_back({t, x, y});
  }
  return series;
}

// Block mean displacements at the frames nearest the trial's start, half, 3/4 and end.
std::map<std::string, std::vector<Row>> block_series(const std::string& out_dir) {
  const auto frames = list_frames(out_dir);
  std::map<std::string, std::vector<Row>> series;
  if (frames.size() < 4) return series;
  const double t0 = frames.front().first, t1 = frames.back().first;
  std::vector<std::size_t> picks;
  for (double s : {0.0, 0.5, 0.75, 1.0}) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < frames.size(); ++i)
      if (std::abs(frames[i].first - (t0 + s * (t1 - t0))) < std::abs(frames[best].first - (t0 + s * (t1 - t0))))
        best = i;
    picks.push_back(best);
  }
  for (std::size_t i : picks) {
    const std::vector<double> u = block_mean_displacement(read_frame(frames[i].second));
    for (std::size_t b = 0; 2 * b + 1 < u.size(); ++b)
      series["block " + std::to_string(b)].push_back({frames[i].first, u[2 * b], u[2 * b + 1]});
  }
  return series;
}

}  // namespace

Watch parse_watch(const std::string& word) {
  if (word == "auto") return Watch::automatic;
  if (word == "points") return Watch::points;
  if (word == "blocks") return Watch::blocks;
  if (word == "both") return Watch::both;
  throw InputError("", "--watch", "unknown '" + word + "' (auto, points, blocks or both)");
}

TrialVerdict judge_trial(const std::string& out_dir, int exit_status, const VerdictCriterion& c) {
  TrialVerdict v;
  std::string stopped;  // why the trial's run stopped ("" when it ended ok)
  {
    std::ifstream in(fs::path(out_dir) / "summary.json");
    if (in) {
      try {
        const Outcome ended = report::run_outcome(nlohmann::json::parse(in));
        if (!ended.ok()) stopped = ended.status();
      } catch (const nlohmann::json::exception&) {
        stopped = "unreadable summary.json";
      }
    } else if (exit_status != 0) {
      stopped = "no summary.json";
    }
  }
  if (exit_status != 0 || !stopped.empty()) {
    v.failing = true;
    v.reason = "run stopped: " + (stopped.empty() ? "exit status " + std::to_string(exit_status) : stopped);
  }
  bool non_finite = false;
  std::map<std::string, std::vector<Row>> series;
  if (c.watch != Watch::blocks) series = point_series(out_dir, &non_finite);
  if (non_finite) {
    v.failing = true;
    v.reason = "non-finite position in history.csv";
    return v;
  }
  if (c.watch == Watch::blocks || c.watch == Watch::both ||
      (c.watch == Watch::automatic && series.empty())) {
    try {
      for (auto& [k, rows] : block_series(out_dir)) series[k] = rows;
    } catch (const RunError&) {
      if (!v.failing) throw;
    }
  }
  if (series.empty()) {
    if (v.failing) return v;
    throw RunError(out_dir + ": nothing to watch (no measure points in history.csv and fewer than "
                   "4 frames; add \"measure_points\" or lower solver.output_every)");
  }
  std::string decided;
  for (const auto& [label, rows] : series) {
    if (rows.size() < 4) {
      if (v.failing) continue;
      throw RunError(out_dir + ": " + label + " has fewer than 4 outputs (lower solver.output_every)");
    }
    const Row& first = rows.front();
    const Row& last = rows.back();
    const double t0 = first.t, t1 = last.t;
    const Row& half = rows[nearest(rows, t0 + 0.5 * (t1 - t0))];
    const Row& q3 = rows[nearest(rows, t0 + 0.75 * (t1 - t0))];
    const double d = dist(last, first);
    const double v_late = q3.t < last.t ? dist(last, q3) / (last.t - q3.t) : 0;
    const double v_mid = half.t < q3.t ? dist(q3, half) / (q3.t - half.t) : 0;
    v.max_displacement = std::max(v.max_displacement, d);
    v.end_velocity = std::max(v.end_velocity, v_late);
    if (v.failing) continue;
    if (c.max_displacement > 0 && d > c.max_displacement) {
      v.failing = true;
      decided = label + " moved " + fmt(d) + " m > limit " + fmt(c.max_displacement) + " m";
    } else if (v_late > c.velocity_floor && v_late > c.decay_ratio * v_mid) {
      v.failing = true;
      decided = label + " still moving: " + fmt(v_late) + " m/s (before: " + fmt(v_mid) +
                " m/s) > floor " + fmt(c.velocity_floor) + " m/s, not slowing to " +
                fmt(c.decay_ratio) + "×";
    }
  }
  if (v.failing && v.reason.empty()) v.reason = decided;
  if (!v.failing)
    v.reason = "everything watched stops or slows down: fastest " + fmt(v.end_velocity) +
               " m/s, moved " + fmt(v.max_displacement) + " m";
  return v;
}

}  // namespace nmm::studies
