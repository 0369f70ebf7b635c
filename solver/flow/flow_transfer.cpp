// The flow state carried onto a re-cut mesh: see flow_transfer.h (the rules there).
#include "solver/flow/flow_transfer.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

namespace nmm::solve {

namespace {

// The segment of `net` that (x, y) lies on within tol, and its position t in [0, 1] from a to b;
// -1 if none. Segments of joint `joint` only when joint ≥ 0.
std::int32_t segment_through(const FlowNetwork& net, double x, double y, double tol, std::int32_t joint, double& t) {
  const std::vector<double>& xy = net.node_xy();
  for (std::size_t k = 0; k < net.segments().size(); ++k) {
    const FlowSegment& sg = net.segments()[k];
    if (joint >= 0 && sg.joint != joint) continue;
    const double ax = xy[2 * static_cast<std::size_t>(sg.a)], ay = xy[2 * static_cast<std::size_t>(sg.a) + 1];
    const double dx = xy[2 * static_cast<std::size_t>(sg.b)] - ax, dy = xy[2 * static_cast<std::size_t>(sg.b) + 1] - ay;
    const double l2 = dx * dx + dy * dy;
    if (!(l2 > 0)) continue;
    const double u = ((x - ax) * dx + (y - ay) * dy) / l2;
    if (u < -tol / std::sqrt(l2) || u > 1 + tol / std::sqrt(l2)) continue;
    if (std::abs((x - ax) * dy - (y - ay) * dx) / std::sqrt(l2) > tol) continue;
    t = std::clamp(u, 0.0, 1.0);
    return static_cast<std::int32_t>(k);
  }
  return -1;
}

// m³ per m: the fluid the free nodes hold, Σ V_i·(1 + p_i/K_f) − s_i (s the vapour, if any).
double content(const FlowNetwork& net, const std::vector<double>& p, const std::vector<double>& ap,
               const std::vector<double>& vapour, double kf) {
  const std::vector<double> v = net.volumes(ap);
  double sum = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (net.node_boundary()[i] < 0) sum += v[i] * (1 + p[i] / kf) - (vapour.empty() ? 0.0 : vapour[i]);
  return sum;
}

}  // namespace

void transfer_flow(const FlowNetwork& before, const FlowNetwork& now, const FlowDef& flow, double tol, RunState& s) {
  if (s.flow_pressure.size() != before.nodes() || s.flow_aperture.size() != 2 * before.segments().size()) return;
  const std::vector<double>& old_p = s.flow_pressure;
  const std::vector<double>& old_ap = s.flow_aperture;
  const std::vector<double>& oxy = before.node_xy();
  const std::vector<double>& nxy = now.node_xy();
  const std::size_t n = now.nodes();
  const bool lag = flow.cavitation && s.flow_void.size() == before.nodes();
  // The share of each old node's room the vapour takes (the lag: flow_balance.h).
  std::vector<double> old_dry(before.nodes(), 0.0);
  if (lag) {
    const std::vector<double> v = before.volumes(old_ap);
    for (std::size_t j = 0; j < old_dry.size(); ++j) {
      const double room = v[j] * (1 + old_p[j] / flow.bulk_modulus);
      old_dry[j] = room > 0 ? std::clamp(s.flow_void[j] / room, 0.0, 1.0) : 0.0;
    }
  }
  std::vector<double> p(n, flow.initial_pressure), dry(n, 0.0);
  std::vector<char> known(n, 0);
  std::vector<std::int32_t> was(n, -1);  // the node before at the same place
  std::vector<std::pair<double, std::int32_t>> by_x(before.nodes());
  for (std::size_t j = 0; j < by_x.size(); ++j) by_x[j] = {oxy[2 * j], static_cast<std::int32_t>(j)};
  std::sort(by_x.begin(), by_x.end());
  for (std::size_t i = 0; i < n; ++i) {
    const double x = nxy[2 * i], y = nxy[2 * i + 1];
    // A node where a node was (the usual case: the re-cut keeps every old vertex in place).
    for (auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(x - tol, std::int32_t{-1}));
         it != by_x.end() && it->first <= x + tol && !known[i]; ++it) {
      const auto j = static_cast<std::size_t>(it->second);
      if (std::hypot(oxy[2 * j] - x, oxy[2 * j + 1] - y) <= tol)
        p[i] = old_p[j], dry[i] = old_dry[j], known[i] = 1, was[i] = it->second;
    }
    if (known[i]) continue;
    double t = 0;
    const std::int32_t k = segment_through(before, x, y, tol, -1, t);
    if (k < 0) continue;
    const FlowSegment& sg = before.segments()[static_cast<std::size_t>(k)];
    p[i] = (1 - t) * old_p[static_cast<std::size_t>(sg.a)] + t * old_p[static_cast<std::size_t>(sg.b)];
    dry[i] = (1 - t) * old_dry[static_cast<std::size_t>(sg.a)] + t * old_dry[static_cast<std::size_t>(sg.b)];
    known[i] = 1;
  }
  // Nodes of new cracks: breadth first from the nodes carried over, along the new segments.
  std::vector<std::vector<std::int32_t>> next(n);
  for (const FlowSegment& sg : now.segments()) {
    next[static_cast<std::size_t>(sg.a)].push_back(sg.b);
    next[static_cast<std::size_t>(sg.b)].push_back(sg.a);
  }
  std::deque<std::int32_t> queue;
  for (std::size_t i = 0; i < n; ++i)
    if (known[i]) queue.push_back(static_cast<std::int32_t>(i));
  while (!queue.empty()) {
    const std::size_t i = static_cast<std::size_t>(queue.front());
    queue.pop_front();
    for (const std::int32_t j : next[i])
      if (!known[static_cast<std::size_t>(j)]) {
        known[static_cast<std::size_t>(j)] = 1;
        // With a lag a new crack opens dry: vapour at p_c, its fluid what flows in later.
        p[static_cast<std::size_t>(j)] = lag ? flow.cavitation_pressure : p[i];
        dry[static_cast<std::size_t>(j)] = 1;
        queue.push_back(j);
      }
  }
  // Apertures: a piece of an old segment of the same joint keeps its aperture, linear along it.
  std::map<std::tuple<std::int32_t, std::int32_t, std::int32_t>, std::int32_t> old_segment;
  for (std::size_t k = 0; k < before.segments().size(); ++k) {
    const FlowSegment& sg = before.segments()[k];
    old_segment[{sg.a, sg.b, sg.joint}] = static_cast<std::int32_t>(k);
  }
  std::vector<double> ap(2 * now.segments().size(), flow.residual);
  for (std::size_t k = 0; k < now.segments().size(); ++k) {
    const FlowSegment& sg = now.segments()[k];
    const std::size_t ends[2] = {static_cast<std::size_t>(sg.a), static_cast<std::size_t>(sg.b)};
    const std::int32_t wa = was[ends[0]], wb = was[ends[1]];
    if (wa >= 0 && wb >= 0) {  // a segment that was: its apertures, end for end
      const auto it = old_segment.find({std::min(wa, wb), std::max(wa, wb), sg.joint});
      if (it != old_segment.end()) {
        const auto o = static_cast<std::size_t>(it->second);
        const bool same = wa < wb;
        ap[2 * k] = old_ap[2 * o + (same ? 0 : 1)];
        ap[2 * k + 1] = old_ap[2 * o + (same ? 1 : 0)];
        continue;
      }
    }
    const double mx = 0.5 * (nxy[2 * ends[0]] + nxy[2 * ends[1]]), my = 0.5 * (nxy[2 * ends[0] + 1] + nxy[2 * ends[1] + 1]);
    double t = 0;
    const std::int32_t o = segment_through(before, mx, my, tol, sg.joint, t);
    if (o < 0) continue;  // a new crack's segment
    const FlowSegment& os = before.segments()[static_cast<std::size_t>(o)];
    const double ox = oxy[2 * static_cast<std::size_t>(os.a)], oy = oxy[2 * static_cast<std::size_t>(os.a) + 1];
    const double dx = oxy[2 * static_cast<std::size_t>(os.b)] - ox, dy = oxy[2 * static_cast<std::size_t>(os.b) + 1] - oy;
    const double l2 = dx * dx + dy * dy;
    for (int e = 0; e < 2; ++e) {
      const double u = std::clamp(((nxy[2 * ends[e]] - ox) * dx + (nxy[2 * ends[e] + 1] - oy) * dy) / l2, 0.0, 1.0);
      ap[2 * k + static_cast<std::size_t>(e)] = (1 - u) * old_ap[2 * static_cast<std::size_t>(o)] + u * old_ap[2 * static_cast<std::size_t>(o) + 1];
    }
  }
  std::vector<double> vapour;
  if (lag) {
    vapour = now.volumes(ap);
    for (std::size_t i = 0; i < n; ++i)
      vapour[i] = now.node_boundary()[i] >= 0 ? 0.0 : dry[i] * vapour[i] * (1 + p[i] / flow.bulk_modulus);
  }
  if (!flow.steady)
    s.flow_filled += content(now, p, ap, vapour, flow.bulk_modulus) -
                     content(before, old_p, old_ap, lag ? s.flow_void : std::vector<double>{}, flow.bulk_modulus);
  if (lag) s.flow_void = std::move(vapour);
  s.flow_pressure = std::move(p);
  s.flow_aperture = std::move(ap);
}

}  // namespace nmm::solve
