// Fluid flow along the joints as an effect of the step: see flow_effect.h (the scheme there).
//
// The face load (boundary_conditions.h): on a face edge from vertex A to B with outward normal n
// and the pressure linear between its nodes, t(ξ) = −((1 − ξ)·p_A + ξ·p_B)·n, ξ the position
// along the edge; the Gauss rule of the element's edge frame integrates it exactly. The work it
// does on the accepted step is load·d (J/m; energy.csv's load work: docs/energy.md).
#include "solver/flow/flow_effect.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "solver/discretisation/boundary_conditions.h"
#include "solver/discretisation/integrators.h"
#include "solver/discretisation/state_bytes.h"
#include "solver/flow/flow_transfer.h"
#include "solver/fracture/crack_release.h"

namespace nmm::solve {

FlowEffect::FlowEffect(const Model& model, const CoverSpace& space) : model_(model), space_(space) {
  if (!active()) return;
  network_ = FlowNetwork(model.mesh(), model.scene(), model.scene_name());
  balance_ = std::make_unique<FlowBalance>(network_, model.scene(), model.scene_name());
  for (const FlowSegment& sg : network_.segments()) {
    if (joint_length_.size() <= static_cast<std::size_t>(sg.joint)) joint_length_.resize(static_cast<std::size_t>(sg.joint) + 1, 0.0);
    joint_length_[static_cast<std::size_t>(sg.joint)] += sg.length;
  }
  segment_modulus_.assign(network_.segments().size(), 0.0);
  for (const FlowFace& face : network_.faces())
    segment_modulus_[static_cast<std::size_t>(face.segment)] =
        std::max(segment_modulus_[static_cast<std::size_t>(face.segment)], model.elasticity(static_cast<std::size_t>(face.element))(0, 0));
  const std::vector<std::int32_t>& offset = model.mesh().element_loop_offset;
  for (const FlowFaceVertex& fv : network_.end_vertices())
    vertex_element_.push_back(
        static_cast<std::int32_t>(std::upper_bound(offset.begin(), offset.end(), fv.vertex) - offset.begin() - 1));
}

FlowEffect::~FlowEffect() = default;

bool FlowEffect::install(RunState& s, const std::string& name) {
  if (!active()) {
    s.flow_pressure.clear();
    s.flow_aperture.clear();
    s.flow_void.clear();
    s.flow_outflow_rate.clear();
    s.flow_injected = s.flow_outflow = s.flow_stored = s.flow_load_work = s.flow_exchanged = 0;
    return true;
  }
  const FlowDef& f = model_.scene().flow;
  if (s.flow_pressure.empty()) {  // the flow starts now
    s.flow_pressure.assign(network_.nodes(), f.initial_pressure);
    s.flow_aperture = network_.apertures(s.loop_u, f.residual, f.max_aperture);
    s.flow_void.clear();
    if (f.cavitation) {  // filled at the start, or all vapour (initially_dry: p = p_c)
      s.flow_void.assign(network_.nodes(), 0.0);
      if (f.initially_dry) {
        const std::vector<double> v = network_.volumes(s.flow_aperture);
        for (std::size_t i = 0; i < v.size(); ++i)
          if (network_.node_boundary()[i] < 0) s.flow_void[i] = v[i] * (1 + f.cavitation_pressure / f.bulk_modulus);
      }
    }
    s.flow_outflow_rate.assign(f.boundaries.size(), 0.0);
    s.flow_injected = s.flow_outflow = s.flow_stored = s.flow_load_work = s.flow_exchanged = 0;
    return true;
  }
  if (s.flow_pressure.size() != network_.nodes() || s.flow_aperture.size() != 2 * network_.segments().size())
    throw InputError(name, "section FLOW",
                     "the flow network has " + std::to_string(s.flow_pressure.size()) + " nodes and " +
                         std::to_string(s.flow_aperture.size() / 2) + " segments, the run's " +
                         std::to_string(network_.nodes()) + " and " + std::to_string(network_.segments().size()));
  s.flow_outflow_rate.resize(f.boundaries.size(), 0.0);  // a restart may give other boundaries
  // A restart that gives the fluid a cavitation pressure starts its lag filled; one that drops it
  // keeps the fluid as it is and forgets the vapour.
  if (f.cavitation) s.flow_void.resize(network_.nodes(), 0.0);
  else s.flow_void.clear();
  return true;
}

void FlowEffect::continue_from(const FlowEffect& before, RunState& s) const {
  if (!active() || !before.active()) return;
  transfer_flow(before.network_, network_, model_.scene().flow, 1e-6 * model_.mesh().mesh_size, s);
}

void FlowEffect::checkpoint_sections(const RunState& s, const Mesh& /*mesh*/, CheckpointSections& sections) const {
  if (s.flow_pressure.empty()) return;  // without flow the checkpoint keeps the bytes of a run without
  ByteWriter w;
  w.put_vector(s.flow_pressure);
  w.put_vector(s.flow_aperture);
  w.put_vector(s.flow_outflow_rate);
  w.put(s.flow_injected);
  w.put(s.flow_outflow);
  w.put(s.flow_stored);
  w.put(s.flow_load_work);
  w.put(s.flow_exchanged);
  // Only once cracks took in fluid (flow_transfer.h): runs without cracks keep their bytes.
  if (s.flow_filled != 0 || !s.flow_void.empty()) w.put(s.flow_filled);
  // Only with a fluid lag (cavitation_pressure): the vapour per node.
  if (!s.flow_void.empty()) w.put_vector(s.flow_void);
  sections.emplace_back("FLOW", w.take());
}

void FlowEffect::restore_sections(const CheckpointSections& sections, const Mesh& /*mesh*/, const std::string& name,
                                  RunState& s) const {
  const auto it = std::find_if(sections.begin(), sections.end(), [](const auto& x) { return x.first == "FLOW"; });
  if (it == sections.end()) return;
  ByteReader r(it->second, name, "FLOW");
  s.flow_pressure = r.get_vector<double>(SIZE_MAX, "flow pressures");
  s.flow_aperture = r.get_vector<double>(SIZE_MAX, "flow apertures");
  s.flow_outflow_rate = r.get_vector<double>(SIZE_MAX, "flow boundary rates");
  s.flow_injected = r.get<double>();
  s.flow_outflow = r.get<double>();
  s.flow_stored = r.get<double>();
  s.flow_load_work = r.get<double>();
  s.flow_exchanged = r.get<double>();
  s.flow_filled = r.at_end() ? 0.0 : r.get<double>();
  s.flow_void = r.at_end() ? std::vector<double>{} : r.get_vector<double>(SIZE_MAX, "flow vapour volumes");
  double sum = s.flow_injected + s.flow_outflow + s.flow_stored + s.flow_load_work + s.flow_exchanged + s.flow_filled;
  for (double v : s.flow_void) sum += v;
  for (const auto* v : {&s.flow_pressure, &s.flow_aperture, &s.flow_outflow_rate})
    for (double x : *v) sum += x;
  if (s.flow_pressure.empty() || !std::isfinite(sum)) r.fail("no flow pressures, or a value that is not finite");
  r.expect_end();
}

void FlowEffect::face_pressures(const RunState& s, std::vector<double>& pressure) const {
  if (!active() || !model_.scene().flow.coupled || s.flow_pressure.empty()) return;
  const std::vector<double> p = network_.face_pressures(s.flow_pressure, pressure.size() / 2);
  for (std::size_t i = 0; i < p.size() && i < pressure.size(); ++i) pressure[i] += p[i];
}

Outcome FlowEffect::begin_step(EffectStep& step) {
  const FlowDef& f = model_.scene().flow;
  const RunState& s = step.s;
  aperture_ = f.coupled && f.steady ? network_.apertures(s.loop_u, f.residual, f.max_aperture) : s.flow_aperture;
  step_ = balance_->step(s.flow_pressure, network_.conductances(aperture_, f.viscosity), network_.volumes(aperture_),
                         step.context.dt, step.context.t_end, nullptr, lag_start(s));
  for (double p : step_.pressure)
    if (!std::isfinite(p))
      return Outcome::stop(StopCode::direction_not_finite, "the flow solve gave a pressure that is not finite", s.time);
  if (two_way()) {
    // The first solve round loads the faces with the lower of the step's start pressure and the
    // balance's at the start's apertures at each node (the boundaries' at the step's end): the
    // balance, with no opening to store into, puts an injection into the fluid's
    // compressibility alone — gigapascals in a crack, far from the solution, whose overshoot the
    // cap on the apertures then locks in; where the fluid drains (a fracture that reached a
    // boundary at 0) its lower pressures keep the first solve from pushing apart what the
    // drained fluid no longer does.
    iterate_ = s.flow_pressure;
    for (std::size_t i = 0; i < iterate_.size(); ++i)
      if (network_.node_boundary()[i] >= 0 || step_.pressure[i] < iterate_[i]) iterate_[i] = step_.pressure[i];
    load_ = face_forces(step.context, s, iterate_);
    attempt_ = &step;
    volume0_ = network_.volumes(aperture_);
    compliance_.clear();
    solves_ = 1;
    split_error_ = 0;
    diverged_ = false;
    last_carried_ = 0;
    best_carried_ = 0;
    best_at_ = 0;
    history_f_.clear();
    history_g_.clear();
    have_last_ = false;
    lagging_.clear();
  } else if (f.coupled) {
    load_ = face_forces(step.context, s, step_.pressure);
  }
  return {};
}

std::vector<double> FlowEffect::moved_loop_u(const StepContext& context, const std::vector<double>& loop_xy,
                                             const std::vector<double>& base, const Eigen::VectorXd& d) const {
  std::vector<double> u = base;
  const CoverSpace& space = context.config.space();
  std::vector<double> phi(static_cast<std::size_t>(space.element_dofs() / 2));
  const std::vector<FlowFaceVertex>& ends = network_.end_vertices();
  for (std::size_t k = 0; k < ends.size(); ++k) {
    const auto v = static_cast<std::size_t>(ends[k].vertex), e = static_cast<std::size_t>(vertex_element_[k]);
    context.config.shape_values(e, loop_xy[2 * v], loop_xy[2 * v + 1], phi.data());
    const int* g = space.element_unknowns(e);
    double ux = 0, uy = 0;
    for (std::size_t a = 0; a < phi.size(); ++a) {
      ux += phi[a] * d[g[2 * a]];
      uy += phi[a] * d[g[2 * a + 1]];
    }
    u[2 * v] = base[2 * v] + ux;
    u[2 * v + 1] = base[2 * v + 1] + uy;
  }
  return u;
}

std::vector<double> FlowEffect::compliance(EffectStep& step) const {
  // The faces' response to 1 Pa on every joint face, by the step's factorisation: Δw at the
  // segment ends, and the volume it gives each node (the volumes' rule is linear in the ends).
  std::vector<double> c(network_.nodes(), 0.0);
  if (!step.system.has_factor()) return c;
  const Eigen::VectorXd unit = face_forces(step.context, step.s, std::vector<double>(network_.nodes(), 1.0));
  Eigen::VectorXd b = Eigen::VectorXd::Zero(step.system.size());
  b.head(unit.size()) = unit;
  const Eigen::VectorXd x = step.system.solve_unrefined(b);
  const std::vector<double> zero(step.s.loop_u.size(), 0.0);
  c = network_.volumes(network_.separations(moved_loop_u(step.context, step.s.loop_xy, zero, x)));
  for (double& ci : c) ci = std::isfinite(ci) ? std::max(0.0, ci) : 0.0;
  // Where the faces touch (the start's aperture the residual at every segment end of a node),
  // the factorisation holds their contact springs and the response above misses the opening
  // a pressure beyond the normal stress gives. There c is at least a Griffith crack's: a joint
  // of length L_J opens at its middle by 2·L_J/E′ per Pa of uniform pressure (the row sums'
  // largest), over the node's half segments; E′ ≈ D₁₁ of the element on the face.
  const FlowDef& f = model_.scene().flow;
  std::vector<char> open(network_.nodes(), 0);
  const std::vector<FlowSegment>& segments = network_.segments();
  for (std::size_t k = 0; k < segments.size(); ++k) {
    if (aperture_[2 * k] > f.residual) open[static_cast<std::size_t>(segments[k].a)] = 1;
    if (aperture_[2 * k + 1] > f.residual) open[static_cast<std::size_t>(segments[k].b)] = 1;
  }
  std::vector<double> griffith(network_.nodes(), 0.0);
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const double per_pa = segment_modulus_[k] > 0
                              ? 2 * joint_length_[static_cast<std::size_t>(segments[k].joint)] / segment_modulus_[k]
                              : 0.0;
    griffith[static_cast<std::size_t>(segments[k].a)] += 0.5 * segments[k].length * per_pa;
    griffith[static_cast<std::size_t>(segments[k].b)] += 0.5 * segments[k].length * per_pa;
  }
  for (std::size_t i = 0; i < c.size(); ++i)
    if (!open[i]) c[i] = std::max(c[i], griffith[i]);
  return c;
}

bool FlowEffect::judge(const Eigen::VectorXd& d) {
  if (!two_way() || !attempt_) return false;
  EffectStep& step = *attempt_;
  const FlowDef& f = model_.scene().flow;
  const RunState& s = step.s;
  if (compliance_.empty()) {
    compliance_ = compliance(step);
    // With a lag, twice the row sums: the split's stability wants c ≥ A/2 of the faces' true
    // compliance A (header), and where a dry new crack's faces touch the row sums fell short of
    // it (the KGD plate's pressures swung 0 ↔ 13 MPa from solve to solve, growing).
    if (f.cavitation)
      for (double& c : compliance_) c *= kLagCompliance;
  }
  // The apertures of the faces the solution d moves, and the balance at them (flow_balance.h).
  std::vector<double> ap = network_.apertures(moved_loop_u(step.context, s.loop_xy, s.loop_u, d), f.residual,
                                              f.max_aperture);
  const FlowStorage moving{volume0_, compliance_, iterate_};
  FlowStepResult next = balance_->step(s.flow_pressure, network_.conductances(ap, f.viscosity), network_.volumes(ap),
                                       step.context.dt, step.context.t_end, &moving, lag_start(s));
  ++solves_;
  // The fixed point x → G(x): the pressures x that loaded the faces, the balance's G(x) at the
  // openings they gave. What the split still carries is Σ c·|G(x) − x|.
  const std::size_t n = next.pressure.size();
  double carried = 0;
  for (std::size_t i = 0; i < n; ++i) carried += compliance_[i] * std::abs(next.pressure[i] - iterate_[i]);
  split_error_ = carried;
  static const bool trace = std::getenv("NMM_TRACE_FLOW") != nullptr;
  if (trace)
    std::fprintf(stderr, "flow t %.6g solve %d: carried %.3e of %.3e; x %.6g G %.6g c %.3e\n", step.context.t_end,
                 solves_, carried, std::max(next.exchanged, std::abs(next.stored)), *std::max_element(iterate_.begin(), iterate_.end()),
                 *std::max_element(next.pressure.begin(), next.pressure.end()),
                 *std::max_element(compliance_.begin(), compliance_.end()));
  if (!std::isfinite(carried)) {
    diverged_ = true;  // the step is cut (max_solves)
    return true;
  }
  const double scale = std::max(next.exchanged, std::abs(next.stored));
  step_ = std::move(next);
  aperture_ = std::move(ap);
  if (carried <= kTolerance * scale) return false;
  // The round-off floor: the mechanical solve's pressures jitter by a few 1e-7 of themselves from
  // one solve to the next (0.3 Pa of 6.7e5 in the KGD plate), so where the step's exchanged volume is
  // small against the network's compliance times the pressure the split settles at a floor above
  // kTolerance (1e-11 of 2.5e-6 m³ per m in the 4 m KGD plate from 5 s on, up to 58 solves to
  // reach it by chance and one step cut; in the 8 m plate a step cut to the floor). Once
  // kStall solves brought no halving of the smallest error and the last is within
  // kStallTolerance, the step is settled: the balance then carries at most that share.
  if (best_carried_ == 0 || carried < 0.5 * best_carried_) {
    best_carried_ = carried;
    best_at_ = solves_;
  } else if (solves_ - best_at_ >= kStall && carried <= kStallTolerance * scale) {
    return false;
  }
  // Anderson's extrapolation is kept while it reduces the error; where it grew (contacts that
  // opened or closed, an aperture at its cap: the map is not smooth there) it starts afresh.
  if (last_carried_ > 0 && carried > last_carried_) {
    history_f_.clear();
    history_g_.clear();
    have_last_ = false;
  }
  last_carried_ = carried;
  // With a lag, G(x) is not smooth where a node enters or leaves the lag: Anderson's secants
  // across that change extrapolate into the oscillation a filled and an empty crack make
  // (13 MPa and 0 in turn in the KGD plate); it starts afresh from the plain step G(x) there.
  if (f.cavitation) {
    std::vector<char> lagging(step_.pressure.size(), 0);
    for (std::size_t i = 0; i < lagging.size(); ++i) lagging[i] = step_.pressure[i] <= f.cavitation_pressure;
    if (lagging != lagging_) {
      history_f_.clear();
      history_g_.clear();
      have_last_ = false;
      lagging_ = std::move(lagging);
    }
  }
  iterate_ = accelerate(iterate_, step_.pressure);
  // With a lag, the extrapolation may not pull a face below the floor the fluid holds.
  if (f.cavitation)
    for (double& p : iterate_) p = std::max(p, f.cavitation_pressure);
  load_ = face_forces(step.context, s, iterate_);
  return true;
}

std::vector<double> FlowEffect::accelerate(const std::vector<double>& x, const std::vector<double>& g) {
  // Anderson (1965) mixing of depth kDepth, as Walker & Ni (2011) write it: with the residuals
  // f_k = G(x_k) − x_k and the differences ΔF, ΔG of the last iterates,
  //   γ = argmin ‖f_k − ΔF·γ‖,   x_{k+1} = G(x_k) − ΔG·γ.
  // The map is nearly affine (linear elasticity, fixed contacts), where this is GMRES on it:
  // the slow modes of the split (a pressure localised to a few nodes, whose opening the
  // compliance's row sums overstate) converge in a few iterations instead of hundreds.
  const auto n = static_cast<Eigen::Index>(x.size());
  Eigen::VectorXd f(n), gk(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    gk[i] = g[static_cast<std::size_t>(i)];
    f[i] = gk[i] - x[static_cast<std::size_t>(i)];
  }
  std::vector<double> out(g);
  if (have_last_) {
    history_f_.push_back(f - last_f_);
    history_g_.push_back(gk - last_g_);
    if (history_f_.size() > static_cast<std::size_t>(kDepth)) {
      history_f_.erase(history_f_.begin());
      history_g_.erase(history_g_.begin());
    }
    const auto m = static_cast<Eigen::Index>(history_f_.size());
    Eigen::MatrixXd df(n, m), dg(n, m);
    for (Eigen::Index j = 0; j < m; ++j) {
      df.col(j) = history_f_[static_cast<std::size_t>(j)];
      dg.col(j) = history_g_[static_cast<std::size_t>(j)];
    }
    const Eigen::VectorXd gamma = df.colPivHouseholderQr().solve(f);
    if (gamma.allFinite()) {
      const Eigen::VectorXd next = gk - dg * gamma;
      for (Eigen::Index i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = next[i];
    }
  }
  last_f_ = f;
  last_g_ = gk;
  have_last_ = true;
  return out;
}

Outcome FlowEffect::not_settled(double t) const {
  return Outcome::stop(StopCode::flow_not_converged,
                       "the coupled flow's pressures and openings did not agree after " + std::to_string(solves_) +
                           " solves of the step (the split still carries " + std::to_string(split_error_) +
                           " m3 per m)",
                       t);
}

void FlowEffect::add_at_rest(EffectStep& rest) {
  if (model_.scene().flow.coupled) rest.rhs.head(space_.unknowns()) += face_forces(rest.context, rest.s, rest.s.flow_pressure);
}

void FlowEffect::assemble(EffectStep& step) {
  if (model_.scene().flow.coupled) step.rhs.head(space_.unknowns()) += load_;
}

void FlowEffect::commit(EffectStep& step, const Eigen::VectorXd& d) {
  RunState& s = step.s;
  if (model_.scene().flow.coupled) s.flow_load_work += load_.dot(d.head(space_.unknowns()));
  s.flow_pressure = step_.pressure;
  s.flow_aperture = aperture_;
  if (!step_.void_volume.empty()) s.flow_void = step_.void_volume;
  s.flow_outflow_rate = step_.outflow_rate;
  s.flow_injected += step_.injected;
  s.flow_outflow += step_.outflow;
  s.flow_stored += step_.stored;
  s.flow_exchanged += step_.exchanged;
  if (two_way()) {
    ++iterations_.steps;
    iterations_.solves += solves_;
    iterations_.worst = std::max<long>(iterations_.worst, solves_);
    attempt_ = nullptr;
  }
}

Eigen::VectorXd FlowEffect::face_forces(const StepContext& context, const RunState& s,
                                        const std::vector<double>& p) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(space_.unknowns());
  for (const FlowFace& face : network_.faces()) {
    if (!context.removed.empty() && context.removed[static_cast<std::size_t>(face.element)]) continue;
    const FlowSegment& sg = network_.segments()[static_cast<std::size_t>(face.segment)];
    const double pa = p[static_cast<std::size_t>(face.reversed ? sg.b : sg.a)];
    const double pb = p[static_cast<std::size_t>(face.reversed ? sg.a : sg.b)];
    if (pa == 0 && pb == 0) continue;
    const double* a = s.loop_xy.data() + 2 * face.vertex;
    const double* b = s.loop_xy.data() + 2 * face.next;
    const double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
    if (!(l2 > 0)) continue;
    const std::vector<double> fe =
        edge_traction_forces(edge_frame(context.config, face.element), a, b,
                             [&](double x, double y, double nx, double ny, double* t) {
                               const double xi = ((x - a[0]) * dx + (y - a[1]) * dy) / l2;
                               const double pressure = (1 - xi) * pa + xi * pb;
                               t[0] = -pressure * nx;
                               t[1] = -pressure * ny;
                             });
    add_edge_force(space_, face.element, fe, 1.0, f);
  }
  return f;
}

void FlowEffect::summarise(const RunState& s, nlohmann::json& summary) const {
  if (!active()) return;
  nlohmann::json boundaries = nlohmann::json::array();
  for (std::size_t b = 0; b < s.flow_outflow_rate.size(); ++b)
    boundaries.push_back({{"boundary", b}, {"outflow_m3_per_s", s.flow_outflow_rate[b]}});
  const FlowDef& f = model_.scene().flow;
  summary["flow"] = {{"injected_m3", s.flow_injected},
                     {"outflow_m3", s.flow_outflow},
                     {"stored_m3", s.flow_stored},
                     {"boundaries", boundaries},
                     {"nodes", network_.nodes()},
                     {"segments", network_.segments().size()},
                     {"balance_error", balance_error(s)},
                     {"filled_m3", s.flow_filled},
                     {"coupled", f.coupled},
                     {"steady", f.steady}};
}

double FlowEffect::balance_error(const RunState& s) const {
  // |stored − (injected − outflow)| over the volume exchanged (or stored, if larger).
  const double st = s.flow_stored, scale = std::max(s.flow_exchanged, std::abs(st));
  return scale > 0 ? std::abs(st - (s.flow_injected - s.flow_outflow)) / scale : 0.0;
}


void FlowEffect::write_outputs(OutputStep& out) const {
  const RunState& s = out.state;
  if (!active() || s.flow_pressure.size() != network_.nodes()) return;
  OutputTable& t = out.tables.table("flow.csv", "step,time,node,x,y,pressure,aperture");
  const std::vector<double> aperture = network_.node_apertures(s.flow_aperture);
  for (std::size_t i = 0; i < network_.nodes(); ++i) {
    t.row(out.step, out.time);
    t.add_index(static_cast<std::int64_t>(i));
    for (const double v : {network_.node_xy()[2 * i], network_.node_xy()[2 * i + 1], s.flow_pressure[i], aperture[i]})
      t.add(v);
    t.end_row();
  }
}

void FlowEffect::frame_parts(const OutputStep& out, std::vector<FramePart>& parts) const {
  const RunState& s = out.state;
  if (!active() || s.flow_pressure.size() != network_.nodes()) return;
  const FlowDef& f = model_.scene().flow;
  const SceneDef& scene = model_.scene();
  const double gx = scene.has_gravity ? scene.gravity.x : 0.0, gy = scene.has_gravity ? scene.gravity.y : 0.0;
  const std::size_t n = network_.nodes();
  const std::vector<double>& xy = network_.node_xy();
  FramePart part;
  part.name = "flow";
  PolygonGrid& g = part.grid;
  g.cell_type = PolygonGrid::kLine;
  const std::vector<double> u = network_.node_displacements(s.loop_u);
  std::vector<double> displacement(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    g.add_point(xy[2 * i] + u[2 * i], xy[2 * i + 1] + u[2 * i + 1]);
    displacement[3 * i] = u[2 * i];
    displacement[3 * i + 1] = u[2 * i + 1];
  }
  // φ = p − ρ_f·g·x, the potential the cubic law drives (flow_balance.h), at the nodes as cut.
  std::vector<double> phi(n);
  for (std::size_t i = 0; i < n; ++i)
    phi[i] = s.flow_pressure[i] - f.density * (gx * xy[2 * i] + gy * xy[2 * i + 1]);
  const std::vector<double> conductance = network_.conductances(s.flow_aperture, f.viscosity);
  const std::vector<FlowSegment>& segments = network_.segments();
  std::vector<std::int32_t> joint(segments.size());
  std::vector<double> aperture(segments.size()), flux(3 * segments.size(), 0.0);
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const FlowSegment& sg = segments[k];
    g.add_cell({sg.a, sg.b});
    joint[k] = sg.joint;
    aperture[k] = 0.5 * (s.flow_aperture[2 * k] + s.flow_aperture[2 * k + 1]);
    const auto a = static_cast<std::size_t>(sg.a), b = static_cast<std::size_t>(sg.b);
    const double q = conductance[k] * (phi[a] - phi[b]);
    // The tangent a → b is the normal (nx, ny) turned clockwise (flow_network.cpp).
    flux[3 * k] = q * sg.ny;
    flux[3 * k + 1] = -q * sg.nx;
  }
  g.add_point_array("pressure", 1, s.flow_pressure);
  g.add_point_array("aperture", 1, network_.node_apertures(s.flow_aperture));
  g.add_point_array("boundary", 1, network_.node_boundary());
  g.add_point_array("displacement", 3, std::move(displacement));
  g.add_cell_array("joint", 1, std::move(joint));
  g.add_cell_array("aperture", 1, std::move(aperture));
  g.add_cell_array("flux", 3, std::move(flux));
  parts.push_back(std::move(part));
}

void FlowEffect::energy_state(const EnergyState& e, EnergyTerms& t) const { t.work += e.s.flow_load_work; }

void FlowEffect::energy_step(const EnergyStep& e, EnergyTerms& t) const {
  if (!e.changed_start || !active() || !model_.scene().flow.coupled || e.s.flow_pressure.size() != network_.nodes())
    return;
  const Mesh& mesh = e.model.mesh();
  // The start's pressures, carried onto the cut network (flow_transfer.h), loaded the new faces
  // in B already (crack_release.h): the change from them to the end's.
  const std::vector<double>& p0 = e.changed_start->flow_pressure;
  if (p0.size() != network_.nodes()) return;
  t.fracture += crack_release_fluid(mesh, e.s, *e.changed_start, e.joints_before,
                                    network_.face_pressures(e.s.flow_pressure, mesh.loop_vertex_count()),
                                    network_.face_pressures(p0, mesh.loop_vertex_count()));
}

}  // namespace nmm::solve
