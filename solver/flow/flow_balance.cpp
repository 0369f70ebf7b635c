// The volume balance of the flow network over one step: see flow_balance.h (equations there).
#include "solver/flow/flow_balance.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "common/error.h"
#include "common/time_table.h"

namespace nmm::solve {

struct FlowBalance::Solver {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  bool analysed = false;
};

namespace {

std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

FlowBalance::FlowBalance(const FlowNetwork& network, const SceneDef& scene, const std::string& scene_name)
    : network_(network), flow_(scene.flow), solver_(std::make_unique<Solver>()) {
  if (scene.has_gravity) {
    gx_ = scene.gravity.x;
    gy_ = scene.gravity.y;
  }
  const std::size_t n = network.nodes();
  const std::vector<std::int32_t>& fixed = network.node_boundary();
  std::vector<char> pinned(n, 0);
  if (flow_.steady) {
    // Pieces of the network (joints connected through nodes) with no fixed node.
    std::vector<std::size_t> parent(n);
    std::iota(parent.begin(), parent.end(), std::size_t{0});
    for (const FlowSegment& s : network.segments())
      parent[root(parent, static_cast<std::size_t>(s.a))] = root(parent, static_cast<std::size_t>(s.b));
    std::vector<char> held(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      if (fixed[i] >= 0) held[root(parent, i)] = 1;
    for (std::size_t i = 0; i < n; ++i) pinned[i] = held[root(parent, i)] ? 0 : 1;
    const auto& shares = network.injection_shares();
    for (std::size_t k = 0; k < shares.size(); ++k)
      if (pinned[static_cast<std::size_t>(shares[k].a)])
        throw InputError(scene_name, "/flow/injections/" + std::to_string(k),
                         "steady flow: the injection's joints reach no \"boundaries\" entry, so they have "
                         "no steady state (use \"steady\": false)");
  }
  unknown_.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    if (fixed[i] < 0 && !pinned[i]) unknown_[i] = unknowns_++;
}

FlowBalance::~FlowBalance() = default;

FlowStepResult FlowBalance::step(const std::vector<double>& p0, const std::vector<double>& conductance,
                                 const std::vector<double>& volume, double dt, double t_end,
                                 const FlowStorage* moving, const std::vector<double>* void0) {
  const std::size_t n = network_.nodes();
  const std::vector<std::int32_t>& fixed = network_.node_boundary();
  const std::vector<double>& xy = network_.node_xy();
  const double rho = flow_.density, kf = flow_.bulk_modulus;
  const bool storage = !flow_.steady;
  const bool lag = storage && flow_.cavitation && void0 && void0->size() == n;
  const double pc = flow_.cavitation_pressure;
  FlowStepResult r;
  r.pressure = p0;
  for (std::size_t i = 0; i < n; ++i)
    if (fixed[i] >= 0) r.pressure[i] = table_value(flow_.boundaries[static_cast<std::size_t>(fixed[i])].pressure, t_end, 0.0);
  // ρ_f·g·(x_i − x_j): the weight term of φ_i − φ_j = p_i − p_j − ρ_f·g·(x_i − x_j).
  auto weight = [&](std::size_t i, std::size_t j) {
    return rho * (gx_ * (xy[2 * i] - xy[2 * j]) + gy_ * (xy[2 * i + 1] - xy[2 * j + 1]));
  };
  std::vector<double> q(n, 0.0);  // m³/s per m into each node from the injections
  double injected_rate = 0;
  for (std::size_t k = 0; k < network_.injection_shares().size(); ++k) {
    const FlowNetwork::Share& sh = network_.injection_shares()[k];
    const double rate = table_value(flow_.injections[k].rate, t_end, 0.0);
    q[static_cast<std::size_t>(sh.a)] += sh.wa * rate;
    q[static_cast<std::size_t>(sh.b)] += sh.wb * rate;
    injected_rate += rate;
  }
  // The lag's active set (header): a node that holds vapour at the start starts in it.
  std::vector<char> in_lag(n, 0);
  if (lag) {
    r.void_volume.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      if (unknown_[i] >= 0 && (*void0)[i] > 0) in_lag[i] = 1;
  }
  // The fluid M_i(p) − M⁰_i + c_i·(p − p^k) the node's storage takes at pressure p, before the vapour.
  auto taken = [&](std::size_t i, double p) {
    if (moving)
      return (volume[i] - moving->volume0[i]) * (1 + p0[i] / kf) + (volume[i] / kf + moving->compliance[i]) * (p - p0[i]) -
             moving->compliance[i] * (moving->iterate[i] - p0[i]);
    return volume[i] / kf * (p - p0[i]);
  };
  for (int round = 0; unknowns_ > 0; ++round) {
    std::vector<Eigen::Triplet<double>> t;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(unknowns_);
    for (std::size_t i = 0; i < n; ++i) {
      const int k = unknown_[i];
      if (k < 0) continue;
      if (in_lag[i]) {  // held at p_c: the identity row
        t.emplace_back(k, k, 1.0);
        b[k] = pc;
        continue;
      }
      b[k] += q[i];
      if (storage && moving) {
        const double c = moving->compliance[i];
        t.emplace_back(k, k, (volume[i] / kf + c) / dt);
        b[k] += ((volume[i] / kf + c) * p0[i] - (volume[i] - moving->volume0[i]) * (1 + p0[i] / kf) +
                 c * (moving->iterate[i] - p0[i])) /
                dt;
      } else if (storage) {
        const double s = volume[i] / kf / dt;
        t.emplace_back(k, k, s);
        b[k] += s * p0[i];
      }
      if (lag) b[k] -= (*void0)[i] / dt;  // the vapour the start held fills first
    }
    for (std::size_t s = 0; s < network_.segments().size(); ++s) {
      const FlowSegment& sg = network_.segments()[s];
      const double c = conductance[s];
      const auto i = static_cast<std::size_t>(sg.a), j = static_cast<std::size_t>(sg.b);
      const int ki = unknown_[i], kj = unknown_[j];
      const double w = weight(i, j);  // flow i → j: c·(p_i − p_j − w)
      // Rows of lag nodes keep their entries' places with zeros (the analysed pattern).
      if (ki >= 0) {
        if (in_lag[i]) {
          t.emplace_back(ki, ki, 0.0);
          if (kj >= 0) t.emplace_back(ki, kj, 0.0);
        } else {
          t.emplace_back(ki, ki, c);
          b[ki] += c * w;
          if (kj >= 0) {
            if (in_lag[j]) t.emplace_back(ki, kj, 0.0), b[ki] += c * pc;
            else t.emplace_back(ki, kj, -c);
          } else {
            b[ki] += c * r.pressure[j];
          }
        }
      }
      if (kj >= 0) {
        if (in_lag[j]) {
          t.emplace_back(kj, kj, 0.0);
          if (ki >= 0) t.emplace_back(kj, ki, 0.0);
        } else {
          t.emplace_back(kj, kj, c);
          b[kj] -= c * w;
          if (ki >= 0) {
            if (in_lag[i]) t.emplace_back(kj, ki, 0.0), b[kj] += c * pc;
            else t.emplace_back(kj, ki, -c);
          } else {
            b[kj] += c * r.pressure[i];
          }
        }
      }
    }
    Eigen::SparseMatrix<double> a(unknowns_, unknowns_);
    a.setFromTriplets(t.begin(), t.end());
    if (!solver_->analysed) {
      solver_->ldlt.analyzePattern(a);
      solver_->analysed = true;
    }
    solver_->ldlt.factorize(a);
    const Eigen::VectorXd p = solver_->ldlt.solve(b);
    for (std::size_t i = 0; i < n; ++i)
      if (unknown_[i] >= 0) r.pressure[i] = p[unknown_[i]];
    if (!lag) break;
    ++r.lag_solves;
    // The vapour each lag node is left with: s_i = M_i(p_c) − M⁰_i + s⁰_i + c_i·(p_c − p^k) − Δt·(Q_i − Σ flows out).
    std::vector<double> out(n, 0.0);  // m³/s per m leaving each node along its segments
    for (std::size_t s = 0; s < network_.segments().size(); ++s) {
      const FlowSegment& sg = network_.segments()[s];
      const auto i = static_cast<std::size_t>(sg.a), j = static_cast<std::size_t>(sg.b);
      const double flow = conductance[s] * (r.pressure[i] - r.pressure[j] - weight(i, j));
      out[i] += flow;
      out[j] -= flow;
    }
    bool moved = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (unknown_[i] < 0) continue;
      if (in_lag[i]) {
        r.void_volume[i] = taken(i, pc) + (*void0)[i] - dt * (q[i] - out[i]);
        if (r.void_volume[i] < 0) in_lag[i] = 0, moved = true;
      } else {
        r.void_volume[i] = 0;
        if (r.pressure[i] < pc) in_lag[i] = 1, moved = true;
      }
    }
    // An M-matrix settles in at most a few passes per node; past that, round-off flips a node
    // whose vapour is within it of zero: keep the last set (its vapour ≥ 0 is clamped by ≤ that).
    if (!moved || round > static_cast<int>(n) + 8) {
      for (double& v : r.void_volume) v = std::max(v, 0.0);
      break;
    }
  }
  // What flows into the boundaries' nodes, and what the free nodes came to hold.
  r.outflow_rate.assign(flow_.boundaries.size(), 0.0);
  for (std::size_t s = 0; s < network_.segments().size(); ++s) {
    const FlowSegment& sg = network_.segments()[s];
    const auto i = static_cast<std::size_t>(sg.a), j = static_cast<std::size_t>(sg.b);
    const double flow = conductance[s] * (r.pressure[i] - r.pressure[j] - weight(i, j));  // i → j
    if (fixed[j] >= 0) r.outflow_rate[static_cast<std::size_t>(fixed[j])] += flow;
    if (fixed[i] >= 0) r.outflow_rate[static_cast<std::size_t>(fixed[i])] -= flow;
  }
  // An injection at a boundary's node leaves through that boundary at once.
  for (std::size_t i = 0; i < n; ++i)
    if (fixed[i] >= 0) r.outflow_rate[static_cast<std::size_t>(fixed[i])] += q[i];
  for (double rate : r.outflow_rate) {
    r.outflow += rate * dt;
    r.exchanged += std::abs(rate) * dt;
  }
  r.injected = injected_rate * dt;
  r.exchanged += std::abs(injected_rate) * dt;
  if (storage && moving) {
    for (std::size_t i = 0; i < n; ++i)
      if (unknown_[i] >= 0)
        r.stored += (volume[i] - moving->volume0[i]) * (1 + p0[i] / kf) + volume[i] / kf * (r.pressure[i] - p0[i]);
  } else if (storage) {
    for (std::size_t i = 0; i < n; ++i)
      if (unknown_[i] >= 0) r.stored += volume[i] / kf * (r.pressure[i] - p0[i]);
  }
  if (lag)  // the fluid: less the vapour's change
    for (std::size_t i = 0; i < n; ++i)
      if (unknown_[i] >= 0) r.stored -= r.void_volume[i] - (*void0)[i];
  return r;
}

}  // namespace nmm::solve
