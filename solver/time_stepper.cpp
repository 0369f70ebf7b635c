// NMM time stepping with Shi's implicit scheme (Shi 1988, 1991; physics.md §2).
//
// Unknowns: the displacement increment d = (u, v) of every physical cover during the step
// (constant cover functions); a sliver cover shares the unknowns of a neighbour
// (cover_unknowns.cpp). In an element, u(x) = Σ_k w_k(x)·d_k over its triangle's three
// covers, with w_k the linear weights of the triangle in its configuration at the start of the
// step (each element's triangle has the covers' own node positions, so a cover moves its
// elements as one piece and covers on two faces of a joint move apart).
//
// Each step solves (Newmark, γ = 1, β = solver.newmark_beta)
//     (K + M/(βΔt²)) d = F_ext − F_int + M·[v0/(βΔt) + (1/(2β) − 1)·a0]     (dynamic)
//     K d = F_ext − F_int                                                    (static)
// then a1 = (d − Δt·v0 − (½ − β)Δt²·a0)/(βΔt²), v1 = v0 + Δt·a1, and the next step starts from
// v0 = k·v1, a0 = k·a1 (k = solver.dynamic_factor; static runs keep v = a = 0).
// β = ½ is Shi's DDA scheme exactly: (K + 2/Δt² M) d = F + 2/Δt M v0, v1 = 2d/Δt − v0. It is
// stable but keeps no damping at high frequency: where a stiff contact stops a cover (d ≈ 0) its
// velocity flips sign every step (v1 = −v0) for ever, and blocks resting on each other rock and
// then launch. With β > ½ (and γ = 1, still 2β ≥ γ: unconditionally stable) the stiff limit
// damps: its amplification matrix [[1 − 1/β, 1 − 1/(2β)], [−1/β, 1 − 1/(2β)]] has spectral
// radius 0.41 at β = 0.6 (the default, near the minimum), while constant acceleration is still
// integrated exactly (free fall, a sliding block) and slow vibrations barely feel it.
//   K_e     = A_e Bᵀ D B                    (elasticity.cpp)
//   M_e     = ρ ∫ Nᵀ N dA                   consistent mass: ρ ∫ w_k w_l dA per direction
//   F_int,e = A_e Bᵀ σ_e                    stress carried from earlier steps (initial stress)
//   F_grav  = ρ g ∫ w_k dA                  only with gravity
//   F_load  = w_k(p)·f                      point load f at p, only with loads
//   fixed point p (started at P): penalty spring k_f, K += k_f NᵀN, F −= k_f Nᵀ (p − P)
// All integrals are exact simplex integrals over the element polygon (element_integration.cpp).
// After the solve: σ_e += D B d_e, and every loop vertex, cover node and tracked point moves by
// the displacement field (geometry update: large displacement over many small steps). The stress
// is not rotated with the element: rotations per step are small (Shi's DDA does the same).
//
// Fixed-point stiffness: solver.fixed_point_stiffness, or by default 100·E_max·(1 m) N/m per unit
// thickness. Under a reaction R, a fixed point gives way by R/k_f: with E = 10 GPa that is 1 µm
// for 1 MN. Stiffer springs make the matrix worse conditioned for no gain in the result.
//
// Only the effects a scene calls for are computed: no mass without inertia (static), no gravity
// term without gravity, nothing for loads or fixed points that are not there.
#include "time_stepper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <sstream>

#include "error.h"
#include "nmm_version.h"

namespace nmm::solve {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Crossing-number test; slits and bridges are walked both ways and cancel.
bool in_loop(const double* xy, std::size_t n, double x, double y) {
  bool inside = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double xi = xy[2 * i], yi = xy[2 * i + 1], xj = xy[2 * j], yj = xy[2 * j + 1];
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

double dist_to_loop(const double* xy, std::size_t n, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double ax = xy[2 * j], ay = xy[2 * j + 1], bx = xy[2 * i], by = xy[2 * i + 1];
    const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((x - ax) * dx + (y - ay) * dy) / l2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    best = std::min(best, std::hypot(ax + t * dx - x, ay + t * dy - y));
  }
  return best;
}

std::string fmt_point(double x, double y) {
  std::ostringstream os;
  os << "(" << x << ", " << y << ")";
  return os.str();
}

}  // namespace

TimeStepper::TimeStepper(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name)
    : mesh_(mesh), scene_(scene), scene_name_(scene_name), contacts_(mesh, scene, scene_name) {
  if (mesh.dofs_per_cover != 2)
    throw InputError(scene_name, "", "this solver supports constant cover functions only "
                                     "(2 unknowns per physical cover), the mesh has " +
                                         std::to_string(mesh.dofs_per_cover));
  const std::size_t ne = mesh.element_count(), nc = mesh.cover_count();
  double e_max = 0;
  for (const MaterialDef& m : scene.materials) {
    material_d_.push_back(elasticity_matrix(m, scene.plane));
    e_max = std::max(e_max, m.young);
  }
  fixed_k_ = scene.solver.fixed_point_stiffness > 0 ? scene.solver.fixed_point_stiffness
                                                    : 100.0 * e_max;
  covers_ = assign_cover_unknowns(mesh, scene.solver.sliver_cover_weight);
  contacts_.use_unknowns(covers_.unknown);
  elem_mat_.resize(ne);
  groups_.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t body = mesh.element_body[e];
    if (body < 0 || static_cast<std::size_t>(body) >= scene.bodies.size())
      throw InputError(scene_name, "/bodies", "the mesh has more bodies than its scene");
    elem_mat_[e] = scene.bodies[body].material;
    for (int k = 0; k < 3; ++k) {
      groups_[e][2 * k] = covers_.unknown[mesh.element_covers[3 * e + k]];
      groups_[e][2 * k + 1] = covers_.unknown[mesh.element_covers[3 * e + k]] + 1;
    }
  }
  cover_xy_.resize(2 * nc);
  for (std::size_t c = 0; c < nc; ++c) {
    cover_xy_[2 * c] = mesh.node_xy[2 * mesh.cover_node[c]];
    cover_xy_[2 * c + 1] = mesh.node_xy[2 * mesh.cover_node[c] + 1];
  }
  cover_u_.assign(2 * nc, 0.0);
  velocity_.assign(2 * nc, 0.0);
  accel_.assign(2 * nc, 0.0);
  stress_.assign(3 * ne, 0.0);
  loop_xy_ = mesh.loop_xy;
  loop_u_.assign(loop_xy_.size(), 0.0);
  frame_.resize(ne);

  // Points: the element that contains each one, else the nearest within 1e-6·h (a point on a
  // boundary), else bad input.
  auto locate = [&](const Vec2& p, const std::string& path) {
    std::int32_t best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t e = 0; e < ne; ++e) {
      const std::size_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
      const double* xy = mesh.loop_xy.data() + 2 * b;
      if (in_loop(xy, n, p.x, p.y)) return TrackedPoint{static_cast<std::int32_t>(e), p.x, p.y, p.x, p.y};
      const double d = dist_to_loop(xy, n, p.x, p.y);
      if (d < best_d) {
        best_d = d;
        best = static_cast<std::int32_t>(e);
      }
    }
    if (best < 0 || best_d > 1e-6 * mesh.mesh_size)
      throw InputError(scene_name, path, "point " + fmt_point(p.x, p.y) + " lies outside every body");
    return TrackedPoint{best, p.x, p.y, p.x, p.y};
  };
  for (std::size_t i = 0; i < scene.fixed_points.size(); ++i)
    fixed_.push_back(locate(scene.fixed_points[i], "/fixed_points/" + std::to_string(i)));
  for (std::size_t i = 0; i < scene.loads.size(); ++i)
    loads_.push_back(locate(scene.loads[i].point, "/loads/" + std::to_string(i) + "/point"));
  for (std::size_t i = 0; i < scene.measure_points.size(); ++i)
    measure_.push_back(locate(scene.measure_points[i], "/measure_points/" + std::to_string(i)));

  // w0: half the model size, the scale of Shi's displacement ratio and contact tolerances.
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (std::size_t i = 0; i < loop_xy_.size(); i += 2) {
    x0 = std::min(x0, loop_xy_[i]);
    x1 = std::max(x1, loop_xy_[i]);
    y0 = std::min(y0, loop_xy_[i + 1]);
    y1 = std::max(y1, loop_xy_[i + 1]);
  }
  w0_ = 0.5 * std::max(x1 - x0, y1 - y0);

  // Fixed points and loads couple only the covers of their element: the element pattern holds
  // until contacts couple pairs of elements (update_pattern).
  system_.build_pattern(unknowns(), groups_);
  rhs_.resize(unknowns());
}

std::vector<std::string> TimeStepper::effects() const {
  std::vector<std::string> e;
  if (mesh_.element_count() > 0) e.push_back("elasticity");
  if (scene_.solver.dynamic) e.push_back("inertia");
  if (scene_.has_gravity && (scene_.gravity.x != 0 || scene_.gravity.y != 0)) e.push_back("gravity");
  if (!loads_.empty()) e.push_back("point_loads");
  if (!fixed_.empty()) e.push_back("fixed_points");
  for (const std::string& c : contacts_.effects()) e.push_back(c);
  return e;
}

void TimeStepper::check_static_support() const {
  // Without inertia, each block needs two fixed points or it is free to move as a rigid body
  // (one point still lets it turn), and the stiffness matrix is singular.
  std::vector<int> held(mesh_.block_count(), 0);
  for (const TrackedPoint& p : fixed_) ++held[mesh_.element_block[p.element]];
  for (std::size_t b = 0; b < held.size(); ++b) {
    if (held[b] >= 2) continue;
    std::size_t e = 0;
    while (mesh_.element_block[e] != static_cast<std::int32_t>(b)) ++e;
    const std::int32_t c = mesh_.element_covers[3 * e];
    std::ostringstream os;
    os << "static run: block " << b << " (body " << mesh_.block_body[b] << ") is held by "
       << held[b] << " fixed point" << (held[b] == 1 ? "" : "s")
       << ", so its covers (e.g. cover " << c << " at node "
       << fmt_point(mesh_.node_xy[2 * mesh_.cover_node[c]], mesh_.node_xy[2 * mesh_.cover_node[c] + 1])
       << ") are unconstrained: give each block two fixed points or run dynamic";
    throw RunError(os.str());
  }
}

void TimeStepper::compute_frames() {
  for (std::size_t e = 0; e < mesh_.element_count(); ++e) {
    // Each cover's own node, also for a tied cover (its weight function is its own).
    const std::int32_t* ec = &mesh_.element_covers[3 * e];
    ElementFrame& f = frame_[e];
    const int c0 = ec[0], c1 = ec[1], c2 = ec[2];
    f.ox = cover_xy_[2 * c0];
    f.oy = cover_xy_[2 * c0 + 1];
    const double p[6] = {0, 0, cover_xy_[2 * c1] - f.ox, cover_xy_[2 * c1 + 1] - f.oy,
                         cover_xy_[2 * c2] - f.ox, cover_xy_[2 * c2 + 1] - f.oy};
    f.w = triangle_weights(p);
    if (!(f.w.twice_area > 0))
      throw RunError("element " + std::to_string(e) + ": its triangle has folded over at t = " +
                     std::to_string(time_) + " s (displacements too large for the time step)");
  }
}

void TimeStepper::update_pattern() {
  // Elements, then one coupling group per pair of elements in contact. The pattern only grows:
  // pairs that part keep their (zero) entries, so the pattern — and with it CHOLMOD's symbolic
  // analysis — changes only when a pair of elements meets for the first time.
  const int first = static_cast<int>(groups_.size());
  const auto now = contacts_.element_pairs();
  if (std::includes(pattern_pairs_.begin(), pattern_pairs_.end(), now.begin(), now.end())) {
    contacts_.assign_groups(pattern_pairs_, first);
    return;
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  std::set_union(pattern_pairs_.begin(), pattern_pairs_.end(), now.begin(), now.end(),
                 std::back_inserter(pairs));
  std::vector<int> offsets{0}, dofs;
  for (const auto& g : groups_) {
    dofs.insert(dofs.end(), g.begin(), g.end());
    offsets.push_back(static_cast<int>(dofs.size()));
  }
  for (const auto& [a, b] : pairs) {
    dofs.insert(dofs.end(), groups_[a].begin(), groups_[a].end());
    dofs.insert(dofs.end(), groups_[b].begin(), groups_[b].end());
    offsets.push_back(static_cast<int>(dofs.size()));
  }
  system_.build_pattern(unknowns(), offsets, dofs);
  pattern_pairs_ = std::move(pairs);
  contacts_.assign_groups(pattern_pairs_, first);
}

void TimeStepper::assemble(double dt) {
  const bool dynamic = scene_.solver.dynamic;
  const bool gravity = scene_.has_gravity && (scene_.gravity.x != 0 || scene_.gravity.y != 0);
  // Until one step has given the acceleration, a0 is unknown: that step takes β = ½, for which
  // a0 drops out, so constant acceleration is exact from the first step on.
  const double beta = accel_known_ ? scene_.solver.newmark_beta : 0.5;
  const double mass_k = dynamic ? 1.0 / (beta * dt * dt) : 0.0;  // on d
  const double mass_v = dynamic ? 1.0 / (beta * dt) : 0.0;        // on v0
  const double mass_a = dynamic ? 1.0 / (2 * beta) - 1.0 : 0.0;   // on a0
  system_.set_zero();
  rhs_.setZero();
  Mat6 k;
  for (std::size_t e = 0; e < mesh_.element_count(); ++e) {
    const auto& g = groups_[e];
    const std::int32_t* ec = &mesh_.element_covers[3 * e];
    const ElementFrame& f = frame_[e];
    const std::size_t b = mesh_.element_loop_offset[e], n = mesh_.element_loop_offset[e + 1] - b;
    const PolygonMoments m = polygon_moments(loop_xy_.data() + 2 * b, n, f.ox, f.oy);
    const Mat36 B = strain_matrix(f.w);
    const Mat3& D = material_d_[elem_mat_[e]];
    k.noalias() = m.a * (B.transpose() * D * B);
    const Vec3 sigma(stress_[3 * e], stress_[3 * e + 1], stress_[3 * e + 2]);
    Vec6 fe = -m.a * (B.transpose() * sigma);
    const double rho = scene_.materials[elem_mat_[e]].density;
    if (gravity)
      for (int i = 0; i < 3; ++i) {
        const double iw = integral_w(f.w, m, i);
        fe[2 * i] += rho * scene_.gravity.x * iw;
        fe[2 * i + 1] += rho * scene_.gravity.y * iw;
      }
    {
      if (dynamic)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const double mij = rho * integral_ww(f.w, m, i, j);
            k(2 * i, 2 * j) += mass_k * mij;
            k(2 * i + 1, 2 * j + 1) += mass_k * mij;
            const int cj = 2 * ec[j];
            fe[2 * i] += mij * (mass_v * velocity_[cj] + mass_a * accel_[cj]);
            fe[2 * i + 1] += mij * (mass_v * velocity_[cj + 1] + mass_a * accel_[cj + 1]);
          }
    }
    system_.add_group(e, k.data());
    for (int i = 0; i < 6; ++i) rhs_[g[i]] += fe[i];
  }
  // Fixed points: penalty springs back to where they started.
  for (const TrackedPoint& p : fixed_) {
    const ElementFrame& f = frame_[p.element];
    double w[3];
    for (int i = 0; i < 3; ++i) w[i] = f.w.at(i, p.x - f.ox, p.y - f.oy);
    k.setZero();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        k(2 * i, 2 * j) = fixed_k_ * w[i] * w[j];
        k(2 * i + 1, 2 * j + 1) = fixed_k_ * w[i] * w[j];
      }
    system_.add_group(p.element, k.data());
    const auto& g = groups_[p.element];
    for (int i = 0; i < 3; ++i) {
      rhs_[g[2 * i]] -= fixed_k_ * w[i] * (p.x - p.x0);
      rhs_[g[2 * i + 1]] -= fixed_k_ * w[i] * (p.y - p.y0);
    }
  }
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    const TrackedPoint& p = loads_[l];
    const ElementFrame& f = frame_[p.element];
    const auto& g = groups_[p.element];
    for (int i = 0; i < 3; ++i) {
      const double w = f.w.at(i, p.x - f.ox, p.y - f.oy);
      rhs_[g[2 * i]] += w * scene_.loads[l].force.x;
      rhs_[g[2 * i + 1]] += w * scene_.loads[l].force.y;
    }
  }
}

void TimeStepper::update(const Eigen::VectorXd& d, double dt) {
  const std::size_t ne = mesh_.element_count();
  double max_d = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    const auto& g = groups_[e];
    const ElementFrame& f = frame_[e];
    Vec6 de;
    for (int i = 0; i < 6; ++i) de[i] = d[g[i]];
    const Vec3 ds = material_d_[elem_mat_[e]] * (strain_matrix(f.w) * de);
    for (int i = 0; i < 3; ++i) stress_[3 * e + i] += ds[i];
    for (std::int32_t v = mesh_.element_loop_offset[e]; v < mesh_.element_loop_offset[e + 1]; ++v) {
      const double x = loop_xy_[2 * v] - f.ox, y = loop_xy_[2 * v + 1] - f.oy;
      double ux = 0, uy = 0;
      for (int k = 0; k < 3; ++k) {
        const double w = f.w.at(k, x, y);
        ux += w * de[2 * k];
        uy += w * de[2 * k + 1];
      }
      loop_xy_[2 * v] += ux;
      loop_xy_[2 * v + 1] += uy;
      loop_u_[2 * v] += ux;
      loop_u_[2 * v + 1] += uy;
    }
  }
  auto move = [&](std::vector<TrackedPoint>& pts) {
    for (TrackedPoint& p : pts) {
      const ElementFrame& f = frame_[p.element];
      const auto& g = groups_[p.element];
      double ux = 0, uy = 0;
      for (int k = 0; k < 3; ++k) {
        const double w = f.w.at(k, p.x - f.ox, p.y - f.oy);
        ux += w * d[g[2 * k]];
        uy += w * d[g[2 * k + 1]];
      }
      p.x += ux;
      p.y += uy;
    }
  };
  move(fixed_);
  move(loads_);
  move(measure_);
  const bool dynamic = scene_.solver.dynamic;
  const double beta = accel_known_ ? scene_.solver.newmark_beta : 0.5;
  const double k = scene_.solver.dynamic_factor;
  for (Eigen::Index i = 0; i < d.size(); ++i) max_d = std::max(max_d, std::abs(d[i]));
  // Per cover; a tied cover takes its master's increment (and so keeps its master's velocity).
  for (std::size_t i = 0; i < cover_u_.size(); ++i) {
    const double di = d[covers_.unknown[i / 2] + static_cast<int>(i % 2)];
    cover_xy_[i] += di;
    cover_u_[i] += di;
    if (dynamic) {
      const double a1 = (di - dt * velocity_[i] - (0.5 - beta) * dt * dt * accel_[i]) / (beta * dt * dt);
      velocity_[i] = k * (velocity_[i] + dt * a1);
      accel_[i] = k * a1;
    }
  }
  max_step_displacement_ = std::max(max_step_displacement_, max_d);
  accel_known_ = dynamic;
}

std::string TimeStepper::attempt(double dt) {
  const bool contact = contacts_.active();
  if (!scene_.solver.dynamic && !contact) check_static_support();
  auto t0 = Clock::now();
  compute_frames();
  timings_.assembly += since(t0);
  if (contact) {
    // Search distance: 2.5 × the displacement a step may make (Shi: g2·w0 per step, cut at 2×).
    const double g2w0 = scene_.solver.max_displacement_ratio * w0_;
    contacts_.begin_step(loop_xy_, frame_, 2.5 * g2w0, 1e-3 * mesh_.mesh_size, w0_);
    update_pattern();
  }
  timings_.contact_detection = contacts_.detection_seconds();
  t0 = Clock::now();
  assemble(dt);
  if (contact) {
    system_.save();
    rhs_base_ = rhs_;
  }
  timings_.assembly += since(t0);

  // Open–close iteration: solve, judge, repeat until no contact changes. A change of state
  // changes the matrix (refactorise); a change of friction force alone only the right-hand side
  // (solve again with the same factorisation).
  Eigen::VectorXd d;
  bool refactor = true;
  int factorisations = 0;
  for (int it = 1;; ++it) {
    if (contact && it > 1) {
      t0 = Clock::now();
      if (refactor) system_.restore();
      rhs_ = rhs_base_;
      contacts_.add_to_system(refactor ? &system_ : nullptr, rhs_);
      timings_.assembly += since(t0);
    } else if (contact) {
      t0 = Clock::now();
      contacts_.add_to_system(&system_, rhs_);
      timings_.assembly += since(t0);
    }
    if (refactor) {
      t0 = Clock::now();
      const bool ok = system_.factorize();
      ++factorisations;
      timings_.factorisation += since(t0);
      if (!ok) {
        const int u = system_.failed_unknown();
        std::ostringstream os;
        os << "the system matrix is not positive definite";
        if (u >= 0) {
          const int c = covers_.cover_of_unknown[u / 2];
          os << " at cover " << c << " (node "
             << fmt_point(mesh_.node_xy[2 * mesh_.cover_node[c]], mesh_.node_xy[2 * mesh_.cover_node[c] + 1])
             << "): it is unconstrained (held by no fixed point or closed contact); add fixed "
                "points or run dynamic";
        }
        throw RunError(os.str());
      }
    }
    t0 = Clock::now();
    d = system_.solve(rhs_);
    timings_.solves += since(t0);
    for (Eigen::Index i = 0; i < d.size(); ++i)
      if (!std::isfinite(d[i]))
        throw RunError("the displacement of cover " + std::to_string(covers_.cover_of_unknown[i / 2]) +
                       " is not a finite number at t = " + std::to_string(time_) + " s");
    if (!contact) break;
    ++iterations_;
    const ContactSet::Changes ch = contacts_.judge(d, it, w0_);
    if (ch.states == 0 && ch.forces == 0) break;
    if (ch.states == 0 && ch.stiffness == 0 && it >= 3 * kMaxIterations) {
      // Every state has settled; only friction forces still move (by more than 0.1 %). Take the
      // step rather than cut it: a smaller step would not settle them better.
      ++friction_unsettled_;
      break;
    }
    refactor = ch.states > 0 || ch.stiffness > 0;
    if (factorisations >= kMaxIterations || it >= 4 * kMaxIterations)
      return "the open-close iteration did not converge in " + std::to_string(it) +
             " iterations (" + std::to_string(factorisations) + " with contact state changes)";
  }
  if (contact) {
    // Shi's step control: a step may move no cover more than 2·g2·w0 (contacts farther than the
    // search distance would be missed), nor leave a penetration deeper than g2·w0.
    const double limit = scene_.solver.max_displacement_ratio * w0_;
    const double dmax = d.cwiseAbs().maxCoeff();
    // A static increment does not shrink with Δt (no inertia): the limit applies to dynamic runs.
    if (scene_.solver.dynamic && dmax > 2 * limit) {
      std::ostringstream os;
      os << "a displacement of " << dmax << " m in one step exceeds 2 × max_displacement_ratio × w0 = "
         << 2 * limit << " m";
      return os.str();
    }
    if (contacts_.max_penetration() > limit) {
      std::ostringstream os;
      os << "a penetration of " << contacts_.max_penetration()
         << " m exceeds max_displacement_ratio × w0 = " << limit << " m";
      return os.str();
    }
    contacts_.end_step();
    max_penetration_ = std::max(max_penetration_, contacts_.max_penetration());
    max_capped_ = std::max(max_capped_, contacts_.capped_count());
  }
  t0 = Clock::now();
  update(d, dt);
  timings_.geometry_update += since(t0);
  time_ += dt;
  return "";
}

void TimeStepper::step(double dt) {
  const std::string why = attempt(dt);
  if (!why.empty()) throw RunError(why);
}

void TimeStepper::impose_displacement(const Eigen::VectorXd& d) {
  compute_frames();  // the element frames of the current configuration
  update(d, 1.0);
}

const Eigen::VectorXd& TimeStepper::assemble_rhs(double dt) {
  compute_frames();
  assemble(dt);
  return rhs_;
}

std::array<double, 2> TimeStepper::displacement_at(const TrackedPoint& p) const {
  return {p.x - p.x0, p.y - p.y0};
}

std::vector<MeasureSample> TimeStepper::sample_measure_points() const {
  std::vector<MeasureSample> s;
  for (const TrackedPoint& p : measure_) s.push_back({p.x, p.y, p.x - p.x0, p.y - p.y0});
  return s;
}

std::string TimeStepper::run_until(double t_end, const std::function<void(std::int64_t)>& on_step) {
  // Without contact every step has the full length time_step. With contact, Shi's step control:
  // a step that fails (iteration not converged, displacement or penetration too large) is redone
  // with Δt × 0.3; after a success Δt grows by at most × 1.3 back towards time_step. Below
  // time_step × 1e-3 the run stops (exit status 3).
  const SolverDef& sv = scene_.solver;
  const double dt_floor = 1e-3 * sv.time_step;
  double dt = std::min(dt_, sv.time_step);
  std::int64_t done = 0;
  while (time_ < t_end - 1e-9 * sv.time_step) {
    // Between steps only, so an interrupted run stops in a consistent state.
    if (stop_check_ && stop_check_()) return "interrupted";
    const double h = std::min(dt, t_end - time_);
    std::string why;
    try {
      why = attempt(h);
    } catch (const RunError& e) {
      return e.what();
    }
    if (!why.empty()) {
      ++cuts_;
      dt = 0.3 * h;
      if (dt < dt_floor) {
        std::ostringstream os;
        os << "time step cut below its floor (" << dt_floor << " s) at t = " << time_
           << " s: " << why;
        return os.str();
      }
      continue;
    }
    dt = std::min(1.3 * dt, sv.time_step);
    dt_ = dt;
    on_step(++done);
  }
  return "ok";
}

nlohmann::json TimeStepper::run(OutputWriter& out, bool progress) {
  const auto wall0 = Clock::now();
  const SolverDef& sv = scene_.solver;
  auto output = [&](std::int64_t s) {
    const auto t0 = Clock::now();
    out.add_history(s, time_, sample_measure_points());
    FrameFields fields;
    fields.loop_xy = &loop_xy_;
    fields.loop_u = &loop_u_;
    fields.stress = &stress_;
    out.write_frame(s, time_, mesh_, fields);
    if (contacts_.active()) {
      std::vector<ContactSample> rows;
      for (const Contact& c : contacts_.contacts()) {
        if (c.state == ContactState::open) continue;  // closed contacts only: they carry force
        rows.push_back({loop_xy_[2 * c.at.vertex], loop_xy_[2 * c.at.vertex + 1],
                        static_cast<int>(c.state), c.law, -c.gap, c.shear, c.normal_force,
                        c.shear_force, c.kn_now, c.ks_now, c.length});
      }
      out.add_contacts(s, time_, rows);
    }
    timings_.output += since(t0);
  };
  output(0);
  std::int64_t done = 0;
  const double t_end = static_cast<double>(sv.steps) * sv.time_step;
  const std::string status = run_until(t_end, [&](std::int64_t n) {
    done = n;
    if (n % sv.output_every == 0 || time_ >= t_end - 1e-9 * sv.time_step) output(n);
    if (progress_) progress_(n, time_);
    if (progress && n % 10 == 0) {
      std::fprintf(stderr, "\rstep %lld  t = %.6g / %.6g s  cuts %zu", static_cast<long long>(n),
                   time_, t_end, cuts_);
      std::fflush(stderr);
    }
  });
  if (progress) std::fprintf(stderr, "\n");
  if (status != "ok" && done % sv.output_every != 0) output(done);  // the last good state
  const auto t0 = Clock::now();
  out.flush_history();
  timings_.output += since(t0);

  nlohmann::json summary;
  summary["status"] = status;
  summary["steps_completed"] = done;
  summary["simulated_time"] = time_;
  summary["wall_seconds"] = since(wall0);
  summary["effects"] = effects();
  summary["open_close_iterations"] = iterations_;
  summary["time_step_cuts"] = cuts_;
  summary["steps_with_unsettled_friction"] = friction_unsettled_;
  summary["max_penetration"] = max_penetration_;
  summary["max_contacts_at_closure_cap"] = max_capped_;
  const ContactSet::Events& ev = contacts_.events;
  summary["contacts"] = {{"at_end", contacts_.contacts().size()},
                         {"closed_at_end", contacts_.closed_count()},
                         {"pairs_tested", contacts_.detection_stats().pairs_tested},
                         // State changes in all iterations (attempts that were cut included):
                         // many "settled" ones mean contacts chattering at zero gap or slip.
                         {"closings", ev.closed},
                         {"openings", ev.opened},
                         {"slips", ev.slid},
                         {"sticks", ev.stuck},
                         {"settled", ev.frozen_sliding}};
  summary["timings"] = {{"contact_detection", timings_.contact_detection},
                        {"assembly", timings_.assembly},
                        {"factorisation", timings_.factorisation},
                        {"solves", timings_.solves},
                        {"geometry_update", timings_.geometry_update},
                        {"output", timings_.output}};
  summary["unknowns"] = unknowns();
  summary["physical_covers"] = mesh_.cover_count();
  summary["tied_sliver_covers"] = covers_.tied;
  summary["manifold_elements"] = mesh_.element_count();
  summary["symbolic_analyses"] = system_.analyses();
  summary["time_step"] = sv.time_step;
  summary["max_step_displacement"] = max_step_displacement_;
  summary["fixed_point_stiffness"] = fixed_k_;
  summary["tool_version"] = NMM_VERSION;
  // CHECKPOINT (issue 12): the checkpoint writer is wired here at merge — it writes
  // out.dir() + "/checkpoint.nmmstate" from the run's state, for every status ("ok",
  // "interrupted", a stopped run), before summary.json so a summary implies a checkpoint.
  out.write_summary(summary);
  return summary;
}

}  // namespace nmm::solve
