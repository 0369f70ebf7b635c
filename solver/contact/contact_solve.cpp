// The step's contact problem (docs/contact.md "The step's contact problem").
//
// With each contact's shear strength S fixed, a step of Shi's implicit scheme is the minimiser
// of a convex, continuously differentiable energy of the step's increment d:
//     Π(d) = ½ dᵀA d − bᵀd + Σ_c Ψn(g_c) + Σ_c Ψs(s_c),   g_c = g0 + cnᵀd,  s_c = s_el + csᵀd
// A: stiffness, inertia 2M/Δt² (or M/(βΔt²)), fixed points, supports (symmetric positive
// definite in dynamic and DDA-static runs); b: loads, initial stress, inertia terms.
// Ψn(g) = ∫ N dδ over the closure δ = −g > 0 (constant spring ½kn·δ²; Bandis–Barton, whose N
// rises with δ): convex. A bond (tensile strength, unbroken) continues the spring into tension.
// Ψs(s) = the elastoplastic spring: ½ks·s² while |ks·s| < S, S·|s| − S²/(2ks) beyond (the
// hyperbolic law: the integral of its capped, non-decreasing force): convex.
// Its gradient is the residual's negative: r(d) = b − A d + Σ N_c·cn_c − Σ T_c·cs_c.
//
// Newton: H δ = r with H = A + Σ kn_t·cn cnᵀ + Σ ks_t·cs csᵀ (tangents at d; a sliding
// contact's ks_t = 0), then d ← d + α δ with α the root of the directional derivative
//     ψ(α) = r(d + αδ)ᵀδ = (b − A d)ᵀδ − α δᵀAδ + Σ N_c(α)·Δg_c − Σ T_c(α)·Δs_c,
// which is non-increasing in α because Π is convex (an exact line search: a regula falsi on a
// monotone, piecewise smooth function). Every accepted α lowers Π, so contact states cannot
// cycle; a convex piecewise-quadratic Π is minimised in finitely many Newton steps once the
// active set is right. Any symmetric positive definite H gives a descent direction, so H may also
// be shaped (a contact within ε of touching gets its spring's tangent) without losing this.
//
// Tolerance (docs/contact.md "Tolerance and error"). The step is accepted when
//     ‖r‖∞ ≤ F_tol = τ · max_c max(|N_c|, |T_c|)      (τ: solver.contact_tolerance, 1e-3)
// (floored at 1e-12·‖b‖∞, round-off), no friction strength is off by more than
// max(0.1 % of itself, F_tol), and — where a joint law softens — the displacement that would
// remove the residual, estimated with the kept factorisation, is within u_tol:
//     ‖P⁻¹r‖∞ ≤ u_tol = 3e-4 · τ · w0                 (contact_solve.h displacement_tolerance)
// A soft contact (a joint near its strength) turns F_tol into F_tol / k_t, which the force test
// alone does not bound; a constant spring's error is F_tol / k at most. The estimate is the
// first step of the CG run that follows a refusal, which takes it over instead of solving again.
// Not "no contact changed state": a contact touching at zero gap may
// show either state without moving a force by more than its spring times the gap, and once that
// is below F_tol it cannot keep a step iterating — the tolerance is the hysteresis of the
// open–close iteration, in forces rather than in a band of penetration: a contact may carry a
// force it should not, or lack one it should, of at most F_tol, and every unknown is in balance
// within F_tol. The error this leaves in a step's displacement is at most ‖H⁻¹‖·F_tol·√n and in
// practice F_tol over the stiffness the unknown is held by. In a static step it does not
// accumulate: the next step's balance starts from the stresses and contact forces this one left.
// With inertia, Shi's velocity update turns it into the impulse of a force F_tol over the step,
// which does not vanish as Δt → 0: residuals of one sign act like an extra force of up to F_tol on
// a moving body (docs/contact.md "What the tolerance allows in a motion"). So the residual the
// step ends with — re-evaluated with the strengths of the accepted normal forces, whose lag within
// the strength test has one sign too — is returned, and the time stepper hands each block's net
// share of it to the next step (block_momentum.h): the momentum errors then telescope. Measured on
// the sliding block at τ = 1e-3 with directions solved to 1e-2 (kForcing): +0.084 % off Coulomb
// without the hand-on, +0.037 % with it, as with τ = 1e-8.
//
// Start. Any d₀ will do for the argument above (Π is convex, every accepted α lowers it): a
// step starts from d = 0, or from a guess — the same step's solution on the mesh before a crack
// re-cut it (ContactStart::guess), which then differs from the answer by what the new cracks
// open, so the friction fixed point below starts near its end instead of from the step's start.
//
// Friction. S = tanφ·N + c·L needs the normal force. Each of the first kMergedUpdates Newton
// iterates updates every strength from its own N (the friction state lags one iterate, as in
// DDA's open–close passes, instead of a round of full solves per update); for fixed strengths
// each iteration lowers the convex Π_S. Should the step need more iterates, strengths are
// updated only at an iterate in balance (a round of the fixed point per update, each round a
// convex problem solved to the tolerance), and after kMaxStrengthRounds rounds the step keeps
// the strengths it has (counted: summary.json steps_with_unsettled_friction).
// Cohesion and tensile bonds do not break within this solve: the strengths are those of the
// bonds the step started with (or broke at an earlier solution of the same step); the time
// stepper breaks the contacts that reach their peak at the solution and solves again
// (ContactProblem::break_at_peak, contact_effect.cpp).
//
// Linear solves. H differs from the matrix P of the last factorisation by the springs that
// switched and, from one step to the next, by the small change of A with the geometry. Conjugate
// gradients preconditioned by P converge in at most r + 1 iterations when H − P has rank r, and
// far fewer when the switched springs are alike (their eigenvalues of P⁻¹H cluster), so a few
// switched contacts cost a few factor solves instead of a factorisation, and a settled system
// needs no factorisation at all. Each CG run gets a budget of iterations worth one factorisation
// (cg_budget: from the factor's flops and nonzeros, capped by a measurement; not from clocks, so
// a run is the same on every machine): when it is spent, H is factorised (P ← H) and the
// direction solved directly. CG is tried whatever the number of switched springs: predicting
// from that number (rank r against the budget) refactorised 4× as often as needed, since CG
// converged in 2–10 iterations where r was in the thousands (bench/contact_bench --peer,
// docs/notes/2026-11-linear-algebra.md).
//
// The system matrix's pattern holds the element pairs of the step's contacts, but for a few
// (contact_effect.cpp update_pattern: with inertia it grows once more than a few touching
// contacts lie outside it, and it sheds the unused pairs now and then). A contact whose pair is missing is left out of
// P by add_tangents(), and the direction after a factorisation is CG's with the new P (H − P of
// the rank of the left-out springs).
//
// A CG run that needs more than half its budget shows the kept factorisation is far from H: the
// next direction comes from a new factorisation, which the following runs then reuse.
#include "solver/contact/contact_solve.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include "common/stopwatch.h"

namespace nmm::solve {

namespace {

constexpr int kMaxNewton = 60;             // Newton iterations per step
// Newton iterations per step while a cohesive face softens (cohesive_law.h). The matrix holds
// nothing for a face on its softening branch (its negative tangent would make H indefinite), so
// where faces cross their peak the line search stops the step at 4–6 % of the Newton step and
// the residual falls 2–4 % an iteration (Petersson's beam, docs/fracture.md "Cohesive
// softening": 10× → 2× its tolerance in 40 iterations). Measured on 2026-11-30 with 300 instead
// of 60: the beam at h 0.025, 0.0167, 0.0125 m went on to a deflection of 0.564, 0.507, 0.298 mm
// instead of stopping at 0.306, 0.330, 0.276 mm, the cohesive bar at h 0.025 m reached its end
// instead of stopping at t = 0.109 s, and the bars at h 0.1 and 0.05 m did not change bit for
// bit; with 1000 the beam at h 0.025 m went to 0.607 mm, in 1.6× the time. What still stops
// those runs is a cycle (two or more iterates repeating), which no allowance cures.
constexpr int kMaxNewtonSoftening = 300;
constexpr int kMergedUpdates = 8;          // iterates whose strengths follow their own N
constexpr int kMaxStrengthRounds = 12;     // strength updates at balance before the step keeps them
constexpr double kRoundOff = 1e-12;        // the tolerance's floor, × ‖b‖∞

// Inexact Newton's forcing term η: CG solves a direction only to ‖Hδ − r‖₂ ≤ η‖r‖₂ (or 0.3·F_tol,
// whichever is larger). Far from balance — a settling wall's step starts at about 1e4 × F_tol —
// solving the linear model to 1e-6 of r buys nothing: the contacts that switch along δ and the
// friction strengths that follow it leave tens × F_tol anyway, and a first CG run that needs more
// than half its budget makes the second iterate factorise. Measured on the DDA code's walls
// (contact_bench --peer, 20 × 20, 100 steps, 2026-11-27, before the residual was handed on;
// solves / factorisations / CG per step):
//   η       static                 dynamic
//   1e-6    3.54 / 1.63 / 19.0     9.83 / 5.61 / 44.1
//   1e-3    3.74 / 0.95 / 13.5    10.40 / 4.81 / 40.4
//   1e-2    3.63 / 0.85 / 12.8     9.32 / 4.08 / 36.4
//   1e-1    4.12 / 0.61 / 13.4    10.18 / 3.41 / 30.5
// Truncated PCG from δ = 0 gives a descent direction at any η (each CG iterate minimises the
// quadratic model over a Krylov space that contains P⁻¹r, so rᵀδ > 0), the exact line search keeps
// Π falling, and acceptance reads the true residual (Dembo, Eisenstat & Steihaug 1982). What an
// inexact path changes is where within the tolerance a step lands; with inertia that is handed
// on to the next step (block_momentum.h), without it the next step's balance starts from it.
constexpr double kForcing = 1e-2;

// Near balance the direction need not solve the linear model further than the tolerance asks:
// CG also stops once its residual is within this share of F_tol in the ∞-norm — the accepted
// step's own test — leaving the rest of F_tol to the contacts that switch along the direction.
// Before, only the 2-norm counted (to 0.3·F_tol), which on a wall of thousands of unknowns near
// balance asks each of them for far less than F_tol: CG spent its budget and a factorisation
// followed. 30 of the 35 factorisations after the first step of the static 30 × 30 wall's
// first 100 steps came at residuals of 1.3–10 × F_tol (16 of them within 3 ×). Measured on the
// DDA code's walls (contact_bench --peer, h = 2 m, 200 steps, one thread, 2026-11-28), ms per
// step (solves / factorisations per step):
//   share     static 20 × 20       static 30 × 30       dynamic 20 × 20      dynamic 30 × 30
//   — (2-norm) 17.1 (2.31 / 0.32)  42.1 (2.15 / 0.32)   41.2 (4.52 / 1.75)   128 (4.84 / 2.27)
//   0.5       15.7 (2.48 / 0.25)   40.7 (2.33 / 0.26)   34.8 (4.62 / 1.41)   109 (4.92 / 1.84)
//   0.7       14.7 (2.56 / 0.19)   37.5 (2.46 / 0.20)   33.2 (4.69 / 1.28)   105 (4.98 / 1.74)
//   0.9       15.2 (2.44 / 0.23)   39.1 (2.48 / 0.20)   34.5 (4.54 / 1.23)   108 (4.98 / 1.61)
//   1.0       15.5 (2.66 / 0.20)   39.0 (2.54 / 0.16)   32.2 (4.62 / 1.19)   107 (5.19 / 1.59)
// A step is accepted on its true residual as before: this changes the path to balance, not
// where balance is.
constexpr double kDirectionBalance = 0.7;

// CG iterations worth one numeric factorisation. From flops: a factorisation's over one
// iteration's (a factor solve pair, a product with the matrix, the contacts' rows). Measured
// (thread CPU time, one core, contact_bench --trace) on the brick walls of
// bench/contact_bench.cpp from 2.4k to 20k unknowns, one factorisation costs 8.5–11 iterations
// (1.3 / 8.0 / 26 ms against 0.15 / 0.72 / 2.9 ms), while the flop ratio grows with the size
// (16 → 57): the factorisation's dense kernels run faster per flop on larger supernodes, the
// memory-bound solves do not. (18–38 before the factorisation ran without libgomp's per-region
// overhead, solver_threads.cpp.) So the flop ratio, at most kMaxFactorisationInCgIterations.
// Counts, not clocks, so a run is the same on every machine.
constexpr double kMaxFactorisationInCgIterations = 10;

// Friction strengths that may move in one iterate, per CG iteration of the budget, for CG on the
// kept factorisation to be worth trying. Measured on the DDA code's walls (contact_bench --peer,
// 20 × 20, static and dynamic, 100 steps each, budget 10): CG converged within its budget in
// 90 % of the runs after at most 4 moved strengths, 83 % after 5–19, 36 % after 20–49, 3 % after
// 50–99 and never after 100 or more — those runs spent their whole budget and then factorised.
constexpr int kMovedPerCgIteration = 5;

int cg_budget(const SystemMatrix& k, std::size_t contacts) {
  const double per_iteration = 4.0 * k.factor_nonzeros() + 4.0 * static_cast<double>(k.nonzeros()) +
                               100.0 * static_cast<double>(contacts);
  return static_cast<int>(std::clamp(k.factor_flops() / per_iteration, 3.0, kMaxFactorisationInCgIterations));
}

// y = H v.
void hessian_times(const SystemMatrix& k, const ContactProblem& contacts, const Eigen::VectorXd& v,
                   Eigen::VectorXd& y) {
  k.saved_times(v, y);
  contacts.tangent_times(v, y);
}

// z = C r, the preconditioner of the CG runs: C = (P + E)⁻¹ P (P + E)⁻¹ from the kept
// factorisation of P + E (E: the regularisation at n ≥ 1, 0 at n = 0, where C = P⁻¹). It is
// symmetric, zero on the null space of P (the zero-field combinations, which H shares) and
// (P + E)⁻¹·(1 − O(ε/λ)) on the rest, so the iterates stay out of the null space: a residual's
// round-off component there, which (P + E)⁻¹ alone amplifies by 1/ε, is not followed
// (docs/higher-order-covers.md "Keeping the null space out"). No iterative refinement: a
// preconditioner needs none.
void precondition(const SystemMatrix& k, const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  k.solve_unrefined(r, z);  // into z's storage: no allocation per CG iteration
  k.remove_null_part(z);
}

// Preconditioned CG for H x = r to ‖H x − r‖₂ ≤ target or ‖H x − r‖∞ ≤ target_inf; false when
// the budget is spent or H shows a non-positive curvature (then the caller factorises H).
// `first`, if given, is C r already computed (the displacement test's estimate).
bool pcg(const SystemMatrix& k, const ContactProblem& contacts, const Eigen::VectorXd& r, double target,
         double target_inf, int budget, Eigen::VectorXd& x, ContactSolveStats& stats,
         const Eigen::VectorXd* first = nullptr) {
  x.setZero(r.size());
  Eigen::VectorXd res = r, z(r.size()), hp(r.size());
  if (first)
    z = *first;
  else
    precondition(k, res, z);
  Eigen::VectorXd p = z;
  double rz = res.dot(z);
  for (int it = 1; it <= budget; ++it) {
    ++stats.cg_iterations;
    hessian_times(k, contacts, p, hp);
    const double php = p.dot(hp);
    if (!(php > 0)) return false;
    const double a = rz / php;
    x.noalias() += a * p;
    res.noalias() -= a * hp;
    if (res.norm() <= target || res.lpNorm<Eigen::Infinity>() <= target_inf) return true;
    precondition(k, res, z);
    const double rz_new = res.dot(z);
    p = z + (rz_new / rz) * p;
    rz = rz_new;
  }
  ++stats.cg_aborted;
  return false;
}

// Root of the non-increasing ψ on α ≥ 0 (ψ(0) > 0), by bracketing and the Illinois variant of
// regula falsi. α = 1 (the Newton step) is taken when ψ(1) is within `tol` of 0.
template <class F>
double line_search(const F& psi, double psi0, double tol) {
  double a = 0, fa = psi0, b = 1, fb = psi(1.0);
  if (std::abs(fb) <= tol) return 1.0;
  while (fb > 0) {  // the step is too short (a spring that turned out open): go further
    if (b >= 1024) return b;
    a = b;
    fa = fb;
    b *= 2;
    fb = psi(b);
  }
  int side = 0;
  double c = b;
  for (int i = 0; i < 100; ++i) {
    c = (a * fb - b * fa) / (fb - fa);
    const double fc = psi(c);
    if (std::abs(fc) <= tol || b - a <= 1e-14 * b) return c;
    if (fc > 0) {
      a = c;
      fa = fc;
      if (side == 1) fb *= 0.5;
      side = 1;
    } else {
      b = c;
      fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    }
  }
  return c;
}
}  // namespace

Outcome solve_contact_step(SystemMatrix& system, ContactProblem& contacts, const Eigen::VectorXd& b,
                                       double tau, double u_tol, Eigen::VectorXd& d, ContactSolveStats& stats,
                                       Eigen::VectorXd* residual, ContactStart start) {
  // NMM_TRACE_CONTACT_SOLVE=1 prints every Newton iteration and friction update on stderr.
  static const bool trace = std::getenv("NMM_TRACE_CONTACT_SOLVE") != nullptr;
  const Eigen::Index n = b.size();
  Eigen::VectorXd ra = b;  // b − A d, kept up to date without a product per iteration
  Eigen::VectorXd r(n), delta(n), adelta(n);
  if (start != ContactStart::zero) {
    // warm: from the solution of the same step before contacts broke (ContactProblem::break_at_peak
    // has set their broken strengths; the others are the fixed point's at d). guess: from the
    // solution on the mesh before a re-cut, with the step's start strengths.
    if (start == ContactStart::guess) contacts.start_strengths();
    system.saved_times(d, adelta);
    ra -= adelta;
  } else {
    d.setZero(n);
    contacts.start_strengths();
  }
  const double floor = kRoundOff * b.lpNorm<Eigen::Infinity>() + std::numeric_limits<double>::min();
  bool refresh = false;       // factorise H for the next direction
  int rounds = 0;             // strength updates at an iterate in balance
  double last_r = std::numeric_limits<double>::infinity();
  bool last_full_cg = false;  // the last step was a full (α = 1) step along a CG direction
  double tol = floor, r_norm = 0;
  double u_err = -1;  // m, the iterate's displacement error estimate ‖P⁻¹r‖∞ (−1: not computed yet)
  // r ← the residual at d, with its ∞-norm and the tolerance (which follows the contact forces).
  const auto evaluate = [&]() {
    r = ra;
    contacts.forces_at(d, r);
    tol = std::max(tau * contacts.force_scale(), floor);
    r_norm = r.lpNorm<Eigen::Infinity>();
    u_err = -1;
  };
  // In balance: no unknown out of balance by more than F_tol, and the displacement that would
  // remove what is left, estimated with the kept factorisation (P⁻¹r, the first step of the
  // next CG run), within u_tol. Estimated once per iterate.
  Eigen::VectorXd z(n);
  const auto in_balance = [&]() {
    if (r_norm > tol) return false;
    if (!(u_tol > 0) || !system.has_factor()) return true;
    if (u_err < 0) {
      const Stopwatch t0;
      precondition(system, r, z);
      u_err = z.lpNorm<Eigen::Infinity>();
      ++stats.displacement_checks;
      if (u_err > u_tol) ++stats.displacement_refusals;
      stats.cg_seconds += t0.seconds();
      if (trace) std::fprintf(stderr, "displacement error %.3e m, tolerance %.3e m\n", u_err, u_tol);
    }
    return u_err <= u_tol;
  };
  for (int it = 0;; ++it) {
    evaluate();
    // Friction strengths follow this iterate's normal forces (not at the first, whose N are the
    // last step's, already in the strengths) for the first kMergedUpdates iterates; after that,
    // only once the iterate is in balance (a round of the fixed point per update), so a strength
    // swinging between two values cannot keep Newton from converging.
    // From a guess the first iterate's N are the guess's, not the last step's: they count too.
    const bool merged = (it > 0 || start == ContactStart::guess) && it <= kMergedUpdates;
    int moved = 0;  // friction strengths this iterate moved
    if (merged || r_norm <= tol) {
      moved = contacts.update_strengths(tol);
      if (trace) std::fprintf(stderr, "it %d strengths moved %d at r/tol %.3e\n", it, moved, r_norm / tol);
      if (moved == 0 && in_balance()) break;
      if (moved > 0) {
        ++stats.strength_updates;
        if (in_balance() && ++rounds >= kMaxStrengthRounds) {
          ++stats.unsettled;  // the fixed point still moves: the step keeps these strengths
          break;
        }
        evaluate();
      }
    }
    if (in_balance()) continue;  // the strengths moved without moving a force beyond the tolerance
    // A full Newton step that did not halve the residual: no contact changed its spring along
    // it (else α < 1), so the direction was not H⁻¹r — CG's recursive residual drifted from the
    // true one (ill-conditioned H, e.g. higher cover orders). The next direction is solved
    // directly.
    if (last_full_cg && r_norm > 0.5 * last_r) refresh = true;
    last_r = r_norm;
    const int max_newton = contacts.softening_faces() > 0 ? kMaxNewtonSoftening : kMaxNewton;
    if (it >= max_newton)
      return {StopCode::contact_not_converged, "the contact solve did not converge in " + std::to_string(max_newton) +
                                         " Newton iterations (residual " + std::to_string(r_norm / tol) +
                                         " × its tolerance)"};
    ++stats.newton;
    // Direction: CG on the reused factorisation, or a new factorisation of H. CG stops at the
    // forcing term's 2-norm, or once what it leaves is within kDirectionBalance · F_tol in the
    // ∞-norm (the 2-norm floor bounds the ∞-norm too).
    bool solved = false;
    const int budget = cg_budget(system, contacts.contacts().size());
    const double cg_target = std::max(kForcing * r.norm(), 0.3 * tol);
    const double cg_target_inf = kDirectionBalance * tol;
    // Many strengths moved at once: the springs are far from the kept factorisation's, and CG
    // on it would only spend its budget before the factorisation (kMovedPerCgIteration).
    if (moved > kMovedPerCgIteration * budget) refresh = true;
    if (system.has_factor() && !refresh) {
      const Stopwatch t0;
      const long before = stats.cg_iterations;
      solved = pcg(system, contacts, r, cg_target, cg_target_inf, budget, delta, stats,
                   u_err >= 0 ? &z : nullptr);
      // A run that needed more than half its budget says the factorisation is far from H: the
      // next direction is cheaper from a new one (which later runs reuse) than from another
      // long CG run.
      refresh = solved && 2 * (stats.cg_iterations - before) > budget;
      stats.cg_seconds += t0.seconds();
    } else {
      refresh = false;
    }
    if (!solved) {
      const Stopwatch t0;
      system.restore();
      contacts.add_tangents(system);
      const bool ok = system.factorize();
      ++stats.factorisations;
      stats.factorisation_seconds += t0.seconds();
      if (!ok) return {StopCode::unconstrained, "the system matrix is not positive definite"};
      const std::size_t outside = contacts.outside_pattern().springs;
      // A factor held in single precision (the largest runs, system_matrix.h) solves H exactly
      // only through refinement passes in double (to 1e-13 of r: one or two more solve pairs and
      // products), far past the forcing term a direction needs. Its direction is CG's on the new
      // factor instead, whose first iteration is the unrefined solve and which stops at the
      // forcing term as any other run; should it not, the refined solve. Measured on the
      // 10,000-block wall at h = 0.5 m: docs/performance.md (h), "The direction after a
      // factorisation".
      if (outside == 0 && !system.single_precision()) {
        delta = system.solve(r);
        // The exact solve leaves r's round-off null component amplified by 1/ε in δ (zero field,
        // but rᵀδ then gives the line search a false slope): remove it.
        system.remove_null_part(delta);
      } else {
        // Springs of pairs not in the pattern are not in the factorisation: H − P has rank
        // `outside`, which CG resolves in about as many iterations (with none outside, P = H up
        // to the factor's rounding). Should it not, P's own direction P⁻¹r is still one of
        // descent (P is symmetric positive definite).
        const Stopwatch t2;
        const int cap = outside == 0 ? budget : std::max(budget, 2 * static_cast<int>(outside) + 10);
        if (!pcg(system, contacts, r, cg_target, cg_target_inf, cap, delta, stats)) {
          delta = system.solve(r);
          system.remove_null_part(delta);
        }
        stats.cg_seconds += t2.seconds();
      }
    }
    if (!delta.allFinite())
      return {StopCode::direction_not_finite, "the contact solve produced a displacement that is not finite"};
    // Exact line search on ψ(α) = r(d + αδ)ᵀδ.
    const Stopwatch t1;
    system.saved_times(delta, adelta);
    const double ra_delta = ra.dot(delta), q = delta.dot(adelta);
    contacts.set_direction(delta);
    const auto psi = [&](double alpha) { return ra_delta - alpha * q + contacts.directional_force(alpha); };
    const double psi0 = psi(0.0);
    if (!(psi0 > 0)) {
      // Not a descent direction: only round-off at a converged point does this.
      system.drop_factor();
      if (r_norm <= 1e3 * tol) break;
      continue;
    }
    const double alpha = line_search(psi, psi0, 1e-8 * psi0);
    last_full_cg = solved && alpha == 1.0;
    if (trace)
      std::fprintf(stderr, "it %d r/tol %.3e solved_cg %d alpha %.6g psi1 %.3e cg %ld fac %ld budget %d\n", it,
                   r_norm / tol, solved ? 1 : 0, alpha, psi(1.0) / psi0, stats.cg_iterations, stats.factorisations,
                   budget);
    stats.line_search_seconds += t1.seconds();
    if (trace) {
      // What stopped the step short of α = 1: each kind's share of ψ(1)'s departure from the
      // Newton model, over ψ(0).
      const ContactProblem::LineModelError m = contacts.line_model_error();
      std::fprintf(stderr, "  model error over psi0:");
      for (int kind = 0; kind < ContactProblem::kLineKinds; ++kind)
        std::fprintf(stderr, " %s %d %.2e%s", ContactProblem::kLineKindNames[kind], m.contacts[kind], m.error[kind] / psi0,
                     kind + 1 < ContactProblem::kLineKinds ? " |" : "\n");
      // The residual at the point taken, over F_tol, and its parts: what the linear model leaves
      // (r − αHδ: CG's inexact direction, and 1 − α of it when the search stopped short) and
      // each kind's departure from it (they may cancel: the parts do not add up in the ∞-norm).
      Eigen::VectorXd model(n);
      hessian_times(system, contacts, delta, model);
      model = r - alpha * model;
      const double linear = model.lpNorm<Eigen::Infinity>();
      const std::array<double, ContactProblem::kLineKinds> left = contacts.line_model_residual(alpha, model);
      std::fprintf(stderr, "  model residual over tol: all %.2e | linear %.2e |", model.lpNorm<Eigen::Infinity>() / tol,
                   linear / tol);
      for (int kind = 0; kind < ContactProblem::kLineKinds; ++kind)
        std::fprintf(stderr, " %s %.2e%s", ContactProblem::kLineKindNames[kind], left[kind] / tol,
                     kind + 1 < ContactProblem::kLineKinds ? " |" : "\n");
    }
    d.noalias() += alpha * delta;
    ra.noalias() -= alpha * adelta;
  }
  // The forces the step ends with: the accepted d with the strengths of its own normal forces
  // (update_strengths() set them above; they moved less than the tolerance, which still leaves
  // one sign to their lag). What is out of balance then is the residual the step hands on.
  const double u_accepted = u_err;
  evaluate();
  if (residual) *residual = r;
  stats.max_force_tolerance = std::max(stats.max_force_tolerance, tol);
  stats.max_displacement_error = std::max(stats.max_displacement_error, std::max(u_accepted, 0.0));
  double kn_min = std::numeric_limits<double>::infinity();
  for (const Contact& c : contacts.contacts())
    if (c.kn_now > 0 && c.normal_force > tol) kn_min = std::min(kn_min, c.kn_now);  // carrying a force
  if (std::isfinite(kn_min)) stats.max_gap_error = std::max(stats.max_gap_error, tol / kn_min);
  return {};
}

}  // namespace nmm::solve
