// Contact springs and the open–close iteration (Shi's DDA, physics.md §3).
//
// A contact is a vertex P of element A facing an edge Q2 → Q3 of element B (contact_detection).
// With the edge's unit tangent t, outward normal n and P's projection P0 = Q2 + ω(Q3 − Q2), the
// gap and the relative tangential motion of the step are linear in the cover displacements d:
//     gap  = g0 + cnᵀd,   cn = [ w_A,k(P)·n  for A's covers ;  −w_B,k(P0)·n  for B's ]
//     slip = csᵀd,        cs = the same with t
// (to first order this is Shi's triangle-area formula dn = Δ(P1,P2,P3)/l with the edge's own
// motion taken at P0).
//
// Springs (energy ½k·x²): normal K += kn·cn cnᵀ, F −= kn·g0·cn. Shear: the spring carries an
// elastic shear s_el from step to step (elastoplastic, "return mapping" friction): the trial
// shear of a step is s = s_el + slip. Locked: K += ks·cs csᵀ, F −= ks·s_el·cs. Sliding: no
// spring, friction F −= σ·(tanφ·N)·cs against the slip direction σ, N = −kn·gap of the previous
// solve (explicit within the iteration, which repeats until N has settled to 0.1 %; those
// repeats change only the right-hand side, so they reuse the factorisation, and are
// under-relaxed after the fourth). A step
// that ends sliding leaves s_el = σ·tanφ·N/ks, the spring loaded at the friction limit, so the
// shear force stays continuous when the contact sticks again (a spring restarting from zero
// would drop the force from tanφ·N to 0 in one step and shake the blocks).
//
// States after each solve (T = tensile strength, c = cohesion, L = the contact's tributary
// length: half of each candidate edge at P; both are lost once the contact slides or opens —
// c drops to the joint set's residual_cohesion, 0 unless given):
//   open    → locked   when gap < −ε (a fresh spring)
//   closed  → open     when N < −T·L − kn·ε   (tension beyond the strength)
//   locked  → sliding  when |ks·s| > N·tanφ + c·L   (Mohr–Coulomb), σ = sign(s)
//   sliding → locked   when σ·ks·s < N·tanφ: the trial spring force falls below the limit (the
//                      slip reversed)
// ε = 1e-10·w0. A contact may change state once in one step; a second change leaves it closed
// and sliding for the rest of the step: its normal spring stays (frozen open, it would sink in,
// then close next step with a large starting penetration, overshoot and open again — a pump),
// and its tangential force is friction at most (frozen locked at zero normal force it could pin
// a whole block). So contacts sitting at zero gap or zero slip cannot flip for ever; a
// tolerance growing instead would turn into huge forces: with kn = 5e11 N/m, 1 µm is 500 kN.
//
// Joint laws (Bandis–Barton closure, hyperbolic shear) replace the constant springs through
// joint_law.h: each spring is linearised at its last iterate (Newton; the force is exactly on
// the constitutive curve, the matrix gets the tangent), and the iteration goes on until no
// spring force has moved by more than 0.1 % against that linearisation.
//
// Laws: a contact takes the joint set of the joint its edge lies on (else the joint at P), else
// the scene's interface_set, else the default interface: kn = 20·E_max·(1 m), ks = kn/2.5,
// frictionless, no cohesion or tension. (Shi's default is 50·E; within his recommended 10–100·E,
// 10–20·E is where the open–close iteration here is accurate and settles quickly: see
// docs/contact.md.)
#include "contact.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "error.h"

namespace nmm::solve {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

ContactSet::ContactSet(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name)
    : mesh_(mesh) {
  active_ = !scene.joints.empty() || mesh.block_count() > 1;
  if (!active_) return;
  topo_ = build_contact_topology(mesh);
  (void)scene_name;
  for (const JointSetDef& js : scene.joint_sets) {
    ContactLaw law;
    law.normal = js.normal.model;
    law.kn = js.normal.kn;
    law.kni = js.normal.kni;
    law.vm = js.normal.vm;
    law.shear = js.shear.model;
    law.ks = js.shear.ks;
    law.ksi = js.shear.ksi;
    law.rf = js.shear.rf;
    law.tan_phi = std::tan(js.friction_deg * kPi / 180.0);
    law.cohesion = js.cohesion;
    law.residual_cohesion = js.residual_cohesion;
    law.tensile = js.tensile_strength;
    laws_.push_back(law);
  }
  for (const JointDef& j : scene.joints) joint_law_.push_back(j.set);
  interface_used_ = mesh.block_count() > 1;
  if (scene.interface_set >= 0) {
    interface_law_ = scene.interface_set;
  } else {
    double e_max = 0;
    for (const MaterialDef& m : scene.materials) e_max = std::max(e_max, m.young);
    ContactLaw law;
    law.kn = 20.0 * e_max;
    law.ks = law.kn / 2.5;
    laws_.push_back(law);
    interface_law_ = static_cast<int>(laws_.size()) - 1;
  }
  std::vector<int> used = joint_law_;
  if (interface_used_) used.push_back(interface_law_);
  for (int l : used) {
    nonlinear_ |= laws_[l].normal != NormalModel::constant || laws_[l].shear != ShearModel::constant;
    if (laws_[l].normal == NormalModel::bandis_barton)
      topo_.master_depth = std::max(topo_.master_depth, 2.0 * laws_[l].vm);
  }
}

void ContactSet::begin_step(const std::vector<double>& xy, const std::vector<ElementFrame>& frames,
                            double d0, double shallow, double w0) {
  const auto t0 = std::chrono::steady_clock::now();
  near_pairs_.clear();
  closed_block_.assign(topo_.next.size(), -1);
  for (const Contact& c : committed_)
    if (c.state != ContactState::open) closed_block_[c.at.vertex] = topo_.block_of[c.at.elem_b];
  eps_ = 1e-10 * w0;
  const std::vector<ContactCandidate> found = detect_contacts(topo_, xy, d0, shallow, closed_block_, &stats_, &near_pairs_);
  detection_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Transfer: a vertex keeps its state while it stays against the same block (on the same edge,
  // or having slid onto another edge of that block, e.g. the next element's along a joint).
  std::map<std::int32_t, const Contact*> before;
  for (const Contact& c : committed_) before[c.at.vertex] = &c;
  std::vector<Contact> now;
  now.reserve(found.size());
  for (const ContactCandidate& f : found) {
    if (!removed_.empty() && (removed_[f.elem_a] || removed_[f.elem_b])) continue;  // excavated
    Contact c;
    c.at = f;
    std::int32_t joint = mesh_.loop_edge_joint[f.edge];
    if (joint < 0) joint = mesh_.loop_edge_joint[f.vertex];
    if (joint < 0) joint = mesh_.loop_edge_joint[topo_.prev[f.vertex]];
    c.law = joint >= 0 ? joint_law_[joint] : interface_law_;
    const auto it = before.find(f.vertex);
    if (it != before.end() && topo_.block_of[it->second->at.elem_b] == topo_.block_of[f.elem_b]) {
      const Contact& o = *it->second;
      c.state = o.state;
      c.broken = o.broken;
      c.slip_sign = o.slip_sign;
      c.normal_force = o.normal_force;
      c.friction_normal = o.normal_force;
      c.shear_el = o.shear_el;
    }
    // A closed contact whose gap is now positive has separated (or has moved onto an edge it
    // does not touch): it starts the step open. Kept closed, its spring would pull the faces
    // together with kn·gap — glue — and, closing the gap within the solve, never show tension.
    if (c.state != ContactState::open && f.gap > eps_) c.state = ContactState::open;
    c.start_state = c.state;
    now.push_back(c);
  }
  contacts_ = std::move(now);

  // Linearise each contact in the current configuration.
  for (Contact& c : contacts_) {
    const std::int32_t p = c.at.vertex, q2 = c.at.edge, q3 = topo_.next[q2];
    const double px = xy[2 * p], py = xy[2 * p + 1];
    const double dx = xy[2 * q3] - xy[2 * q2], dy = xy[2 * q3 + 1] - xy[2 * q2 + 1];
    const double l = std::hypot(dx, dy), tx = dx / l, ty = dy / l, nx = ty, ny = -tx;
    const double p0x = xy[2 * q2] + c.at.omega * dx, p0y = xy[2 * q2 + 1] + c.at.omega * dy;
    const ElementFrame& fa = frames[c.at.elem_a];
    const ElementFrame& fb = frames[c.at.elem_b];
    for (int k = 0; k < 3; ++k) {
      const double wa = fa.w.at(k, px - fa.ox, py - fa.oy);
      const double wb = fb.w.at(k, p0x - fb.ox, p0y - fb.oy);
      const int ca = mesh_.element_covers[3 * c.at.elem_a + k];
      const int cb = mesh_.element_covers[3 * c.at.elem_b + k];
      const int ua = unknown_.empty() ? 2 * ca : unknown_[ca];
      const int ub = unknown_.empty() ? 2 * cb : unknown_[cb];
      c.dofs[2 * k] = ua;
      c.dofs[2 * k + 1] = ua + 1;
      c.dofs[6 + 2 * k] = ub;
      c.dofs[6 + 2 * k + 1] = ub + 1;
      c.cn[2 * k] = wa * nx;
      c.cn[2 * k + 1] = wa * ny;
      c.cn[6 + 2 * k] = -wb * nx;
      c.cn[6 + 2 * k + 1] = -wb * ny;
      c.cs[2 * k] = wa * tx;
      c.cs[2 * k + 1] = wa * ty;
      c.cs[6 + 2 * k] = -wb * tx;
      c.cs[6 + 2 * k + 1] = -wb * ty;
    }
    c.gap0 = c.at.gap;
    c.gap = c.at.gap;
    c.shear0 = c.state == ContactState::open ? 0.0 : c.shear_el;
    // Tributary length: half of each candidate edge at P that faces the contacted edge (a
    // corner's other side is not on this joint).
    c.length = 0;
    for (std::int32_t s : {topo_.prev[p], p}) {
      if (!topo_.edge_candidate[s]) continue;
      const std::int32_t f = topo_.next[s];
      const double ex = xy[2 * f] - xy[2 * s], ey = xy[2 * f + 1] - xy[2 * s + 1];
      const double el = std::hypot(ex, ey);
      if (el > 0 && (ey / el) * nx + (-ex / el) * ny < -0.7) c.length += 0.5 * el;
    }
    if (c.length == 0) c.length = 1e-3 * topo_.mesh_size;  // a bare corner: a point
    // Newton starts from the state the step starts in.
    c.closure_k = std::max(0.0, -c.gap0);
    c.shear_k = c.shear0;
  }
}

std::vector<std::string> ContactSet::effects() const {
  if (!active_) return {};
  std::vector<int> used = joint_law_;
  if (interface_used_) used.push_back(interface_law_);
  bool friction = false, cohesion = false, tension = false, bb = false, hyp = false;
  for (int l : used) {
    friction |= laws_[l].tan_phi > 0;
    cohesion |= laws_[l].cohesion > 0;
    tension |= laws_[l].tensile > 0;
    bb |= laws_[l].normal == NormalModel::bandis_barton;
    hyp |= laws_[l].shear == ShearModel::hyperbolic;
  }
  std::vector<std::string> e{"contact"};
  if (friction) e.push_back("friction");
  if (cohesion) e.push_back("cohesion");
  if (tension) e.push_back("tension");
  if (bb) e.push_back("bandis_barton");
  if (hyp) e.push_back("hyperbolic");
  return e;
}

std::vector<std::pair<std::int32_t, std::int32_t>> ContactSet::element_pairs() const {
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs = near_pairs_;
  for (const Contact& c : contacts_) pairs.emplace_back(c.at.elem_a, c.at.elem_b);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

void ContactSet::assign_groups(const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs,
                               int first_group) {
  for (Contact& c : contacts_) {
    const auto it = std::lower_bound(pairs.begin(), pairs.end(), std::make_pair(c.at.elem_a, c.at.elem_b));
    c.group = first_group + static_cast<int>(it - pairs.begin());
  }
}

void ContactSet::add_to_system(SystemMatrix* k, Eigen::VectorXd& rhs) const {
  // Each spring is linearised at its last iterate: force F_k and tangent k_t there. With
  // gap = g0 + cnᵀd and closure δ = −gap, N(δ) ≈ N_k + k_t(δ − δ_k) gives
  //   K += k_t·cn cnᵀ,  F += (N_k − k_t·δ_k − k_t·g0)·cn;
  // the shear force T(s) ≈ T_k + k_t(s − s_k), s = s_el + csᵀd, gives
  //   K += k_t·cs csᵀ,  F −= (T_k − k_t·s_k + k_t·s_el)·cs.
  // For constant springs both reduce to the plain penalty terms.
  Eigen::Matrix<double, 12, 12> block;
  for (const Contact& c : contacts_) {
    if (c.state == ContactState::open) continue;
    const ContactLaw& law = laws_[c.law];
    const Eigen::Map<const Eigen::Matrix<double, 12, 1>> cn(c.cn.data()), cs(c.cs.data());
    const SpringState nsp = normal_spring(law, c.closure_k, c.length);
    block.noalias() = nsp.stiffness * cn * cn.transpose();
    Eigen::Matrix<double, 12, 1> f =
        (nsp.force - nsp.stiffness * c.closure_k - nsp.stiffness * c.gap0) * cn;
    if (c.state == ContactState::locked) {
      const double strength = shear_strength(law, nsp.force, c.length, c.broken);
      const SpringState ssp = shear_spring(law, c.shear_k, strength, c.length);
      block.noalias() += ssp.stiffness * cs * cs.transpose();
      f -= (ssp.force - ssp.stiffness * c.shear_k + ssp.stiffness * c.shear0) * cs;
    } else {
      f -= c.slip_sign * shear_strength(law, c.friction_normal, c.length, true) * cs;
    }
    if (k) k->add_group(static_cast<std::size_t>(c.group), block.data());
    for (int i = 0; i < 12; ++i) rhs[c.dofs[i]] += f[i];
  }
}

ContactSet::Changes ContactSet::judge(const Eigen::VectorXd& d, int iteration, double w0) {
  const double eps = 1e-10 * w0;
  int changed = 0, forces = 0, stiffness = 0;
  for (Contact& c : contacts_) {
    if (iteration == 1) c.flips = 0;
    const ContactState before = c.state;
    const ContactLaw& law = laws_[c.law];
    double dg = 0, ds = 0;
    for (int i = 0; i < 12; ++i) {
      dg += c.cn[i] * d[c.dofs[i]];
      ds += c.cs[i] * d[c.dofs[i]];
    }
    c.gap = c.gap0 + dg;
    c.shear = c.shear0 + ds;
    // Normal force on the constitutive curve (compression > 0; tension with the initial
    // stiffness, for the opening check).
    const double k0 = initial_normal_stiffness(law, c.length);
    const SpringState nsp = normal_spring(law, std::max(0.0, -c.gap), c.length);
    const double n = c.gap < 0 ? nsp.force : -k0 * c.gap;
    c.capped = nsp.capped;
    const double tension_cap = c.broken ? 0.0 : law.tensile * c.length;
    const double strength = shear_strength(law, n, c.length, c.broken);
    // Newton: has the closure the normal spring was linearised at moved the force by > 0.1 %?
    if (c.state != ContactState::open && law.normal != NormalModel::constant) {
      const SpringState at_k = normal_spring(law, c.closure_k, c.length);
      const double linear = at_k.force + at_k.stiffness * (std::max(0.0, -c.gap) - c.closure_k);
      if (std::abs(nsp.force - linear) > 1e-3 * std::max(std::abs(nsp.force), 1e-9 * k0 * w0)) {
        if (std::abs(nsp.stiffness - at_k.stiffness) > 0.2 * at_k.stiffness) ++stiffness;
        ++forces;
      }
      c.closure_k = std::max(0.0, -c.gap);
    }
    c.kn_now = c.state == ContactState::open ? 0 : nsp.stiffness;
    switch (c.state) {
      case ContactState::open:
        c.normal_force = 0;
        c.shear_force = 0;
        c.ks_now = 0;
        if (c.gap < -eps) {
          c.shear0 = 0;  // a fresh spring: its trial shear is the slip of this step
          c.friction_normal = n;
          c.shear = ds;
          c.closure_k = -c.gap;
          c.shear_k = ds;
          c.state = ContactState::locked;
          ++events.closed;
          ++changed;
        }
        break;
      case ContactState::locked:
      case ContactState::sliding: {
        c.normal_force = std::max(n, 0.0);
        const SpringState ssp = shear_spring(law, c.shear, strength, c.length);
        if (n < -tension_cap - k0 * eps) {
          c.state = ContactState::open;
          c.broken = true;
          ++events.opened;
          ++changed;
        } else if (c.state == ContactState::locked) {
          c.shear_force = ssp.force;
          c.ks_now = ssp.stiffness;
          // Mohr–Coulomb; a hyperbola with Rf = 1 only approaches the strength: 99.9 % is slip.
          const double limit = law.shear == ShearModel::constant ? strength : 0.999 * strength;
          if (std::abs(ssp.force) > limit) {
            c.state = ContactState::sliding;
            c.slip_sign = c.shear > 0 ? 1 : -1;
            ++events.slid;
            c.friction_normal = n;
            c.broken = true;
            ++changed;
          } else if (law.shear != ShearModel::constant) {
            const SpringState at_k = shear_spring(law, c.shear_k, strength, c.length);
            const double linear = at_k.force + at_k.stiffness * (c.shear - c.shear_k);
            if (std::abs(ssp.force - linear) > 1e-3 * std::max(std::abs(ssp.force), 1e-9 * k0 * w0)) {
              if (std::abs(ssp.stiffness - at_k.stiffness) > 0.2 * at_k.stiffness) ++stiffness;
              ++forces;
            }
            c.shear_k = c.shear;
          }
        } else {
          c.ks_now = 0;
          c.shear_force = c.slip_sign * shear_strength(law, c.friction_normal, c.length, true);
          if (c.slip_sign * ssp.force < strength - initial_shear_stiffness(law, c.length) * eps) {
            c.state = ContactState::locked;  // the slip reversed: it sticks, the spring loaded
            c.shear_k = c.shear;
            ++events.stuck;
            ++changed;
          } else if (std::abs(n - c.friction_normal) >
                     1e-3 * std::max(std::abs(n), std::abs(c.friction_normal)) + 1e-12 * k0 * w0) {
            // Friction must use the normal force it ends with. A fixed-point iteration on it can
            // oscillate where contacts press on each other; from the fifth iteration on it is
            // under-relaxed (half way), which damps that.
            c.friction_normal = iteration <= 4 ? n : 0.5 * (c.friction_normal + n);
            ++forces;
          }
        }
        break;
      }
    }
    if (c.state != before && ++c.flips > 1) {
      // Second change in this step: settle closed and sliding (see the file comment).
      c.state = ContactState::sliding;
      if (before != ContactState::sliding) c.slip_sign = c.shear > 0 ? 1 : -1;
      c.friction_normal = std::max(n, 0.0);
      ++events.frozen_sliding;
      if (c.state == before) --changed;
    }
  }
  return {changed, forces, stiffness};
}

void ContactSet::end_step() {
  for (Contact& c : contacts_) {
    const ContactLaw& law = laws_[c.law];
    if (c.state == ContactState::open) {
      c.shear_el = 0;
    } else if (c.state == ContactState::locked) {
      c.shear_el = c.shear;
    } else {
      // Sliding: the spring stays loaded at the friction limit.
      const double strength = shear_strength(law, c.normal_force, c.length, true);
      c.shear_el = c.slip_sign * shear_at_force(law, strength, strength, c.length);
    }
  }
  committed_ = contacts_;
}

double ContactSet::max_penetration() const {
  double p = 0;
  for (const Contact& c : contacts_) p = std::max(p, -c.gap);
  return p;
}

std::size_t ContactSet::capped_count() const {
  std::size_t n = 0;
  for (const Contact& c : contacts_) n += c.capped && c.state != ContactState::open ? 1 : 0;
  return n;
}

std::size_t ContactSet::closed_count() const {
  std::size_t n = 0;
  for (const Contact& c : contacts_) n += c.state != ContactState::open ? 1 : 0;
  return n;
}

}  // namespace nmm::solve
