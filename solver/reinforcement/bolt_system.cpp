// The bolts in the step's system (docs/reinforcement.md, docs/physics.md "Bolts and cables").
//
// Unknowns. The rock's cover unknowns d, and for each grouted cable one unknown per point i:
// the increment Δδ_i of its slip δ_i, the cable's displacement along its axis less the rock's
// there. The cable is massless (UDEC's cable nodes carry a mass for its explicit scheme; the
// implicit step needs none), so it is in balance at the end of every step.
//
// Kinematics at the step's start, from the current positions p_i of the bolt's points (a block
// that turns turns its bolts with it). The rock's displacement in the step at a point is
// u_i = Σ_a φ_a(p_i)·d_a over its element's shape functions (configuration.h), linear in d, and
// its turn there ω_i = ½(∂u_y/∂x − ∂u_x/∂y), also linear in d.
//   anchored bolt, ends A and B (DDA's point-anchored bolt): the chord r = p_B − p_A, ℓs = |r|,
//       e = r/ℓs, e⊥ = ẑ × e; w = u_B − u_A the ends' relative motion in the step
//   grouted cable (UDEC's cable), segment j from point j to j+1: r_j, ℓs_j, e_j as above;
//       t_i the cable's axis at point i (e_0 and e_n−1 at the ends, the bisector of e_i−1 and
//       e_i inside); the cable's point moves by u_i + t_i·Δδ_i, so
//       w_j = u_j+1 − u_j + t_j+1·Δδ_j+1 − t_j·Δδ_j
//   Each axial spring's end-of-step chord, taken relative to the rock's turn at it
//   (ω̄ = ½(ω_A + ω_B)):
//       m(d) = r + w − ω̄·(ẑ × r) = (ℓs + x)·e + y·e⊥,   x = eᵀw = cᵀd,  y = e⊥ᵀw − ℓs·ω̄ = c⊥ᵀd
//       ℓ(d) = |m(d)| = √((ℓs + x)² + y²)      its exact length, m and c, c⊥ linear in d
//   The rock's own turn is taken out because the rock is updated with the linearised field:
//   its points drift apart by (√(1 + ω²) − 1)·ℓ in a step that turns it by ω, a dilation its
//   stress (σ += D·B·d) does not see; a bolt turned with the rock around it must not see it
//   either (a pretensioned bolt in a block turned by 127° keeps its force). A segment across an
//   opening joint whose far block sways sideways (ω = 0) sees its full length.
//
// Forces from the length (not increments of a projected stretch): each step adds k times the
// exact change of the spring's length, ℓ(d) − ℓs, to the force it started with. The rock chords'
// exact changes telescope over the steps (the next step's ℓs is |r + u_B − u_A| of this one's
// end), so in the elastic range
//       anchored:  N = N_p + k·(|r| − |r_installed|)                 k = stiffness, N_p pretension
//       segment:   N = (EA/L_j)·(|r_j| − L_j + δ_j+1 − δ_j),  |N| ≤ yield   (L_j installed;
//                  δ the slips, along a straight cable; t·e < 1 at a bend)
//       grout:     G_i = k_bond·L_i·δ_i^el,  |G_i| ≤ bond_strength·L_i   (L_i tributary)
// — a bolt's force is that of its current length, not of the sum of its steps' projections
// eᵀw, which misses each step's (e⊥ᵀw)²/(2ℓ): a segment across a joint that sways to and fro
// lengthens at a constant force (0.05 → 0.139 m at 40 kN) — less only what yield, slip and the
// rock's turn take out; those
// are the history (the last accepted step's forces and slips, BoltState), committed on the
// accepted step.
//   G_i is the grout's force on the rock along t_i (and −G_i on the cable), so in balance the
//   cable's axial force falls along it by what the grout takes: N_j−1 − N_j ≈ G_i, the shear
//   lag that test_bolts checks against N(x) = P0·sinh(λ(L − x))/sinh(λL), λ = √(k_bond/EA).
//
// The step's equation. Per metre of the plane-strain model every force and stiffness is divided
// by the bolt's spacing s. An axial spring pulls on the unknowns with f(d) = N(ℓ(d))·∇ℓ, and
// ∇ℓ = cosα·c + sinα·c⊥ =: c_k,  ∂²ℓ = c⊥_k c⊥_kᵀ/ℓ,  c⊥_k := −sinα·c + cosα·c⊥, with
// (cosα, sinα) = (ℓs + x, y)/ℓ: linearised at d_k (x_k, y_k; d_0 = 0, the step's start),
//   K += (k_t·c_k c_kᵀ + (N_k⁺/ℓ_k)·c⊥_k c⊥_kᵀ)/s,   F −= (N_k·c_k − K_k·d_k)/s
// with k_t = k elastic, ε·k at the cap ±(N_k = ±cap + ε·k·(ℓ_k − ℓs), ε = kCapTangent), and the
// geometric stiffness (N/ℓ)(I − e eᵀ) — rank one in 2-D — of a spring in tension only
// (N⁺ = max(N, 0)): a compressed segment's negative one would make the matrix indefinite on a
// free block, where the grout and the rock around a real cable (no dowel action here) hold it.
// Across an opening joint this is what holds the far block sideways: a sway v of the segment's
// far end turns its force by v/ℓ, a stiffness N/ℓ (40 kN over a 5 cm segment: 8e5 N/m), in the
// matrix, so the step is stable at any Δt, static or dynamic. The grout is linear in its slip:
// K += (k_t/s), F −= (G0/s) elastic, (±cap/s) at the cap.
//   Modes by an active set, as contacts' states were decided before the convex contact solve:
// each spring starts the step in the mode of its start force (at the cap if |f0| ≥ cap, elastic
// otherwise); after each solve the trial force f0 + k·(ℓ(d) − ℓs) (f0 + k·Δδ: grout) decides
// (|trial| ≤ cap: elastic, else at the cap of its sign). The same judge compares each axial
// spring's exact force vector N(d)·∇ℓ(d) with the linearised one; where they differ by more than
// kNewtonTolerance·|N| + 1e-9·k·ℓs (the step turned a segment far enough for the linearisation to
// miss), or a mode changed, every axial spring is linearised again at the solution and the step
// solved again from it: Newton's method on the bolts, whose other terms (the rock, the grout) are
// linear in d. A step whose segments turn little (every step of a bolted tunnel) needs no second
// solve; at most kMaxRounds solves (then the step is cut: bolts_not_settled). An anchored bolt
// does not yield: at a solution where its |trial| reaches its strength it breaks, and the step is
// solved again without it (as contact bonds break, contact_problem.h break_at_peak). What lasts —
// forces, slips, yielded, broken, the plastic work — is written into the state by commit() on
// the accepted step only: an attempt that is cut leaves nothing behind.
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

/// The rock's turn in the step at (x, y) in element e, ω = ½(∂u_y/∂x − ∂u_x/∂y), as
/// coefficients over the element's unknowns (local order 2a + component, configuration.h).
void turn_row(const Configuration& config, std::size_t e, double x, double y, double* out) {
  const CoverSpace& space = config.space();
  const int nf = space.element_dofs() / 2;
  if (space.order() == 0) {  // the triangle's weights: constant gradients
    const TriangleWeights& w = config.frame(e).w;
    for (int a = 0; a < nf; ++a) {
      out[2 * a] = -0.5 * w.c[a];
      out[2 * a + 1] = 0.5 * w.b[a];
    }
    return;
  }
  const ElementBasis& basis = config.basis(e);
  const double xi = (x - basis.ox) / basis.h, eta = (y - basis.oy) / basis.h;
  for (int a = 0; a < nf; ++a) {
    out[2 * a] = -0.5 * basis.dy[static_cast<std::size_t>(a)](xi, eta);      // −½·∂φ_a/∂y on u_x
    out[2 * a + 1] = 0.5 * basis.dx[static_cast<std::size_t>(a)](xi, eta);   // ½·∂φ_a/∂x on u_y
  }
}

/// An axial spring's exact length at the step's end and its direction, from x = cᵀd, y = c⊥ᵀd.
struct Chord {
  double l = 0;           ///< m, ℓ(d)
  double cos = 1, sin = 0;  ///< its direction in the step-start frame (e, e⊥)
};
Chord chord(const BoltSpring& s, double x, double y) {
  Chord c;
  c.l = std::hypot(s.length + x, y);
  if (c.l > 0) {
    c.cos = (s.length + x) / c.l;
    c.sin = y / c.l;
  }
  return c;
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
  cp_.clear();
  active_.assign(s.bolts.size(), 1);
  std::vector<double> phi_a(static_cast<std::size_t>(nf)), phi_b(static_cast<std::size_t>(nf));
  std::vector<double> turn_a(static_cast<std::size_t>(ed)), turn_b(static_cast<std::size_t>(ed));
  // Appends the rock part of an axial spring's rows from a to b (e its direction, l its length):
  // along it −φ(p_a)·e on a's element, +φ(p_b)·e on b's; across it the same with e⊥, less
  // l·ω̄, the mean of the rock's turns at a and b (the header's m(d)).
  const auto rock_rows = [&](const TrackedPoint& a, const TrackedPoint& b, const std::array<double, 2>& e, double l) {
    const std::array<double, 2> n{-e[1], e[0]};
    config.shape_values(static_cast<std::size_t>(a.element), a.x, a.y, phi_a.data());
    config.shape_values(static_cast<std::size_t>(b.element), b.x, b.y, phi_b.data());
    turn_row(config, static_cast<std::size_t>(a.element), a.x, a.y, turn_a.data());
    turn_row(config, static_cast<std::size_t>(b.element), b.x, b.y, turn_b.data());
    const int* ga = space_->element_unknowns(static_cast<std::size_t>(a.element));
    const int* gb = space_->element_unknowns(static_cast<std::size_t>(b.element));
    for (int i = 0; i < ed; ++i) {
      dofs_.push_back(ga[i]);
      c_.push_back(-phi_a[i / 2] * e[i % 2]);
      cp_.push_back(-phi_a[i / 2] * n[i % 2] - 0.5 * l * turn_a[i]);
    }
    for (int i = 0; i < ed; ++i) {
      dofs_.push_back(gb[i]);
      c_.push_back(phi_b[i / 2] * e[i % 2]);
      cp_.push_back(phi_b[i / 2] * n[i % 2] - 0.5 * l * turn_b[i]);
    }
  };
  const auto chord_length = [](const TrackedPoint& a, const TrackedPoint& b) { return std::hypot(b.x - a.x, b.y - a.y); };
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
      sp.length = chord_length(bs.nodes[0], bs.nodes[1]);
      rock_rows(bs.nodes[0], bs.nodes[1], direction(bs.nodes[0], bs.nodes[1]), sp.length);
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
      sp.length = chord_length(bs.nodes[j], bs.nodes[j + 1]);
      rock_rows(bs.nodes[j], bs.nodes[j + 1], e[j], sp.length);
      const std::array<double, 2> nj{-e[j][1], e[j][0]};
      dofs_.push_back(first_slip_[b] + static_cast<int>(j));
      c_.push_back(-(t[j][0] * e[j][0] + t[j][1] * e[j][1]));
      cp_.push_back(-(t[j][0] * nj[0] + t[j][1] * nj[1]));
      dofs_.push_back(first_slip_[b] + static_cast<int>(j) + 1);
      c_.push_back(t[j + 1][0] * e[j][0] + t[j + 1][1] * e[j][1]);
      cp_.push_back(t[j + 1][0] * nj[0] + t[j + 1][1] * nj[1]);
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
      cp_.push_back(0.0);
      springs_.push_back(sp);
    }
  }
}

void BoltSystem::assemble(SystemMatrix& system, Eigen::VectorXd& rhs, std::size_t first_group) const {
  Eigen::MatrixXd block;
  Eigen::VectorXd along, across;
  for (const BoltSpring& s : springs_) {
    if (s.broken) continue;
    const double kt = (s.mode == 0 ? s.k : kCapTangent * s.k) * s.per_m;  // N/m per m, its tangent
    const int* dofs = dofs_.data() + s.row;
    const Eigen::Map<const Eigen::VectorXd> c(c_.data() + s.row, s.size);
    if (s.kind == BoltSpring::grout) {  // linear in its slip: f0 (or the cap) is its force at d = 0
      const double f = (s.mode == 0 ? s.f0 : s.mode * s.cap) * s.per_m;
      system.add_diagonal(dofs[0], kt * c[0] * c[0]);
      rhs[dofs[0]] -= f * c[0];
      continue;
    }
    // An axial spring linearised at d_k: its force N_k along ∇ℓ = c_k, material and geometric
    // tangents, and the right-hand side −(N_k·c_k − K_k·d_k).
    const Eigen::Map<const Eigen::VectorXd> cp(cp_.data() + s.row, s.size);
    const Chord at = chord(s, s.xk, s.yk);
    const double stretch = at.l - s.length;
    const double n = (s.mode == 0 ? s.f0 + s.k * stretch : s.mode * s.cap + kCapTangent * s.k * stretch) * s.per_m;
    const double g = std::max(n, 0.0) / at.l;  // N/m per m, the geometric stiffness of a spring in tension
    along.noalias() = at.cos * c + at.sin * cp;
    across.noalias() = at.cos * cp - at.sin * c;
    // K_k·d_k in the rows: c_kᵀd_k = cos·x_k + sin·y_k, c⊥_kᵀd_k = cos·y_k − sin·x_k.
    const double along_k = at.cos * s.xk + at.sin * s.yk, across_k = at.cos * s.yk - at.sin * s.xk;
    const double f_along = n - kt * along_k, f_across = -g * across_k;
    for (int i = 0; i < s.size; ++i) rhs[dofs[i]] -= f_along * along[i] + f_across * across[i];
    block.noalias() = kt * along * along.transpose();
    if (g > 0) block.noalias() += g * across * across.transpose();
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
  if (s.kind == BoltSpring::grout) return x;
  return chord(s, x, across(s, d)).l - s.length;
}

double BoltSystem::across(const BoltSpring& s, const Eigen::VectorXd& d) const {
  double y = 0;
  for (int i = 0; i < s.size; ++i) y += cp_[s.row + static_cast<std::size_t>(i)] * d[dofs_[s.row + static_cast<std::size_t>(i)]];
  return y;
}

double BoltSystem::force(const BoltSpring& s, const Eigen::VectorXd& d) const {
  if (s.broken) return 0;
  const double x = stretch(s, d);
  return s.mode == 0 ? s.f0 + s.k * x : s.mode * s.cap + kCapTangent * s.k * x;
}

bool BoltSystem::judge(const Eigen::VectorXd& d) {
  bool changed = false;
  // Newton: the axial springs' exact force vectors at d against the linearisation the solve
  // used (in its modes, before they switch), in the step-start frame (e, e⊥) of each.
  for (const BoltSpring& s : springs_) {
    if (s.broken || s.kind == BoltSpring::grout) continue;
    double x = 0, y = 0;
    for (int i = 0; i < s.size; ++i) {
      const double di = d[dofs_[s.row + static_cast<std::size_t>(i)]];
      x += c_[s.row + static_cast<std::size_t>(i)] * di;
      y += cp_[s.row + static_cast<std::size_t>(i)] * di;
    }
    const Chord now = chord(s, x, y), at = chord(s, s.xk, s.yk);
    const double kt = s.mode == 0 ? s.k : kCapTangent * s.k;
    const double base = s.mode == 0 ? s.f0 : s.mode * s.cap;
    const double n = base + kt * (now.l - s.length), n_k = base + kt * (at.l - s.length);
    const double g = std::max(n_k, 0.0) / at.l;
    // Linearised: N_k·c_k + k_t·(c_kᵀΔ)·c_k + g·(c⊥_kᵀΔ)·c⊥_k, Δ = d − d_k, in (e, e⊥).
    const double dx = x - s.xk, dy = y - s.yk;
    const double da = at.cos * dx + at.sin * dy, dp = at.cos * dy - at.sin * dx;
    const double lin_a = n_k + kt * da, lin_p = g * dp;  // along c_k, across c⊥_k
    const double lin_x = at.cos * lin_a - at.sin * lin_p, lin_y = at.sin * lin_a + at.cos * lin_p;
    // A compressed spring has no geometric stiffness in the matrix (the header): only its
    // force along it is judged; the turn of its push follows from the next step's geometry.
    const double miss = n_k > 0 ? std::hypot(n * now.cos - lin_x, n * now.sin - lin_y) : std::abs(n - lin_a);
    if (miss > kNewtonTolerance * std::max(std::abs(n), std::abs(n_k)) + 1e-9 * s.k * s.length) changed = true;
  }
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
  if (changed)  // the next solve linearised at this solution
    for (BoltSpring& s : springs_) {
      if (s.broken || s.kind == BoltSpring::grout) continue;
      s.xk = 0;
      s.yk = 0;
      for (int i = 0; i < s.size; ++i) {
        const double di = d[dofs_[s.row + static_cast<std::size_t>(i)]];
        s.xk += c_[s.row + static_cast<std::size_t>(i)] * di;
        s.yk += cp_[s.row + static_cast<std::size_t>(i)] * di;
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
