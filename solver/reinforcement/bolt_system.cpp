// The bolts in the step's system (docs/reinforcement.md, docs/physics.md "Bolts and cables").
//
// Unknowns. The rock's cover unknowns d, and for each grouted cable one unknown per point i:
// the increment Δδ_i of its slip δ_i, the cable's displacement along its axis less the rock's
// there. The cable is massless (UDEC's cable nodes carry a mass for its explicit scheme; the
// implicit step needs none), so it is in balance at the end of every step.
//
// Linearisation at the step's start, from the current positions p_i of the bolt's points (a
// block that turns turns its bolts with it, so large rotations keep their direction right).
// The rock's displacement at a point is u_i = Σ_a φ_a(p_i)·d_a over its element's shape
// functions (configuration.h).
//   anchored bolt, ends A and B, e = (p_B − p_A)/|p_B − p_A| (DDA's point-anchored bolt):
//       Δℓ = eᵀ(u_B − u_A),                  N = N0 + k·Δℓ                 k = stiffness
//   grouted cable (UDEC's cable), segment j from point j to j+1, e_j its direction, L_j its
//   installed length, t_i the cable's axis at point i (e_0 and e_n−1 at the ends, the bisector
//   of e_i−1 and e_i inside), L_i = ½(L_i−1 + L_i) the grout's tributary length there:
//       Δℓ_j = e_jᵀ(u_j+1 − u_j) + (t_j+1·e_j)·Δδ_j+1 − (t_j·e_j)·Δδ_j
//       N_j = N_j0 + (EA/L_j)·Δℓ_j,  |N_j| ≤ yield                  (steel: elastic–perfectly plastic)
//       G_i = G_i0 + k_bond·L_i·Δδ_i,  |G_i| ≤ bond_strength·L_i     (grout: elastic–perfectly plastic)
//   G_i is the grout's force on the rock along t_i (and −G_i on the cable), so in balance the
//   cable's axial force falls along it by what the grout takes: N_j−1 − N_j ≈ G_i, the shear
//   lag that test_bolts checks against N(x) = P0·sinh(λ(L − x))/sinh(λL), λ = √(k_bond/EA).
//   Increments are linear in the step's unknowns and the forces are carried incrementally, as the
//   element stresses are (σ += D·B·d, state_update.h): a rigid turn of a bolted block then
//   loads neither the rock nor its bolts, where N = k·(|p_B − p_A| − ℓ0) would see the step's
//   linearised displacement field stretch the block and the bolt alike by O(ω²) per step.
//
// Each spring is f = f0 + k·Δ, Δ = cᵀd its row (c over the unknowns of its elements' covers and
// slips), capped at |f| ≤ cap: a convex energy in the step. Per metre of the plane-strain model
// every force and stiffness is divided by the bolt's spacing s. In the step's equation:
//   elastic:        K += (k/s)·c cᵀ,       F −= (f0/s)·c
//   at the cap ±:   K += (εk/s)·c cᵀ,      F −= (±cap/s)·c          ε = kCapTangent
// The modes by an active set, as contacts' states were decided before the convex contact
// solve: each spring starts the step in the mode of its start force (at the cap if |f0| ≥ cap,
// elastic otherwise); after each solve the trial force f0 + k·Δ decides (|trial| ≤ cap: elastic,
// else at the cap of its sign), and a step whose solution changed a mode is solved again, from
// that solution, at most kMaxRounds times (then it is cut: bolts_not_settled). An anchored bolt
// does not yield: at a solution where its |trial| reaches its strength it breaks, and the step
// is solved again without it (as contact bonds break, contact_problem.h break_at_peak). What
// lasts — forces, slips, yielded, broken, the plastic work — is written into the state by
// commit() on the accepted step only: an attempt that is cut leaves nothing behind.
// No geometric stiffness (N/ℓ)(I − eeᵀ): a bolt's direction is renewed every step instead, and
// a step's rotations are small.
#include "solver/reinforcement/bolt_system.h"

#include <algorithm>
#include <cmath>

#include "solver/reinforcement/bolt_layout.h"

namespace nmm::solve {

namespace {

/// Unit vector from a to b.
std::array<double, 2> direction(const TrackedPoint& a, const TrackedPoint& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, l = std::hypot(dx, dy);
  return {dx / l, dy / l};
}

}  // namespace

double bolt_elastic_energy(const BoltDef& def, const BoltState& b) {
  double e = 0;  // J per bolt
  if (def.type == BoltType::anchored) {
    if (!b.broken) e = b.axial[0] * b.axial[0] / (2 * def.stiffness);
  } else {
    for (std::size_t j = 0; j < b.axial.size(); ++j)
      e += b.axial[j] * b.axial[j] * installed_length(b.nodes[j], b.nodes[j + 1]) / (2 * def.ea);
    for (std::size_t i = 0; i < b.bond.size(); ++i)
      e += b.bond[i] * b.bond[i] / (2 * def.bond_stiffness * tributary_length(b.nodes, i));
  }
  return e / def.spacing;
}

void BoltSystem::number(const std::vector<BoltState>& bolts, int first_unknown) {
  const int ed = space_->element_dofs();
  first_unknown_ = first_unknown;
  unknowns_ = 0;
  first_slip_.assign(bolts.size(), -1);
  slips_.assign(bolts.size(), 0);
  group_offsets_.assign(1, 0);
  group_dofs_.clear();
  const auto add_element = [&](std::int32_t e) {
    const int* g = space_->element_unknowns(static_cast<std::size_t>(e));
    group_dofs_.insert(group_dofs_.end(), g, g + ed);
  };
  for (std::size_t b = 0; b < bolts.size(); ++b) {
    const BoltState& bs = bolts[b];
    if (bs.type == static_cast<std::uint8_t>(BoltType::anchored)) {
      add_element(bs.nodes[0].element);
      add_element(bs.nodes[1].element);
      group_offsets_.push_back(static_cast<int>(group_dofs_.size()));
      continue;
    }
    first_slip_[b] = first_unknown + unknowns_;
    for (std::size_t j = 0; j + 1 < bs.nodes.size(); ++j) {
      add_element(bs.nodes[j].element);
      add_element(bs.nodes[j + 1].element);
      group_dofs_.push_back(first_slip_[b] + static_cast<int>(j));
      group_dofs_.push_back(first_slip_[b] + static_cast<int>(j) + 1);
      group_offsets_.push_back(static_cast<int>(group_dofs_.size()));
    }
    slips_[b] = static_cast<int>(bs.nodes.size());
    unknowns_ += slips_[b];
  }
}

void BoltSystem::add_groups(std::vector<int>& offsets, std::vector<int>& dofs) const {
  for (std::size_t g = 0; g < groups(); ++g) {
    dofs.insert(dofs.end(), group_dofs_.begin() + group_offsets_[g], group_dofs_.begin() + group_offsets_[g + 1]);
    offsets.push_back(static_cast<int>(dofs.size()));
  }
}

std::string BoltSystem::describe_unknown(int unknown) const {
  for (std::size_t b = 0; b < first_slip_.size(); ++b)
    if (unknown >= first_slip_[b] && unknown < first_slip_[b] + slips_[b])
      return "the slip of bolt " + std::to_string(b) + " at its point " + std::to_string(unknown - first_slip_[b]);
  return "";
}

void BoltSystem::begin_step(const Configuration& config, const RunState& s, const std::vector<std::uint8_t>& removed) {
  const SceneDef& scene = model_->scene();
  const int ed = space_->element_dofs(), nf = ed / 2;
  springs_.clear();
  dofs_.clear();
  c_.clear();
  active_.assign(s.bolts.size(), 1);
  std::vector<double> phi_a(static_cast<std::size_t>(nf)), phi_b(static_cast<std::size_t>(nf));
  // Appends the rock part of a row: −φ(p_a)·e on a's element, +φ(p_b)·e on b's.
  const auto rock_row = [&](const TrackedPoint& a, const TrackedPoint& b, const std::array<double, 2>& e) {
    config.shape_values(static_cast<std::size_t>(a.element), a.x, a.y, phi_a.data());
    config.shape_values(static_cast<std::size_t>(b.element), b.x, b.y, phi_b.data());
    const int* ga = space_->element_unknowns(static_cast<std::size_t>(a.element));
    const int* gb = space_->element_unknowns(static_cast<std::size_t>(b.element));
    for (int i = 0; i < ed; ++i) dofs_.push_back(ga[i]), c_.push_back(-phi_a[i / 2] * e[i % 2]);
    for (int i = 0; i < ed; ++i) dofs_.push_back(gb[i]), c_.push_back(phi_b[i / 2] * e[i % 2]);
  };
  // The mode of a start force against its cap.
  const auto start_mode = [](double f0, double cap) { return std::abs(f0) >= cap ? (f0 > 0 ? 1 : -1) : 0; };
  int group = 0;
  for (std::size_t b = 0; b < s.bolts.size(); ++b) {
    const BoltState& bs = s.bolts[b];
    const BoltDef& def = scene.bolts[b];
    for (const TrackedPoint& p : bs.nodes) active_[b] = active_[b] && !removed[static_cast<std::size_t>(p.element)];
    const double per_m = 1.0 / def.spacing;
    if (def.type == BoltType::anchored) {
      const int g = group++;
      if (!active_[b] || bs.broken) continue;
      BoltSpring sp;
      sp.kind = BoltSpring::anchor;
      sp.bolt = static_cast<int>(b);
      sp.group = g;
      sp.row = dofs_.size();
      sp.size = 2 * ed;
      sp.k = def.stiffness;
      sp.cap = def.strength;
      sp.breaks = true;
      sp.f0 = bs.axial[0];
      sp.per_m = per_m;
      rock_row(bs.nodes[0], bs.nodes[1], direction(bs.nodes[0], bs.nodes[1]));
      springs_.push_back(sp);
      continue;
    }
    const std::size_t n = bs.nodes.size();  // points; n − 1 segments
    const int first_group = group;
    group += static_cast<int>(n - 1);
    if (!active_[b]) continue;
    std::vector<std::array<double, 2>> e(n - 1), t(n);
    for (std::size_t j = 0; j + 1 < n; ++j) e[j] = direction(bs.nodes[j], bs.nodes[j + 1]);
    t[0] = e[0];
    t[n - 1] = e[n - 2];
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const double x = e[i - 1][0] + e[i][0], y = e[i - 1][1] + e[i][1], l = std::hypot(x, y);
      t[i] = l > 0 ? std::array<double, 2>{x / l, y / l} : e[i];
    }
    for (std::size_t j = 0; j + 1 < n; ++j) {
      BoltSpring sp;
      sp.kind = BoltSpring::segment;
      sp.bolt = static_cast<int>(b);
      sp.index = static_cast<int>(j);
      sp.group = first_group + static_cast<int>(j);
      sp.row = dofs_.size();
      sp.size = 2 * ed + 2;
      sp.k = def.ea / installed_length(bs.nodes[j], bs.nodes[j + 1]);
      sp.cap = def.yield;
      sp.f0 = bs.axial[j];
      sp.per_m = per_m;
      sp.mode = start_mode(sp.f0, sp.cap);
      rock_row(bs.nodes[j], bs.nodes[j + 1], e[j]);
      dofs_.push_back(first_slip_[b] + static_cast<int>(j));
      c_.push_back(-(t[j][0] * e[j][0] + t[j][1] * e[j][1]));
      dofs_.push_back(first_slip_[b] + static_cast<int>(j) + 1);
      c_.push_back(t[j + 1][0] * e[j][0] + t[j + 1][1] * e[j][1]);
      springs_.push_back(sp);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double tributary = tributary_length(bs.nodes, i);
      BoltSpring sp;
      sp.kind = BoltSpring::grout;
      sp.bolt = static_cast<int>(b);
      sp.index = static_cast<int>(i);
      sp.row = dofs_.size();
      sp.size = 1;
      sp.k = def.bond_stiffness * tributary;
      sp.cap = def.bond_strength * tributary;
      sp.f0 = bs.bond[i];
      sp.per_m = per_m;
      sp.mode = start_mode(sp.f0, sp.cap);
      dofs_.push_back(first_slip_[b] + static_cast<int>(i));
      c_.push_back(1.0);
      springs_.push_back(sp);
    }
  }
}

void BoltSystem::assemble(SystemMatrix& system, Eigen::VectorXd& rhs, std::size_t first_group) const {
  Eigen::MatrixXd block;
  for (const BoltSpring& s : springs_) {
    if (s.broken) continue;
    const double k = (s.mode == 0 ? s.k : kCapTangent * s.k) * s.per_m;
    const double f = (s.mode == 0 ? s.f0 : s.mode * s.cap) * s.per_m;
    const int* dofs = dofs_.data() + s.row;
    const double* c = c_.data() + s.row;
    for (int i = 0; i < s.size; ++i) rhs[dofs[i]] -= f * c[i];
    if (s.group < 0) {
      system.add_diagonal(dofs[0], k * c[0] * c[0]);
      continue;
    }
    const Eigen::Map<const Eigen::VectorXd> cv(c, s.size);
    block.noalias() = k * cv * cv.transpose();
    system.add_group(first_group + static_cast<std::size_t>(s.group), block.data());
  }
  // The slips of a bolt that carries nothing (a point in an excavated body) are held at zero,
  // as excavated covers are (excavation.h), so that the matrix stays regular.
  for (std::size_t b = 0; b < first_slip_.size(); ++b)
    if (!active_[b])
      for (int u = first_slip_[b]; u < first_slip_[b] + slips_[b]; ++u) system.add_diagonal(u, model_->pin_stiffness());
}

double BoltSystem::stretch(const BoltSpring& s, const Eigen::VectorXd& d) const {
  double x = 0;
  for (int i = 0; i < s.size; ++i) x += c_[s.row + static_cast<std::size_t>(i)] * d[dofs_[s.row + static_cast<std::size_t>(i)]];
  return x;
}

double BoltSystem::force(const BoltSpring& s, const Eigen::VectorXd& d) const {
  if (s.broken) return 0;
  const double x = stretch(s, d);
  return s.mode == 0 ? s.f0 + s.k * x : s.mode * s.cap + kCapTangent * s.k * x;
}

bool BoltSystem::judge(const Eigen::VectorXd& d) {
  bool changed = false;
  for (BoltSpring& s : springs_) {
    if (s.broken) continue;
    const double trial = s.f0 + s.k * stretch(s, d);
    if (s.breaks) {
      if (std::abs(trial) >= s.cap) s.broken = changed = true;
      continue;
    }
    const int mode = std::abs(trial) <= s.cap ? 0 : (trial > 0 ? 1 : -1);
    if (mode != s.mode) {
      s.mode = mode;
      changed = true;
    }
  }
  return changed;
}

void BoltSystem::commit(const Eigen::VectorXd& d, const Configuration& config, std::vector<BoltState>& bolts) const {
  for (const BoltSpring& s : springs_) {
    BoltState& b = bolts[static_cast<std::size_t>(s.bolt)];
    const double f = force(s, d);
    if (s.mode != 0) {
      // The plastic share of the step's motion and the work the cap force did on it.
      const double plastic = stretch(s, d) - (f - s.f0) / s.k;
      b.plastic_work += std::abs(f * plastic) * s.per_m;
    }
    switch (s.kind) {
      case BoltSpring::anchor:
        b.axial[0] = f;
        if (s.broken) {  // it reached its strength in this step, and holds nothing since
          b.broken = 1;
          b.max_axial = std::max(b.max_axial, s.cap);
        }
        break;
      case BoltSpring::segment:
        b.axial[static_cast<std::size_t>(s.index)] = f;
        if (s.mode != 0) b.yielded = 1;
        break;
      case BoltSpring::grout:
        b.bond[static_cast<std::size_t>(s.index)] = f;
        b.slip[static_cast<std::size_t>(s.index)] += d[dofs_[s.row]];
        break;
    }
    if (s.kind != BoltSpring::grout) b.max_axial = std::max(b.max_axial, std::abs(f));
  }
  for (BoltState& b : bolts) config.move_points(d, b.nodes);
}

}  // namespace nmm::solve
