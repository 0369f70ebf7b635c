// The stable / failing criterion (rules and why in the header).
#include "trial_verdict.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "error.h"

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
}  // namespace

TrialVerdict judge_trial(const std::string& out_dir, int exit_status, const VerdictCriterion& c) {
  TrialVerdict v;
  std::string status = "ok";
  {
    std::ifstream in(fs::path(out_dir) / "summary.json");
    if (in) {
      try {
        status = nlohmann::json::parse(in).value("status", std::string("ok"));
      } catch (const nlohmann::json::exception&) {
        status = "unreadable summary.json";
      }
    } else if (exit_status != 0) {
      status = "no summary.json";
    }
  }
  std::map<int, std::vector<Row>> points;
  std::ifstream in(fs::path(out_dir) / "history.csv");
  if (!in) throw RunError(out_dir + ": no history.csv (the trial did not run)");
  std::string line;
  std::getline(in, line);  // header: step,time,point,x,y,ux,uy
  while (std::getline(in, line)) {
    long long step = 0;
    int p = 0;
    double t = 0, x = 0, y = 0;
    if (std::sscanf(line.c_str(), "%lld,%lf,%d,%lf,%lf", &step, &t, &p, &x, &y) != 5) continue;
    if (!std::isfinite(x) || !std::isfinite(y)) {
      v.failing = true;
      v.reason = "non-finite position in history.csv";
      return v;
    }
    points[p].push_back({t, x, y});
  }
  if (exit_status != 0 || status != "ok") {
    v.failing = true;
    v.reason = "run stopped: " + status;
  }
  if (points.empty()) {
    if (v.failing) return v;
    throw RunError(out_dir + "/history.csv: no measure points (add \"measure_points\" to the scene "
                   "or --set measure_points=[[x,y]])");
  }
  std::string decided;
  for (const auto& [p, rows] : points) {
    if (rows.size() < 4) {
      if (v.failing) continue;
      throw RunError(out_dir + "/history.csv: point " + std::to_string(p) +
                     " has fewer than 4 output rows (lower solver.output_every)");
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
      decided = "point " + std::to_string(p) + " moved " + fmt(d) + " m > limit " +
                fmt(c.max_displacement) + " m";
    } else if (v_late > c.velocity_floor && v_late > c.decay_ratio * v_mid) {
      v.failing = true;
      decided = "point " + std::to_string(p) + " still moving: " + fmt(v_late) + " m/s (before: " +
                fmt(v_mid) + " m/s) > floor " + fmt(c.velocity_floor) + " m/s, not slowing to " + fmt(c.decay_ratio) + "×";
    }
  }
  if (v.failing && v.reason.empty()) v.reason = decided;
  if (!v.failing)
    v.reason = "every point stops or slows down: fastest " + fmt(v.end_velocity) + " m/s, moved " +
               fmt(v.max_displacement) + " m";
  return v;
}

}  // namespace nmm::studies
