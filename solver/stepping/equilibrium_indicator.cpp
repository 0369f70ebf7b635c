// Equilibrium indicators: the unbalanced force ratio (UDEC's `solve ratio`) adapted to Shi's
// implicit scheme, and the largest velocity (docs/solver.md "Equilibrium indicators").
//
// UDEC (explicit) computes at every gridpoint the out-of-balance force ΣF = F_ext + F_contact −
// F_int, which its lumped mass turns into the gridpoint's acceleration, and judges a static run by
//     ratio = max_gridpoints |ΣF| / (mean over gridpoints of the applied force magnitude)
// (3DEC and FLAC also report the mean ratio: mean |ΣF| over the same denominator). Its default
// limit for `solve ratio` is 1e-5.
//
// Here the cover is the gridpoint. What is left of the force balance at a step's end is exactly
// the inertia the step's equation absorbed (newmark.h: the Newmark step solves
// M a1 = F_ext + F_c − F_int(t1) at t1):
//     dynamic:           R = M a1,   a1 = (d − Δt v0 − (½ − β)Δt² a0) / (β Δt²)
//     static "dda":      R = 2 M d / Δt²    (every step from rest: (K + 2M/Δt²) d = F)
//     static "equilibrium" (no mass): R = K d = F_ext − F_int of the step's starting state with
//                        the step's contact forces — the force the step's solve had to balance
//                        (0 once the state no longer moves)
// per cover c, with its lumped (row-sum) mass m_c = Σ_e ρ_e ∫_e w_c dA — UDEC's gridpoint mass.
// (The consistent M·a differs from m_c·a_c only by how a varies between neighbouring covers;
// lumped keeps the indicator a per-cover number and needs no element loop per step.) Only the
// cover's translation (its constant term, the displacement at its node) counts, as a gridpoint's.
// A tied sliver cover shares its master's unknowns and adds its mass to the master's.
//     R_c = m_c |a_c|                                                       N/m
//     F_ref = (|b| Σ m_c + Σ |f_load| + Σ_edges |t| L) / N_covers          N/m
//     max ratio = max_c R_c / F_ref,   mean ratio = (Σ_c R_c / N_covers) / F_ref     –
// b is the body force (gravity − base acceleration), t the boundary traction (in-situ ones
// |σ·n|), both at the step's end; covers of excavated bodies are left out. F_ref is UDEC's
// "average applied force per gridpoint": the weight of a cover in a gravity-loaded slope. When
// nothing is applied (no gravity, loads or tractions) the denominator is the force the stress
// carries across a face of mesh size h, mean_e |σ_e| h, so that the ratio stays a ratio.
//
// Velocity: the largest |v| of a cover's translation at the step's end — v1 = v0 + Δt a1 in a
// dynamic run (before dynamic_factor scales it for the next step), d/Δt in a static one.
//
// Verdict (summary.json "equilibrium"), from the last step:
//   static:  at_rest when max ratio < 1e-5 (UDEC's default for `solve ratio`).
//   dynamic: at_rest when the largest velocity < 1e-4 m/s, as UDEC users judge a dynamic run.
//            The ratio is reported but not judged: in a dynamic run it is the inertia of the
//            elastic vibration the scheme keeps (R ≈ m ω v: data/jointed_slope.json at 1 s rings
//            at 7.7e-5 m/s with a ratio of 1.3e-4, an amplitude v/ω below 1e-6 m), which says
//            nothing about whether blocks still move. A block sliding at constant speed has no
//            unbalanced force but is moving: the velocity catches it. Why 1e-4 m/s: it is the
//            velocity an unbalanced ratio at UDEC's limit (a ≈ 1e-5 g) builds up in 1 s, and
//            0.1 mm/s, below what slope monitoring resolves; the wedge sliding on a 30° incline
//            (a = 1.8 m/s²) passes it within 60 µs of starting.
#include "solver/stepping/equilibrium_indicator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "solver/discretisation/excavation.h"
#include "solver/discretisation/insitu_stress.h"
#include "common/time_table.h"

namespace nmm::solve {

EquilibriumIndicator::EquilibriumIndicator(const Mesh& mesh, const SceneDef& scene,
                                           const CoverSpace& space)
    : mesh_(&mesh), scene_(&scene), dpc_(static_cast<std::size_t>(space.dofs_per_cover())) {
  const std::size_t dpc = dpc_;
  const std::size_t groups = static_cast<std::size_t>(space.unknowns()) / dpc;
  mass_.assign(groups, 0.0);
  body_.assign(groups, -1);
  cover_.assign(groups, 0);
  // A velocity per unknown group: any cover of the group (tied covers carry their master's).
  for (std::size_t c = mesh.cover_count(); c-- > 0;) {
    body_[static_cast<std::size_t>(space.first_unknown(c)) / dpc] = mesh.cover_body[c];
    cover_[static_cast<std::size_t>(space.first_unknown(c)) / dpc] = c;
  }
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    // ∫_e w_c dA = A_e · w_c(centroid): the weights are linear over the element's triangle.
    const std::size_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
    const double* xy = mesh.loop_xy.data() + 2 * b;
    double a2 = 0, cx = 0, cy = 0;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const double cr = xy[2 * j] * xy[2 * i + 1] - xy[2 * i] * xy[2 * j + 1];
      a2 += cr;
      cx += (xy[2 * j] + xy[2 * i]) * cr;
      cy += (xy[2 * j + 1] + xy[2 * i + 1]) * cr;
    }
    if (!(std::abs(a2) > 0)) continue;
    cx /= 3 * a2;
    cy /= 3 * a2;
    const std::int32_t* ec = &mesh.element_covers[3 * e];
    double p[3][2];
    for (int k = 0; k < 3; ++k) {
      p[k][0] = mesh.node_xy[2 * mesh.cover_node[ec[k]]];
      p[k][1] = mesh.node_xy[2 * mesh.cover_node[ec[k]] + 1];
    }
    const double det = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if (!(std::abs(det) > 0)) continue;
    const double l1 = ((cx - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (cy - p[0][1])) / det;
    const double l2 = ((p[1][0] - p[0][0]) * (cy - p[0][1]) - (cx - p[0][0]) * (p[1][1] - p[0][1])) / det;
    const double w[3] = {1 - l1 - l2, l1, l2};
    const std::int32_t body = mesh.element_body[e];
    const double rho = scene.materials[static_cast<std::size_t>(scene.bodies[static_cast<std::size_t>(body)].material)].density;
    const double m = rho * 0.5 * std::abs(a2);
    for (int k = 0; k < 3; ++k)
      mass_[static_cast<std::size_t>(space.first_unknown(static_cast<std::size_t>(ec[k]))) / dpc] += m * w[k];
  }
}

double EquilibriumIndicator::active_mass(const std::vector<std::uint8_t>& body_removed) const {
  double total = 0;
  for (std::size_t g = 0; g < mass_.size(); ++g)
    if (body_[g] < 0 || !body_removed[static_cast<std::size_t>(body_[g])]) total += mass_[g];
  return total;
}

EquilibriumSample EquilibriumIndicator::measure(const StepBalance& st,
                                                const std::vector<std::uint8_t>& body_removed) const {
  EquilibriumSample out;
  out.measured = true;
  const bool dynamic = scene_->solver.dynamic;
  const bool dda = scene_->solver.static_mode == StaticMode::dda;
  const std::size_t dpc = dpc_;
  const Eigen::VectorXd& d = *st.d;
  double sum = 0;
  std::size_t active = 0;
  const double dt = st.dt, beta = st.beta;
  for (std::size_t g = 0; g < mass_.size(); ++g) {
    if (body_[g] >= 0 && body_removed[static_cast<std::size_t>(body_[g])]) continue;
    ++active;
    const std::size_t u = g * dpc;      // first unknown of the group
    const std::size_t s = cover_[g] * dpc;  // its cover's slot in velocity/accel
    double r = 0, v = 0;
    if (dynamic) {
      double a[2], vv[2];
      for (int i = 0; i < 2; ++i) {
        const double v0 = (*st.v0)[s + i], a0 = (*st.a0)[s + i];
        a[i] = (d[static_cast<Eigen::Index>(u + i)] - dt * v0 - (0.5 - beta) * dt * dt * a0) / (beta * dt * dt);
        vv[i] = v0 + dt * a[i];
      }
      r = mass_[g] * std::hypot(a[0], a[1]);
      v = std::hypot(vv[0], vv[1]);
    } else {
      const double dx = d[static_cast<Eigen::Index>(u)], dy = d[static_cast<Eigen::Index>(u + 1)];
      if (dda) r = mass_[g] * 2 * std::hypot(dx, dy) / (dt * dt);
      else if (st.balance != nullptr)
        r = std::hypot((*st.balance)[static_cast<Eigen::Index>(u)], (*st.balance)[static_cast<Eigen::Index>(u + 1)]);
      v = std::hypot(dx, dy) / dt;
    }
    out.max_unbalanced = std::max(out.max_unbalanced, r);
    out.max_velocity = std::max(out.max_velocity, v);
    sum += r;
  }
  if (active == 0) return out;
  double ref = st.applied_sum / static_cast<double>(active);
  if (!(ref > 0) && st.stress != nullptr) {
    // Nothing applied: the force the stress carries across a face of mesh size h.
    double s = 0;
    std::size_t n = 0;
    for (std::size_t e = 0; e < mesh_->element_count(); ++e) {
      if (body_removed[static_cast<std::size_t>(mesh_->element_body[e])]) continue;
      const double* sg = st.stress->data() + 3 * st.stress_terms * e;
      s += std::sqrt(sg[0] * sg[0] + sg[1] * sg[1] + 2 * sg[2] * sg[2]);
      ++n;
    }
    ref = n > 0 ? s / static_cast<double>(n) * mesh_->mesh_size : 0;
  }
  out.applied_force = ref;
  if (ref > 0) {
    out.max_ratio = out.max_unbalanced / ref;
    out.mean_ratio = sum / static_cast<double>(active) / ref;
  } else if (out.max_unbalanced > 0) {
    out.max_ratio = out.mean_ratio = std::numeric_limits<double>::infinity();
  }
  return out;
}

EquilibriumSample EquilibriumIndicator::measure_step(const Model& model, const StepContext& step,
                                                     const Eigen::VectorXd& d, const Eigen::VectorXd* balance) const {
  const RunState& s = step.s;
  const auto [bx, by] = step.body_force;
  StepBalance b;
  b.d = &d;
  b.v0 = &s.velocity;
  b.a0 = &s.accel;
  b.dt = step.dt;
  b.beta = step.beta;
  b.balance = balance;
  b.applied_sum = applied_force_sum(model.scene(), s, step.t_end, std::hypot(bx, by), active_mass(s.body_removed),
                                    model.traction_edges(), model.interface_edges(), step.removed);
  b.stress = &s.stress;
  b.stress_terms = static_cast<std::size_t>(step.config.space().terms());
  return measure(b, s.body_removed);
}

double applied_force_sum(const SceneDef& scene, const RunState& s, double t, double body_force,
                         double active_mass,
                         const std::vector<std::vector<BoundaryEdge>>& traction_edges,
                         const std::vector<InterfaceEdge>& interface_edges,
                         const std::vector<std::uint8_t>& removed_element) {
  double sum = std::abs(body_force) * active_mass;
  for (std::size_t l = 0; l < s.loads.size() && l < scene.loads.size(); ++l) {
    if (removed_element[static_cast<std::size_t>(s.loads[l].element)]) continue;
    const double factor = l < scene.load_tables.size() ? table_value(scene.load_tables[l], t) : 1.0;
    sum += std::abs(factor) * std::hypot(scene.loads[l].force.x, scene.loads[l].force.y);
  }
  const double* xy = s.loop_xy.data();
  const double* u = s.loop_u.data();
  // |σ_insitu·n|·L at the edge's midpoint, in the configuration as cut (x − u).
  auto insitu_force = [&](const BoundaryEdge& be) {
    const double* a = xy + 2 * be.vertex;
    const double* b = xy + 2 * be.next;
    const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
    if (!(len > 0)) return 0.0;
    const double nx = dy / len, ny = -dx / len;
    const double mx = 0.5 * (a[0] + b[0] - u[2 * be.vertex] - u[2 * be.next]);
    const double my = 0.5 * (a[1] + b[1] - u[2 * be.vertex + 1] - u[2 * be.next + 1]);
    const auto sg = insitu_stress_at(scene.insitu_stress, mx, my);
    return std::hypot(sg[0] * nx + sg[2] * ny, sg[2] * nx + sg[1] * ny) * len;
  };
  for (std::size_t i = 0; i < traction_edges.size() && i < scene.tractions.size(); ++i) {
    const TractionDef& td = scene.tractions[i];
    const double factor = std::abs(table_value(td.table, t));
    for (const BoundaryEdge& be : traction_edges[i]) {
      if (removed_element[static_cast<std::size_t>(be.element)]) continue;
      if (td.from_insitu) {
        sum += factor * insitu_force(be);
      } else {
        const double len = std::hypot(xy[2 * be.next] - xy[2 * be.vertex], xy[2 * be.next + 1] - xy[2 * be.vertex + 1]);
        sum += factor * std::hypot(td.normal, td.shear) * len;
      }
    }
  }
  for (const InterfaceEdge& ie : interface_edges) {
    if (removed_element[static_cast<std::size_t>(ie.edge.element)]) continue;
    const double factor = interface_traction_factor(s, ie.other_body, scene.solver.excavation_steps);
    if (factor != 0) sum += std::abs(factor) * insitu_force(ie.edge);
  }
  return sum;
}

bool at_rest(const EquilibriumSample& last, bool dynamic) {
  if (!last.measured) return false;
  return dynamic ? last.max_velocity < RestCriterion::kVelocity
                 : last.max_ratio < RestCriterion::kRatio;
}

nlohmann::json equilibrium_verdict(const EquilibriumSample& last, bool dynamic) {
  std::ostringstream criterion;
  if (dynamic) criterion << "max_velocity_m_s < " << RestCriterion::kVelocity;
  else criterion << "max_unbalanced_ratio < " << RestCriterion::kRatio;
  nlohmann::json j;
  j["verdict"] = !last.measured ? "unknown" : at_rest(last, dynamic) ? "at_rest" : "moving";
  // JSON has no infinity: a ratio without any force to compare with is written as null.
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  j["max_unbalanced_ratio"] = number(last.max_ratio);
  j["mean_unbalanced_ratio"] = number(last.mean_ratio);
  j["max_velocity_m_s"] = last.max_velocity;
  j["max_unbalanced_force_n_per_m"] = last.max_unbalanced;
  j["applied_force_per_cover_n_per_m"] = last.applied_force;
  j["criterion"] = criterion.str();
  if (dynamic) j["velocity_threshold_m_s"] = RestCriterion::kVelocity;
  else j["ratio_threshold"] = RestCriterion::kRatio;
  return j;
}

std::string equilibrium_line(const nlohmann::json& v) {
  std::ostringstream os;
  os << v.value("verdict", std::string("unknown"));
  const nlohmann::json& r = v["max_unbalanced_ratio"];
  if (v.value("verdict", std::string()) != "unknown") {
    os.precision(2);
    os << " (max unbalanced ratio ";
    if (r.is_number()) os << r.get<double>();
    else os << "undefined";
    os << ", largest velocity " << v.value("max_velocity_m_s", 0.0) << " m/s)";
  }
  return os.str();
}

}  // namespace nmm::solve
