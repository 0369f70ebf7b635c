// The step's contact problem: rows, springs, friction and states (Shi's DDA contacts, solved as a
// convex problem: contact_solve.cpp; docs/physics.md §3).
//
// A contact is a vertex P of element A facing an edge Q2 → Q3 of element B (contact_detection).
// With the edge's unit tangent t, outward normal n and P's projection P0 = Q2 + ω(Q3 − Q2), the
// gap and the relative tangential motion of the step are linear in the step's unknowns d,
// through the full approximation of each element u(x) = Σ_a φ_a(x)·d_a (cover_space.h: at
// cover order n the φ_a = w_k·p_j are the weights times the cover polynomials, 3·(n+1)(n+2)/2
// functions per element, each with an x and a y unknown):
//     gap  = g0 + cnᵀd,   cn = [ φ_A,a(P)·n  for A's unknowns ;  −φ_B,a(P0)·n  for B's ]
//     slip = csᵀd,        cs = the same with t
// so a contact's row holds the unknowns of the covers of its two elements, 2 × 3 × dofs per
// cover (12 at n = 0, 36 at n = 1, 72 at n = 2), in the order of the element pair's coupling
// group in the system matrix. At n = 0 this is Shi's triangle-area formula dn = Δ(P1,P2,P3)/l
// to first order, with the edge's own motion taken at P0.
//
// Springs, each a convex energy of the step's increment (the step is solved as one convex
// minimisation: contact_solve.cpp):
//   normal  N(δ) on the closure δ = −gap (constant kn·L·δ, penalty kn·δ, or Bandis–Barton), 0 when open; a bond
//           (tensile strength T, unbroken, closed at the start of the step) continues it into
//           tension with the initial stiffness;
//   shear   elastoplastic: the spring carries an elastic shear s_el from step to step; the trial
//           shear is s = s_el + slip and the force T(s) = ks·s (or the hyperbola) capped at the
//           strength S = tanφ·N + c·L (c while unbroken, then the joint set's residual
//           cohesion, 0 unless given; S = 0 when open). A step that ends
//           sliding leaves s_el at the cap (return mapping), so the force stays continuous when
//           the contact sticks again.
// Forces enter the residual r = b − A d + Σ N·cn − Σ T·cs, tangents the Newton matrix
// (forces_at, add_tangents, tangent_times); the line search evaluates N and T along a direction
// (set_direction, directional_force). S needs N: a fixed point around the convex solve
// (update_strengths). States (open, locked, sliding) are read off the solution at the end of
// the step (settle_states): open when N = 0 and no bond, sliding when the trial force reaches S.
// Breaking (docs/contact.md "Cohesion and tensile bonds"): a bond or a cohesion breaks for good
// only at a solution of the step — never on an iterate of the friction fixed point — where its
// force reaches the peak: N < −T·L, or |T| at S = c·L + tanφ·N (break_at_peak). The step is then
// solved again with it broken (residual cohesion c_r, no tension), until no unbroken contact is
// beyond its peak; a contact that was closed and ends the step open loses its cohesion too.
//
// Softening crack faces (cohesive_law.h; a new crack in rock with a fracture energy): the normal
// spring in tension is the cohesive law at the damage κ = max(κ_start, λ(g, w_s)) of the iterate
// (λ the effective opening), the secant t(κ)·g/κ — the envelope itself while loading — with the
// elastic stiffness, the secant or nothing (softening) in the Newton matrix; an open face's shear
// is β²·(t(κ)/κ)·w_s on the same secant, a closed one's strength tanφ·N + β·σt·(t(κ)/σt)·L. A
// damaged face closes on a normal spring that rises from its secant to the crack set's kn over
// w_e and keeps the secant shear spring under that strength (cohesive_law.cpp "Closing"): force
// and tangent are continuous where it closes, so its iterates do not cycle between the two. Such
// a face is a bond while κ < w_c (it never breaks at a peak: it softens), and commit() keeps κ,
// the plastic slip and the energy the step's softening dissipated. Π is then not convex along a
// softening face: the exact line search finds a root of ψ all the same, and where the static
// path snaps back the Newton iterations find none and the step is cut (contact_effect.cpp).
//
// The springs come from joint_law.h: a joint stress per unit closure or shear (constant kn, ks in
// Pa/m, Bandis–Barton closure, hyperbolic shear) times the contact's tributary length L
// (tributary_length.h), or DDA's point penalty (N/m per contact); the force is exactly on the
// constitutive curve, the matrix gets the tangent.
//
#include "solver/contact/contact_problem.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/vec2.h"
#include "solver/contact/contact_tolerances.h"

namespace nmm::solve {

void ContactProblem::build(const std::vector<double>& xy, const Configuration& config, double w0) {
  std::vector<Contact>& contacts = set_.step_contacts();
  const ContactTopology& topo = set_.topology();
  eps_ = kContactTolerances.open_gap * w0;
  skin_ = kContactTolerances.skin * w0;
  // Linearise each contact in the current configuration: its row over the unknowns of both
  // elements (the element's local unknown 2a + s is shape function a, direction s: cover_space.h).
  const int nd = space_.element_dofs(), nf = nd / 2;
  row_ = 2 * nd;
  const std::size_t rows = contacts.size() * static_cast<std::size_t>(row_);
  dofs_.resize(rows);
  phi_.resize(rows / 2);
  tangent_.resize(2 * contacts.size());
  std::vector<double> phi_a(static_cast<std::size_t>(nf)), phi_b(static_cast<std::size_t>(nf));
  work_.assign(contacts.size(), ContactWork{});
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    Contact& c = contacts[i];
    ContactWork& w = work_[i];
    const std::int32_t p = c.at.vertex, q2 = c.at.edge, q3 = topo.next[q2];
    const double px = xy[2 * p], py = xy[2 * p + 1];
    const double dx = xy[2 * q3] - xy[2 * q2], dy = xy[2 * q3 + 1] - xy[2 * q2 + 1];
    const double l = length(dx, dy), tx = dx / l, ty = dy / l;
    const double p0x = xy[2 * q2] + c.at.omega * dx, p0y = xy[2 * q2 + 1] + c.at.omega * dy;
    config.shape_values(static_cast<std::size_t>(c.at.elem_a), px, py, phi_a.data());
    config.shape_values(static_cast<std::size_t>(c.at.elem_b), p0x, p0y, phi_b.data());
    const int* ga = space_.element_unknowns(static_cast<std::size_t>(c.at.elem_a));
    const int* gb = space_.element_unknowns(static_cast<std::size_t>(c.at.elem_b));
    int* dof = dofs_.data() + i * static_cast<std::size_t>(row_);
    double* phi = phi_.data() + i * static_cast<std::size_t>(nd);
    // Row: cn = φ·n, cs = φ·t per unknown, n = (ty, −tx); B's φ negated (−φ_B·n: negation is
    // exact).
    tangent_[2 * i] = tx;
    tangent_[2 * i + 1] = ty;
    for (int a = 0; a < nf; ++a) {
      phi[a] = phi_a[a];
      phi[nf + a] = -phi_b[a];
      for (int sd = 0; sd < 2; ++sd) {
        const int la = 2 * a + sd, lb = nd + 2 * a + sd;
        dof[la] = ga[la];
        dof[lb] = gb[la];
      }
    }
    w.start_normal_force = c.normal_force;
    w.start_broken = c.broken;
    w.gap0 = c.at.gap - c.joint.dilation;
    c.gap = w.gap0;
    w.shear0 = c.state == ContactState::open ? 0.0 : c.shear_el;
    // A face whose memory is new (undamaged, no slip) but whose faces start the step open beyond
    // the elastic opening was not cut in this step (a cut's faces coincide): its contact lost its
    // history in a re-cut or paired a face with another piece's, already apart. Its damage is the
    // opening it has: what the faces dissipated to get there was booked by the contact that held
    // them, or nothing held them, and the energy balance has no part of it to give now (booked
    // afresh, Petersson's beam at h 0.0167 m booked 0.69 J/m, G_f × 5.6 mm, for faces 2.35 mm
    // apart in one step).
    if (c.cohesive.on && c.cohesive.opening_max == 0 && c.cohesive.slip == 0 && c.length > 0) {
      const CohesiveLaw& law = set_.cohesive_law(c);
      const double k = initial_normal_stiffness(set_.laws()[c.law], c.length) / c.length;
      if (law.on() && w.gap0 > cohesive_elastic_opening(law, k)) c.cohesive.opening_max = w.gap0;
    }
    if (set_.cohesive_holds(c) && c.length > 0) {
      w.cohesive = &set_.cohesive_law(c);
      w.k_len = initial_normal_stiffness(set_.laws()[c.law], c.length) / c.length;
      w.slip = c.cohesive.slip;
      w.kappa = c.cohesive.opening_max;
      set_cohesion(c, w);
    }
    const ContactLaw& law = set_.laws()[c.law];
    w.linear = !w.cohesive && law.normal != NormalModel::bandis_barton && linear_shear(law);
    if (w.linear) {
      w.kn0 = initial_normal_stiffness(law, c.length);
      w.ks0 = initial_shear_stiffness(law, c.length);
    }
  }
}

namespace {
// cnᵀv and csᵀv of a row (ContactProblem::Row: unknown 2a + s has cn = φ_a·n_s, cs = φ_a·t_s),
// term by term in the unknowns' order as over stored cn and cs: the same bits.
inline void row_dots(const int* dof, const double* phi, int pairs, double tx, double ty, const double* v, double& dn,
                     double& dt) {
  const double nx = ty, ny = -tx;
  double a = 0, b = 0;
  for (int j = 0; j < pairs; ++j) {
    const double p = phi[j], v0 = v[dof[2 * j]], v1 = v[dof[2 * j + 1]];
    a += (p * nx) * v0;
    b += (p * tx) * v0;
    a += (p * ny) * v1;
    b += (p * ty) * v1;
  }
  dn = a;
  dt = b;
}
// y += fn·cn + ft·cs over a row, entry by entry in the unknowns' order (a repeated unknown
// takes its terms in the same order as over stored cn and cs).
inline void row_add(const int* dof, const double* phi, int pairs, double tx, double ty, double fn, double ft,
                    double* y) {
  const double nx = ty, ny = -tx;
  for (int j = 0; j < pairs; ++j) {
    const double p = phi[j];
    y[dof[2 * j]] += fn * (p * nx) + ft * (p * tx);
    y[dof[2 * j + 1]] += fn * (p * ny) + ft * (p * ty);
  }
}

// A spring's force and tangent at one point of the line search.
struct Spring {
  double force = 0;      // N (normal: compression > 0; shear: along the shear)
  double stiffness = 0;  // N/m, tangent
  bool capped = false;
};

// The springs of a contact whose law is a straight line (ContactWork::linear): normal_at() and
// shear_at() below for such a contact, inline, in the same operations (their laws' force is
// k·δ with k = initial_normal_stiffness or initial_shear_stiffness, joint_law.cpp): the same
// bits. The Newton kernels call these in their loops over all contacts.
inline Spring straight_normal(double k, bool bonded, double g, double skin) {
  const double closure = -g;
  if (bonded && closure < skin) return {k * closure, k, false};
  if (closure >= skin) return {k * closure, k, false};
  if (closure <= -skin) return {};
  const double e = (closure + skin) * (closure + skin) / (4 * skin);
  return {k * e, k * (closure + skin) / (2 * skin), false};
}
inline double straight_normal_force(double k, bool bonded, double g, double skin) {
  const double closure = -g;
  if (bonded && closure < skin) return k * closure;
  if (closure >= skin) return k * closure;
  if (closure <= -skin) return 0.0;
  return k * ((closure + skin) * (closure + skin) / (4 * skin));
}
// `sliding_in`: it slid into the step (start_state sliding) the way of `slip_sign`.
inline Spring straight_shear(double k, double strength, bool sliding_in, int slip_sign, double s) {
  if (!(strength > 0)) return {};
  const double f = k * s;
  if (std::abs(f) >= strength) return {s > 0 ? strength : -strength, 0.0, false};
  if (sliding_in && f * slip_sign > 0 && std::abs(f) >= (1 - kContactTolerances.slip_kink) * strength)
    return {f, 0.0, false};
  return {f, k, false};
}
inline double straight_shear_force(double k, double strength, double s) {
  if (!(strength > 0)) return 0.0;
  const double f = k * s;
  if (std::abs(f) >= strength) return s > 0 ? strength : -strength;
  return f;
}

// Normal force at gap g (m): the closure law in compression; in tension only a bond holds (with
// the initial stiffness). The closure the law sees is smoothed over a skin of ±τ around touching,
//     δ_e = 0 (δ ≤ −τ),  (δ + τ)²/(4τ) (|δ| < τ),  δ (δ ≥ τ),
// so force and tangent are continuous: a contact that touches with no force (the sides of
// bricks in a wall) sits inside the skin, and round-off in its gap moves its tangent a little
// instead of switching it between 0 and kn, which would change the Newton matrix every
// iteration. τ = 1e-12·w0 (a few pm): the force at touching is kn·τ/4, far below any load.
Spring normal_at(const ContactLaw& law, const Contact& c, const ContactWork& w, double g, double skin) {
  const double closure = -g;
  if (w.cohesive) {  // a softening crack face: its cohesive law in tension, the crack set's in compression
    if (closure < 0) {
      const CohesiveTraction t = cohesive_traction(*w.cohesive, w.k_len, c.cohesive.opening_max, -closure, w.slip);
      return {-t.traction * c.length, t.stiffness * c.length, false};
    }
    // Closing: from the secant of its damage to the crack set's spring over w_e (cohesive_law.h
    // cohesive_closure), the damage the open side has at zero opening.
    const double kappa = std::max(c.cohesive.opening_max, effective_opening(*w.cohesive, 0.0, w.slip));
    const CohesiveClosure b = cohesive_closure(*w.cohesive, w.k_len, kappa, closure);
    if (b.band) return {b.stress * c.length, b.stiffness * c.length, false};
    const SpringState s = normal_spring(law, b.closure, c.length, c.joint.closure_max);
    return {s.force, s.stiffness, s.capped};
  }
  if (w.bonded && closure < skin) {
    const double k0 = initial_normal_stiffness(law, c.length);
    return {k0 * closure, k0, false};
  }
  if (closure >= skin) {
    const SpringState s = normal_spring(law, closure, c.length, c.joint.closure_max);
    return {s.force, s.stiffness, s.capped};
  }
  if (closure <= -skin) return {};
  const double e = (closure + skin) * (closure + skin) / (4 * skin);
  const SpringState s = normal_spring(law, e, c.length, c.joint.closure_max);
  return {s.force, s.stiffness * (closure + skin) / (2 * skin), false};
}

// N/m, the shear spring of a damaged softening face, open or closed: its secant β²·s(κ)·L, no
// stiffer than the crack set's (cohesive_law.cpp "Closing"); 0 for any other contact (its law's).
double face_shear_stiffness(const ContactLaw& law, const Contact& c, const ContactWork& w) {
  if (!w.cohesive) return 0;
  const CohesiveState st = cohesive_state(*w.cohesive, w.k_len, w.kappa);
  const double ks = initial_shear_stiffness(law, c.length);
  if (c.gap <= 0 && !(st.factor < 1)) return 0;  // closed and undamaged: the crack set's law
  return std::min(cohesive_shear_secant(*w.cohesive, w.k_len, w.kappa) * c.length, ks);
}

// The trial shear force of the spring at elastic shear s, before the strength caps it.
double trial_shear(const ContactLaw& law, const Contact& c, const ContactWork& w, double s) {
  const double k = face_shear_stiffness(law, c, w);
  if (k > 0) return k * s;
  return shear_spring(law, s, w.strength, c.length).force;
}

// m, the elastic shear at which the spring reaches the strength S.
double shear_at_cap(const ContactLaw& law, const Contact& c, const ContactWork& w, double strength) {
  const double k = face_shear_stiffness(law, c, w);
  if (k > 0) return strength / k;
  return shear_at_force(law, strength, strength, c.length);
}

// Shear force at elastic shear s (m): the spring, capped at the strength S (elastoplastic: the
// energy is ½ks·s² inside the cap and S·|s| − S²/(2ks) beyond, convex and C¹).
Spring shear_at(const ContactLaw& law, const Contact& c, const ContactWork& w, double s) {
  if (w.cohesive && c.gap > 0) {
    // An open softening crack face (Camacho & Ortiz 1996): the shear traction on the secant of
    // the damage, β²·s(κ)·w_s, no stiffer than the crack set's shear spring; the traction then
    // follows the faces' relative motion, so a pull across a crack that kinks puts no spurious
    // shear on it. Its cap is the envelope itself (κ includes β·w_s).
    const double k = face_shear_stiffness(law, c, w);
    return {k * s, k, false};
  }
  if (!(w.strength > 0)) return {};
  SpringState sp;
  if (const double k = face_shear_stiffness(law, c, w); k > 0)
    sp = {k * s, k, false};  // a closed damaged face: the same secant, capped at its strength
  else
    sp = shear_spring(law, s, w.strength, c.length);
  if (std::abs(sp.force) >= w.strength) return {s > 0 ? w.strength : -w.strength, 0.0, false};
  // At the kink to round-off after sliding into the step the same way: the slip branch's tangent
  // (the force is the spring's, exact either way; contact_tolerances.h slip_kink).
  if (c.start_state == ContactState::sliding && sp.force * c.slip_sign > 0 &&
      std::abs(sp.force) >= (1 - kContactTolerances.slip_kink) * w.strength)
    return {sp.force, 0.0, false};
  return {sp.force, sp.stiffness, false};
}

// Barton–Bandis: the strength at the end of the step, from the memory (at its start) and the
// step's signed shear so far (travel δ + |Δu|, and the direction: forward or back toward the
// start position). The strength follows it in the friction fixed point below, as it follows the
// normal force of the solution (implicit in the step), so that the joint's τ and δ at the end of
// a step lie on the mobilised curve. With the travel at the start of the step the strength
// lagged the curve by one step: at δp/250 per step by up to 1 % on the pre-peak rise and 2 % at
// 0.1·δp, where τ rises from zero; 4 % at the seed joint's δp/340 near the start
// (tests/test_barton_bandis.cpp DirectShearUnderDisplacementControl, docs/joint-studies.md).
double step_shear(const Contact& c, const ContactWork& w) { return c.shear - w.shear0; }

// Sliding: the trial force reaches the strength (a hyperbola with Rf = 1 only approaches it:
// 99.9 % counts as slip).
bool slides(const ContactLaw& law, const Contact& c, const ContactWork& w) {
  if (w.cohesive && c.gap > 0) return false;  // open and cohesive: the secant shear, no slip
  const double limit = linear_shear(law) || face_shear_stiffness(law, c, w) > 0
                           ? w.strength
                           : kContactTolerances.hyperbola_slip * w.strength;
  return std::abs(trial_shear(law, c, w, c.shear)) >= limit;
}
}  // namespace

void ContactProblem::set_cohesion(const Contact& c, ContactWork& w) const {
  w.c_coh = w.cohesive->cohesion * cohesive_state(*w.cohesive, w.k_len, w.kappa).factor * c.length;
  w.bonded = w.kappa < w.cohesive->w_c;
}

double ContactProblem::plastic_slip(const Contact& c, const ContactWork& w) const {
  const ContactLaw& law = set_.laws()[c.law];
  if (!(w.strength > 0) || !slides(law, c, w)) return 0;
  return std::max(0.0, std::abs(c.shear) - shear_at_cap(law, c, w, w.strength));
}

std::size_t ContactProblem::assign_groups(const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs,
                                          int first_group) {
  std::vector<Contact>& contacts = set_.step_contacts();
  work_.resize(contacts.size());
  // The run of each first element's pairs in `pairs` (sorted, unique): a contact's pair is looked
  // for among its element's few partners, not by a binary search over the whole pattern (a
  // search per contact: with it the pattern's check cost 391 µs of a 20 × 20 wall's step at
  // h = 2 m, 199 µs without).
  std::int32_t top = -1;
  if (!pairs.empty()) top = pairs.back().first;
  group_run_.assign(static_cast<std::size_t>(top + 2), 0);
  for (const auto& pr : pairs) ++group_run_[static_cast<std::size_t>(pr.first) + 1];
  for (std::size_t a = 0; a + 1 < group_run_.size(); ++a) group_run_[a + 1] += group_run_[a];
  std::size_t outside = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    int group = -1;
    if (c.at.elem_a <= top)
      for (std::int32_t k = group_run_[static_cast<std::size_t>(c.at.elem_a)];
           k < group_run_[static_cast<std::size_t>(c.at.elem_a) + 1]; ++k)
        if (pairs[static_cast<std::size_t>(k)].second == c.at.elem_b) {
          group = first_group + k;
          break;
        }
    work_[i].group = group;
    outside += group < 0;
  }
  return outside;
}

ContactProblem::OutsidePattern ContactProblem::outside_pattern() const {
  const std::vector<Contact>& contacts = set_.contacts();
  OutsidePattern o;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (work_[i].group >= 0) continue;
    o.touching += set_.touching_at_start(contacts[i]);
    o.springs += (contacts[i].kn_now != 0) + (contacts[i].ks_now != 0);
  }
  return o;
}

void ContactProblem::start_strengths() {
  std::vector<Contact>& contacts = set_.step_contacts();
  const std::vector<ContactLaw>& laws = set_.laws();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    ContactWork& w = work_[i];
    const ContactLaw& law = laws[c.law];
    const bool closed = c.start_state != ContactState::open;
    w.bonded = w.cohesive ? w.kappa < w.cohesive->w_c : closed && !c.broken && law.tensile > 0;
    const double n = closed ? std::max(w.start_normal_force, 0.0) : 0.0;
    w.strength = closed ? shear_strength(law, n, c.length, c.broken, c.joint) + (w.cohesive ? w.c_coh : 0.0) : 0.0;
    // Elastic predictor (set_elastic_predictor): a new touching contact of a joint with strength
    // sticks until the fixed point has its normal force.
    if (!closed && elastic_predictor_ && w.gap0 <= eps_ && (law.tan_phi > 0 || law.cohesion > 0))
      w.strength = std::numeric_limits<double>::infinity();
  }
}

double ContactProblem::normal_force_at_rest(std::size_t i) const {
  const Contact& c = set_.contacts()[i];
  const ContactWork& w = work_[i];
  if (w.cohesive) return 0;
  return normal_at(set_.laws()[c.law], c, w, w.gap0, skin_).force;
}

double ContactProblem::law_force_at_rest(std::size_t i) const {
  return normal_at(set_.laws()[set_.contacts()[i].law], set_.contacts()[i], work_[i], work_[i].gap0, skin_).force;
}

double ContactProblem::shear_force_at_rest(std::size_t i) const {
  const Contact& c = set_.contacts()[i];
  if (c.start_state == ContactState::open || work_[i].cohesive) return 0;
  // The strength start_strengths() gives it (the iterations have moved work_[i].strength since):
  // from the normal force it carries, unbroken as it started.
  const ContactLaw& law = set_.laws()[c.law];
  ContactWork w = work_[i];
  w.strength = shear_strength(law, std::max(w.start_normal_force, 0.0), c.length, w.start_broken, c.joint);
  return shear_at(law, c, w, w.shear0).force;
}

void ContactProblem::forces_at(const Eigen::VectorXd& d, Eigen::VectorXd& r) {
  std::vector<Contact>& contacts = set_.step_contacts();
  const std::vector<ContactLaw>& laws = set_.laws();
  springs_.clear();
  double scale = 0;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    Contact& c = contacts[k];
    ContactWork& w = work_[k];
    const ContactLaw& law = laws[c.law];
    const int* dof = dofs_.data() + k * static_cast<std::size_t>(row_);
    const double* phi = phi_.data() + k * static_cast<std::size_t>(row_ / 2);
    const double tx = tangent_[2 * k], ty = tangent_[2 * k + 1];
    double dg = 0, ds = 0;
    row_dots(dof, phi, row_ / 2, tx, ty, d.data(), dg, ds);
    c.gap = w.gap0 + dg;
    c.shear = w.shear0 + ds;
    if (w.cohesive) {  // the damage of this iterate (its cohesion follows in update_strengths)
      // The tangential jump since the crack formed: the spring's shear and the slip.
      w.slip = std::abs(c.shear) + c.cohesive.slip + plastic_slip(c, w);
      w.kappa = std::max(c.cohesive.opening_max, effective_opening(*w.cohesive, c.gap, w.slip));
      w.bonded = w.kappa < w.cohesive->w_c;
    }
    const Spring n = w.linear ? straight_normal(w.kn0, w.bonded, c.gap, skin_) : normal_at(law, c, w, c.gap, skin_);
    const Spring t = w.linear ? straight_shear(w.ks0, w.strength, c.start_state == ContactState::sliding, c.slip_sign, c.shear)
                              : shear_at(law, c, w, c.shear);
    c.normal_force = n.force;
    c.kn_now = n.stiffness;
    c.capped = n.capped;
    c.shear_force = t.force;
    c.ks_now = t.stiffness;
    scale = std::max({scale, std::abs(n.force), std::abs(t.force)});
    if (n.stiffness != 0 || t.stiffness != 0) springs_.push_back({k, n.stiffness, t.stiffness});
    if (n.force == 0 && t.force == 0) continue;
    row_add(dof, phi, row_ / 2, tx, ty, n.force, -t.force, r.data());
  }
  force_scale_ = scale;
}

void ContactProblem::add_tangents(SystemMatrix& k) const {
  const std::vector<Contact>& contacts = set_.contacts();
  block_.resize(row_, row_);
  cn_.resize(static_cast<std::size_t>(row_));
  cs_.resize(static_cast<std::size_t>(row_));
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    const int group = work_[i].group;
    if ((c.kn_now == 0 && c.ks_now == 0) || group < 0) continue;  // outside the pattern: CG's
    const Row row_i = row(i);
    for (int j = 0; j < row_; ++j) {
      cn_[static_cast<std::size_t>(j)] = row_i.cn(j);
      cs_[static_cast<std::size_t>(j)] = row_i.cs(j);
    }
    const Eigen::Map<const Eigen::VectorXd> cn(cn_.data(), row_), cs(cs_.data(), row_);
    block_.noalias() = c.kn_now * cn * cn.transpose();
    if (c.ks_now != 0) block_.noalias() += c.ks_now * cs * cs.transpose();
    k.add_group(static_cast<std::size_t>(group), block_.data());
  }
}

void ContactProblem::tangent_times(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  // Over the contacts with a spring only (springs_, in the contacts' order): the same sums.
  const double* vv = v.data();
  double* yy = y.data();
  for (const TangentSprings& sp : springs_) {
    const int* dof = dofs_.data() + sp.contact * static_cast<std::size_t>(row_);
    const double* phi = phi_.data() + sp.contact * static_cast<std::size_t>(row_ / 2);
    const double tx = tangent_[2 * sp.contact], ty = tangent_[2 * sp.contact + 1];
    double a = 0, b = 0;
    row_dots(dof, phi, row_ / 2, tx, ty, vv, a, b);
    row_add(dof, phi, row_ / 2, tx, ty, a * sp.kn, b * sp.ks, yy);
  }
}

void ContactProblem::set_direction(const Eigen::VectorXd& delta) {
  std::vector<Contact>& contacts = set_.step_contacts();
  along_.clear();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    ContactWork& w = work_[k];
    double dg = 0, ds = 0;
    row_dots(dofs_.data() + k * static_cast<std::size_t>(row_), phi_.data() + k * static_cast<std::size_t>(row_ / 2),
             row_ / 2, tangent_[2 * k], tangent_[2 * k + 1], delta.data(), dg, ds);
    w.rate_gap = dg;
    w.rate_shear = ds;
    // The line search takes α ≥ 0 only. A contact open beyond the skin that opens further along
    // δ, neither bonded nor a softening face, has N = 0 at every such α (normal_at): its term is
    // 0. A shear term counts only with a strength (directional_force()).
    const Contact& c = contacts[k];
    const bool stays_open = !w.cohesive && !w.bonded && c.gap > skin_ && dg > 0;
    const auto index = static_cast<std::uint32_t>(k);
    if (dg != 0 && !stays_open)
      along_.push_back({c.gap, dg, w.kn0, 0.0, index, w.linear ? LineTerm::linear_normal : LineTerm::normal, w.bonded});
    if (ds != 0 && w.strength > 0)
      along_.push_back({c.shear, ds, w.ks0, w.strength, index, w.linear ? LineTerm::linear_shear : LineTerm::shear, false});
  }
}

double ContactProblem::directional_force(double alpha) const {
  const std::vector<Contact>& contacts = set_.contacts();
  const std::vector<ContactLaw>& laws = set_.laws();
  // Contact by contact in the contacts' order, normal term before shear term, as over all
  // contacts: the terms left out (set_direction()) are exactly zero, so the sum is the same.
  // (x + α·rate is c.gap + α·w.rate_gap, c.shear + α·w.rate_shear, as set_direction() found them.)
  double sum = 0;
  for (const LineTerm& e : along_) {
    const double at = e.x + alpha * e.rate;
    switch (e.kind) {
      case LineTerm::linear_normal:
        sum += straight_normal_force(e.k, e.bonded, at, skin_) * e.rate;
        break;
      case LineTerm::linear_shear:
        sum -= straight_shear_force(e.k, e.cap, at) * e.rate;
        break;
      case LineTerm::normal: {
        const Contact& c = contacts[e.contact];
        sum += normal_at(laws[c.law], c, work_[e.contact], at, skin_).force * e.rate;
        break;
      }
      case LineTerm::shear: {
        const Contact& c = contacts[e.contact];
        sum -= shear_at(laws[c.law], c, work_[e.contact], at).force * e.rate;
        break;
      }
    }
  }
  return sum;
}

ContactProblem::LineModelError ContactProblem::line_model_error() const {
  const std::vector<Contact>& contacts = set_.contacts();
  const std::vector<ContactLaw>& laws = set_.laws();
  // A normal spring closes when its tangent rises past half the law's initial stiffness between
  // α = 0 and 1 (touching contacts inside the skin included), opens when it falls below; a shear
  // spring slips when its tangent goes to 0, and a sliding one whose force changes sign or that
  // sticks again is "reversed or stuck".
  LineModelError out;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    const ContactWork& w = work_[k];
    const ContactLaw& law = laws[c.law];
    if (w.rate_gap != 0) {
      const Spring a = normal_at(law, c, w, c.gap, skin_), b = normal_at(law, c, w, c.gap + w.rate_gap, skin_);
      const double half = 0.5 * initial_normal_stiffness(law, c.length);
      const double error = (b.force - a.force + a.stiffness * w.rate_gap) * w.rate_gap;
      const int kind = a.stiffness < half && b.stiffness > half ? 0 : a.stiffness > half && b.stiffness < half ? 1 : 2;
      if (error != 0) {
        ++out.contacts[kind];
        out.error[kind] += error;
      }
      // Which softening faces the step missed: at a peak a face's matrix stiffness jumps (the
      // elastic one to 0, or the secant in tension to the crack set's kn·L in compression).
      if (w.cohesive && std::abs(error) > 1e-3 * std::abs(w.rate_gap * (b.force - a.force)))
        std::fprintf(stderr,
                     "    cohesive face %zu: gap %.4e m, damage %.4e -> %.4e m, rate %.3e m, stiffness %.3e -> %.3e N/m, "
                     "force %.4e -> %.4e N, error %.3e\n",
                     k, c.gap, c.cohesive.opening_max, w.kappa, w.rate_gap, a.stiffness, b.stiffness, a.force, b.force,
                     error);
    }
    if (w.rate_shear != 0 && w.strength > 0) {
      const Spring a = shear_at(law, c, w, c.shear), b = shear_at(law, c, w, c.shear + w.rate_shear);
      const double error = -(b.force - a.force - a.stiffness * w.rate_shear) * w.rate_shear;
      const int kind = a.stiffness > 0 && b.stiffness == 0                          ? 3
                       : a.stiffness == 0 && (b.stiffness > 0 || a.force * b.force < 0) ? 4
                                                                                      : 5;
      if (error != 0) {
        ++out.contacts[kind];
        out.error[kind] += error;
      }
    }
  }
  return out;
}

std::array<double, ContactProblem::kLineKinds> ContactProblem::line_model_residual(double alpha,
                                                                                 Eigen::VectorXd& total) const {
  const Eigen::Index unknowns = total.size();
  const std::vector<Contact>& contacts = set_.contacts();
  const std::vector<ContactLaw>& laws = set_.laws();
  std::array<Eigen::VectorXd, kLineKinds> r;
  for (Eigen::VectorXd& v : r) v.setZero(unknowns);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    const ContactWork& w = work_[k];
    const ContactLaw& law = laws[c.law];
    const Row row_k = row(k);
    // The kinds as line_model_error() sorts them, between α = 0 and the α taken.
    if (w.rate_gap != 0) {
      const Spring a = normal_at(law, c, w, c.gap, skin_), b = normal_at(law, c, w, c.gap + alpha * w.rate_gap, skin_);
      const double half = 0.5 * initial_normal_stiffness(law, c.length);
      const double e = b.force - (a.force - a.stiffness * alpha * w.rate_gap);
      const int kind = a.stiffness < half && b.stiffness > half ? 0 : a.stiffness > half && b.stiffness < half ? 1 : 2;
      if (e != 0)
        for (int i = 0; i < row_; ++i) r[kind][row_k.dofs[i]] += e * row_k.cn(i);
    }
    if (w.rate_shear != 0 && w.strength > 0) {
      const Spring a = shear_at(law, c, w, c.shear), b = shear_at(law, c, w, c.shear + alpha * w.rate_shear);
      const double e = b.force - (a.force + a.stiffness * alpha * w.rate_shear);
      const int kind = a.stiffness > 0 && b.stiffness == 0                          ? 3
                       : a.stiffness == 0 && (b.stiffness > 0 || a.force * b.force < 0) ? 4
                                                                                      : 5;
      if (e != 0)
        for (int i = 0; i < row_; ++i) r[kind][row_k.dofs[i]] -= e * row_k.cs(i);
    }
  }
  std::array<double, kLineKinds> out{};
  for (int kind = 0; kind < kLineKinds; ++kind) {
    out[kind] = r[kind].lpNorm<Eigen::Infinity>();
    total += r[kind];
  }
  return out;
}

int ContactProblem::softening_faces() const {
  int n = 0;
  for (const ContactWork& w : work_)
    if (w.cohesive && w.kappa < w.cohesive->w_c && cohesive_state(*w.cohesive, w.k_len, w.kappa).factor < 1) ++n;
  return n;
}

int ContactProblem::update_strengths(double force_floor) {
  std::vector<Contact>& contacts = set_.step_contacts();
  const std::vector<ContactLaw>& laws = set_.laws();
  int changed = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    Contact& c = contacts[i];
    ContactWork& w = work_[i];
    const ContactLaw& law = laws[c.law];
    const bool closed = c.normal_force > 0 || w.bonded;
    // The friction fixed point: the strength follows the normal force of the solution. A change
    // matters only where the shear force is at or near the limit (or on a hyperbola, whose
    // whole curve scales with the strength). (Keeping the strength of the normal force a
    // contact carried into the step instead — one convex problem per step — was measured: a
    // sliding block then ends 0.17–0.31 % off Coulomb's answer, because its normal forces shift
    // between its corners as it slides.)
    const double n = closed ? std::max(c.normal_force, 0.0) : 0.0;
    if (w.cohesive) set_cohesion(c, w);
    double s = closed ? shear_strength(law, n, c.length, c.broken, c.joint, step_shear(c, w)) + (w.cohesive ? w.c_coh : 0.0)
                      : 0.0;
    // Barely touching (tanφ·N + c·L below F_tol): no shear spring to switch on and off. The
    // strength falls to zero along a ramp, 2s − F_tol from F_tol down to F_tol / 2, not in one
    // jump at F_tol: a jump of F_tol is a change the fixed point counts, so contacts whose N
    // hovers around it cycled — zero strength lets a block slide, which moves N above the cut,
    // whose strength holds it, which moves N below — and kept a step iterating until
    // kMaxStrengthRounds (on the DDA code's dynamic 20 × 20 wall, 2.3 of 7.3 solves per step
    // came after the step first reached balance; 0.4 with the ramp). Continuous, the fixed point
    // settles; the strength is still off by at most F_tol / 2, within the tolerance.
    if (s < force_floor) s = std::max(0.0, 2 * s - force_floor);
    const double moved = std::abs(s - w.strength);
    if (!std::isfinite(w.strength)) {
      ++changed;  // the elastic predictor's stick ends: solve again with the real strength
    } else if (moved > kContactTolerances.strength_change * std::max(s, w.strength) && moved > force_floor) {
      const bool matters = !linear_shear(law) ||
                           std::abs(trial_shear(law, c, w, c.shear)) >= kContactTolerances.near_limit * std::min(s, w.strength);
      if (matters) ++changed;
    }
    w.strength = s;
  }
  return changed;
}

ContactProblem::Breaks ContactProblem::break_at_peak() {
  std::vector<Contact>& contacts = set_.step_contacts();
  const std::vector<ContactLaw>& laws = set_.laws();
  // Only at a solution: an iterate of the friction fixed point may pass through forces the
  // solution does not reach (a strength lagging its normal force, a bond stretched by a
  // direction the line search then shortens), and breaking there lost the cohesion of joints
  // that never slid (a Hoek–Bray wedge at F = 2.26 counted 26 broken bonds).
  Breaks b;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    Contact& c = contacts[i];
    ContactWork& w = work_[i];
    const ContactLaw& law = laws[c.law];
    if (c.broken || !(law.cohesion > 0 || law.tensile > 0)) continue;
    const bool tension = w.bonded && c.normal_force < -law.tensile * c.length;
    const bool closed = c.normal_force > 0 || w.bonded;
    const bool shear = !tension && closed && w.strength > 0 && slides(law, c, w);
    if (!tension && !shear) continue;
    c.broken = true;
    w.bonded = false;
    // The strength it has broken: the step's next solve starts from this solution.
    w.strength = shear_strength(law, std::max(c.normal_force, 0.0), c.length, true, c.joint, step_shear(c, w));
    ++(tension ? b.tensile : b.shear);
    // A perfectly plastic joint without tension (c_r = c, T = 0) keeps the same strength: the
    // solution stands as it is.
    if (law.tensile > 0 || law.residual_cohesion != law.cohesion) b.resolve = true;
  }
  return b;
}

void ContactProblem::settle_states() {
  std::vector<Contact>& contacts = set_.step_contacts();
  const std::vector<ContactLaw>& laws = set_.laws();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    Contact& c = contacts[i];
    const ContactWork& w = work_[i];
    const ContactLaw& law = laws[c.law];
    const bool closed = c.normal_force > 0 || w.bonded;
    ContactState now = ContactState::open;
    if (closed) now = slides(law, c, w) ? ContactState::sliding : ContactState::locked;
    if (now == ContactState::sliding) c.slip_sign = c.shear > 0 ? 1 : -1;
    if (now == ContactState::open) {
      c.normal_force = 0;
      c.shear_force = 0;
      c.kn_now = c.ks_now = 0;
      if (c.start_state != ContactState::open) c.broken = true;  // cohesion lost once it opens
    }
    const ContactState before = c.start_state;
    if (before == ContactState::open && now != ContactState::open) ++set_.events.closed;
    if (before != ContactState::open && now == ContactState::open) ++set_.events.opened;
    if (before != ContactState::sliding && now == ContactState::sliding) ++set_.events.slid;
    if (before == ContactState::sliding && now == ContactState::locked) ++set_.events.stuck;
    c.state = now;
  }
  // The open contacts' springs are gone: tangent_times() follows.
  springs_.erase(std::remove_if(springs_.begin(), springs_.end(),
                                [&](const TangentSprings& sp) {
                                  const Contact& c = contacts[sp.contact];
                                  return c.kn_now == 0 && c.ks_now == 0;
                                }),
                 springs_.end());
}

void ContactProblem::commit() {
  std::vector<Contact>& contacts = set_.step_contacts();
  const std::vector<ContactLaw>& laws = set_.laws();
  max_damage_jump_ = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    Contact& c = contacts[i];
    const ContactWork& w = work_[i];
    const ContactLaw& law = laws[c.law];
    // The joint law's memory follows the accepted step (a closed contact's shear travel and
    // dilation, its largest closure).
    const double dilation0 = c.joint.dilation;
    if (c.state != ContactState::open)
      c.joint = advance_joint_memory(law, c.joint, c.normal_force, c.length, step_shear(c, w), -c.gap);
    c.dilation_step = c.joint.dilation - dilation0;
    if (w.cohesive) {
      // The damage of the accepted solution, and what its softening dissipated over the step
      // (cohesive_law.h D(κ), a function of the damage alone); the cohesion's share of the
      // slip's work, which the friction work counts too (energy.h takes it out there).
      const double slip = c.state == ContactState::sliding ? plastic_slip(c, w) : 0.0;
      c.cohesive_step = c.length * (cohesive_dissipation(*w.cohesive, w.k_len, w.kappa) -
                                    cohesive_dissipation(*w.cohesive, w.k_len, c.cohesive.opening_max));
      c.cohesion_slip_work = w.c_coh * slip;
      max_damage_jump_ = std::max(max_damage_jump_, (w.kappa - c.cohesive.opening_max) / w.cohesive->w_c);
      c.cohesive.opening_max = w.kappa;
      c.cohesive.slip += slip;
    }
    if (c.state == ContactState::open) {
      c.shear_el = 0;
    } else if (c.state == ContactState::locked) {
      c.shear_el = c.shear;
    } else {
      // Sliding: the spring stays loaded at the friction limit (return mapping).
      c.shear_el = c.slip_sign * shear_at_cap(law, c, w, w.strength);
    }
  }
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    const ContactLaw& law = laws[c.law];
    if (c.broken && !work_[i].start_broken && (law.cohesion > 0 || law.tensile > 0)) ++set_.events.broken;
  }
}

}  // namespace nmm::solve
