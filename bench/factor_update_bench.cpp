// Reusing a factorisation when contact springs switch: three ways measured against each other on
// the DDA code's brick walls (reference/brick_wall.h peer_wall), static and dynamic.
//
//   factor_update_bench [--sizes 10,20,30] [--mesh 2] [--steps 30] [--from 10] [--csv FILE] [--kinds]
//
// Between two consecutive accepted steps k and k+1 of a settling wall, some contacts' spring
// tangents change (a contact opens or closes, sticks or slides); the rest of the Newton matrix
// changes with the geometry. With A the matrix without contacts at step k+1 and w the contacts'
// gap and slip rows at step k+1 (docs/contact.md "The step's contact problem"),
//     H0 = A + Σ_c t_k(c)·w_c w_cᵀ        (the springs as they were at the end of step k)
//     H1 = A + Σ_c t_k+1(c)·w_c w_cᵀ      (as they are at the end of step k+1)
// differ by exactly r rank-one terms, one per spring term (normal or shear) whose tangent switched
// (on, off, or by more than 1 %; smaller changes — a constant spring's kn·L follows its
// tributary length L — are taken as step k+1's in H0, like the rows):
//     H1 − H0 = Σ_changed (t_k+1 − t_k)·w wᵀ.
// So H0 is the best a kept factorisation can be (the geometry's change is not in it), and r is
// the fewest changes a step makes (a step's Newton iterates pass through more). Measured, with
// the factor of H0 in hand, the cost of getting a direction for H1:
//   factorise   supernodal LLᵀ of H1, the symbolic analysis reused (what the contact solve does
//               when it refactorises: solver/discretisation/system_matrix.cpp);
//   updown      CHOLMOD's cholmod_updown of a simplicial LDLᵀ factor of H0 by the r terms
//               (an update for the terms that stiffen, a downdate for those that soften); the
//               simplicial factor's own build is reported beside it, as the price of keeping a
//               factor cholmod_updown can modify, and one solve with the updated factor checks
//               it against H1 (not timed);
//   cg          conjugate gradients on H1 preconditioned by the factor of H0 (what the contact
//               solve does before it refactorises), iterations to ‖H1 x − b‖ ≤ 1e-2‖b‖ (the
//               solve's forcing term) and to 1e-8‖b‖, each iteration a factor solve pair and a
//               product with H1.
// With --kinds, instead (its own columns): CHOLMOD's two kinds of factor of H1 against each other
//   supernodal  LLᵀ by dense blocks (BLAS), what the contact solve keeps;
//   simplicial  LLᵀ and LDLᵀ column by column (cholmod_rowfac), no BLAS;
// the numeric factorisation (analysis reused, same AMD ordering) and one solve pair
// (cholmod_solve, as a CG iteration's preconditioner), and the analysis's flops per factor
// nonzero, which CHOLMOD_AUTO compares with supernodal_switch (40) to choose between them.
// Times are thread CPU, best of 2, one core (run with OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1).
// One row per wall and mode: means over the step pairs from --from to --steps (and the contacts
// with a normal spring at the end of a step: the size of the contact space), and r's largest.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/CholmodSupport>
#include <cholmod.h>

#include "bench/bench_common.h"
#include "preprocess/cover_cutter.h"
#include "reference/brick_wall.h"
#include "solver/stepping/time_stepper.h"
#include "solver/stepping/time_stepper_probe.h"
#include "solver/discretisation/blas_kernels.h"

namespace {
using Sparse = nmm::solve::SystemMatrix::Sparse;
using Key = std::tuple<std::int32_t, std::int32_t, std::int32_t>;  // vertex, element A, element B

// One accepted step's spring terms: each contact's rows and tangents (0 where open or sliding).
struct Spring {
  std::vector<int> dofs;
  std::vector<double> cn, cs;
  double kn = 0, ks = 0;
};
using Springs = std::map<Key, Spring>;

Springs springs_of(const nmm::solve::ContactProblem& cs) {
  Springs out;
  for (std::size_t i = 0; i < cs.contacts().size(); ++i) {
    const nmm::solve::Contact& c = cs.contacts()[i];
    const nmm::solve::ContactProblem::Row row = cs.row(i);
    const int m = row.size;
    Spring s;
    s.dofs.assign(row.dofs, row.dofs + m);
    for (int k = 0; k < m; ++k) {
      s.cn.push_back(row.cn(k));
      s.cs.push_back(row.cs(k));
    }
    s.kn = c.kn_now;
    s.ks = c.ks_now;
    out[{c.at.vertex, c.at.elem_a, c.at.elem_b}] = std::move(s);
  }
  return out;
}

// Lower triangle of t·w wᵀ into triplets.
void add_term(std::vector<Eigen::Triplet<double>>& t, const std::vector<int>& dofs, const std::vector<double>& w,
              double k) {
  if (k == 0) return;
  for (std::size_t a = 0; a < dofs.size(); ++a)
    for (std::size_t b = 0; b < dofs.size(); ++b)
      if (dofs[a] >= dofs[b]) t.emplace_back(dofs[a], dofs[b], k * w[a] * w[b]);
}

// A spring term switched: on or off, or its tangent moved by more than 1 % (a nonlinear law's
// tangent; a constant spring's kn·L moves with the tributary length L).
constexpr double kSwitch = 0.01;
bool switched(double t0, double t1) {
  return (t0 == 0) != (t1 == 0) || std::abs(t1 - t0) > kSwitch * std::max(std::abs(t0), std::abs(t1));
}

struct Term {
  const std::vector<int>* dofs;
  const std::vector<double>* w;
  double dk;  // t_k+1 − t_k
};

struct Pair {
  int r_normal = 0, r_shear = 0, r_on_off = 0, closed = 0;
  double factorise_ms = 0, updown_ms = 0, simplicial_ms = 0, updown_error = 0;
  int cg_forcing = 0, cg_tight = 0;
};

double cpu_ms(const std::function<void()>& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int rep = 0; rep < 2; ++rep) {
    const double c0 = nmm::bench::thread_cpu_seconds();
    f();
    best = std::min(best, 1e3 * (nmm::bench::thread_cpu_seconds() - c0));
  }
  return best;
}

// PCG iterations on h with the factorisation `p` to ‖h x − b‖ ≤ rel·‖b‖ (−1: not within 500).
template <class Llt>
int pcg_iterations(const Sparse& h, const Llt& p, const Eigen::VectorXd& b, double rel) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size()), r = b, z = p.solve(r), q = z, hq;
  double rz = r.dot(z);
  for (int it = 1; it <= 500; ++it) {
    hq = h.selfadjointView<Eigen::Lower>() * q;
    const double a = rz / q.dot(hq);
    x += a * q;
    r -= a * hq;
    if (r.norm() <= rel * b.norm()) return it;
    z = p.solve(r);
    const double rz1 = r.dot(z);
    q = z + (rz1 / rz) * q;
    rz = rz1;
  }
  return -1;
}

// CHOLMOD's supernodal and simplicial factors of one matrix: numeric factorisation and solve
// pair, CPU ms (the analysis reused; each kind under the same AMD ordering).
struct Kinds {
  double super_ms = 0, super_solve_ms = 0, ll_ms = 0, ll_solve_ms = 0, ldl_ms = 0, ldl_solve_ms = 0;
  double flops_per_lnz = 0, super_lnz = 0, simplicial_lnz = 0, max_difference = 0;
};

Kinds factor_kinds(Sparse h, const Eigen::VectorXd& rhs) {
  Kinds out;
  h.makeCompressed();
  cholmod_sparse v = Eigen::viewAsCholmod(h);
  v.stype = -1;
  Eigen::VectorXd b = rhs;
  cholmod_dense bd = Eigen::viewAsCholmod(b);
  Eigen::VectorXd x_super;
  // kind: 0 supernodal LLᵀ, 1 simplicial LLᵀ, 2 simplicial LDLᵀ.
  for (int kind = 0; kind < 3; ++kind) {
    cholmod_common cc;
    cholmod_start(&cc);
    cc.nmethods = 1;
    cc.method[0].ordering = CHOLMOD_AMD;
    cc.postorder = 1;
    cc.supernodal = kind == 0 ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
    cc.final_ll = kind != 2;
    cc.print = 0;
    cholmod_factor* l = cholmod_analyze(&v, &cc);
    if (kind == 0) out.flops_per_lnz = cc.fl / std::max(cc.lnz, 1.0);
    const double ms = cpu_ms([&] { cholmod_factorize(&v, l, &cc); });
    // A solve pair: the mean of 20, best of 2 (one is tens of µs on the smallest wall).
    cholmod_dense* x = nullptr;
    const double solve_ms = cpu_ms([&] {
      for (int i = 0; i < 20; ++i) {
        if (x) cholmod_free_dense(&x, &cc);
        x = cholmod_solve(CHOLMOD_A, l, &bd, &cc);
      }
    }) / 20;
    const Eigen::Map<Eigen::VectorXd> xv(static_cast<double*>(x->x), h.rows());
    if (kind == 0) {
      x_super = xv;
      out.super_ms = ms, out.super_solve_ms = solve_ms, out.super_lnz = cc.lnz;
    } else {
      out.max_difference = std::max(out.max_difference, (xv - x_super).norm() / x_super.norm());
      (kind == 1 ? out.ll_ms : out.ldl_ms) = ms;
      (kind == 1 ? out.ll_solve_ms : out.ldl_solve_ms) = solve_ms;
      out.simplicial_lnz = cc.lnz;
    }
    cholmod_free_dense(&x, &cc);
    cholmod_free_factor(&l, &cc);
    cholmod_finish(&cc);
  }
  return out;
}

// The Newton matrix at the end of a step: A and the springs' tangents of `after`.
Sparse with_springs(const Sparse& a, const Springs& after) {
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < a.outerSize(); ++j)
    for (Sparse::InnerIterator it(a, j); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  for (const auto& [key, s] : after) {
    add_term(t, s.dofs, s.cn, s.kn);
    add_term(t, s.dofs, s.cs, s.ks);
  }
  Sparse h(a.rows(), a.cols());
  h.setFromTriplets(t.begin(), t.end());
  return h;
}

Pair measure(const Sparse& a, const Springs& before, const Springs& after, const Eigen::VectorXd& rhs) {
  Pair out;
  const int n = static_cast<int>(a.rows());
  std::vector<Eigen::Triplet<double>> t0, t1;
  for (int j = 0; j < a.outerSize(); ++j)
    for (Sparse::InnerIterator it(a, j); it; ++it) {
      t0.emplace_back(it.row(), it.col(), it.value());
      t1.emplace_back(it.row(), it.col(), it.value());
    }
  std::vector<Term> terms;
  // Every term of H1, with step k's tangent in H0 (0 for a contact step k did not have).
  for (const auto& [key, s] : after) {
    out.closed += s.kn != 0;
    const auto at = before.find(key);
    double kn0 = at == before.end() ? 0.0 : at->second.kn, ks0 = at == before.end() ? 0.0 : at->second.ks;
    // A tangent that moved by less than kSwitch of itself (a constant spring's kn·L follows the
    // contact's tributary length L) is no switch: H0 takes step k+1's, as it takes its rows.
    if (!switched(kn0, s.kn)) kn0 = s.kn;
    if (!switched(ks0, s.ks)) ks0 = s.ks;
    add_term(t0, s.dofs, s.cn, kn0);
    add_term(t0, s.dofs, s.cs, ks0);
    add_term(t1, s.dofs, s.cn, s.kn);
    add_term(t1, s.dofs, s.cs, s.ks);
    if (s.kn != kn0) terms.push_back({&s.dofs, &s.cn, s.kn - kn0}), ++out.r_normal;
    if (s.ks != ks0) terms.push_back({&s.dofs, &s.cs, s.ks - ks0}), ++out.r_shear;
    out.r_on_off += ((kn0 == 0) != (s.kn == 0)) + ((ks0 == 0) != (s.ks == 0));
  }
  // Contacts of step k that step k+1 does not have: their springs leave (step k's rows).
  for (const auto& [key, s] : before)
    if (!after.count(key)) {
      add_term(t0, s.dofs, s.cn, s.kn);
      add_term(t0, s.dofs, s.cs, s.ks);
      if (s.kn != 0) terms.push_back({&s.dofs, &s.cn, -s.kn}), ++out.r_normal, ++out.r_on_off;
      if (s.ks != 0) terms.push_back({&s.dofs, &s.cs, -s.ks}), ++out.r_shear, ++out.r_on_off;
    }
  // Both on the union of the two patterns (explicit zeros), so one analysis serves both.
  const std::size_t n0 = t0.size(), n1 = t1.size();
  for (std::size_t i = 0; i < n1; ++i) t0.emplace_back(t1[i].row(), t1[i].col(), 0.0);
  for (std::size_t i = 0; i < n0; ++i) t1.emplace_back(t0[i].row(), t0[i].col(), 0.0);
  Sparse h0(n, n), h1(n, n);
  h0.setFromTriplets(t0.begin(), t0.end());
  h1.setFromTriplets(t1.begin(), t1.end());

  // Supernodal LLᵀ, as the contact solve factorises.
  Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> super0, super1;
  super0.cholmod().nmethods = 1;
  super0.cholmod().method[0].ordering = CHOLMOD_AMD;
  super0.analyzePattern(h0);
  super0.factorize(h0);
  super1.cholmod().nmethods = 1;
  super1.cholmod().method[0].ordering = CHOLMOD_AMD;
  super1.analyzePattern(h1);
  out.factorise_ms = cpu_ms([&] { super1.factorize(h1); });

  // Simplicial LDLᵀ of H0 (same ordering), then updated to H1.
  cholmod_common cc;
  cholmod_start(&cc);
  cc.nmethods = 1;
  cc.method[0].ordering = CHOLMOD_AMD;
  cc.supernodal = CHOLMOD_SIMPLICIAL;
  cc.final_ll = 0;
  cc.print = 0;
  h0.makeCompressed();
  cholmod_sparse v0 = Eigen::viewAsCholmod(h0);
  v0.stype = -1;  // the lower triangle of a symmetric matrix
  cholmod_factor* l = cholmod_analyze(&v0, &cc);
  // Position of each unknown in the factor's ordering (rows of the update are permuted).
  const int* perm = static_cast<const int*>(l->Perm);
  std::vector<int> pos(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) pos[static_cast<std::size_t>(perm[i])] = i;
  const auto update_matrix = [&](bool up) {
    std::vector<Eigen::Triplet<double>> ct;
    int col = 0;
    for (const Term& tm : terms) {
      if ((tm.dk > 0) != up) continue;
      const double s = std::sqrt(std::abs(tm.dk));
      std::map<int, double> column;  // an unknown may appear twice in a row (shared covers)
      for (std::size_t i = 0; i < tm.dofs->size(); ++i) column[pos[static_cast<std::size_t>((*tm.dofs)[i])]] += s * (*tm.w)[i];
      for (const auto& [row, value] : column) ct.emplace_back(row, col, value);
      ++col;
    }
    Sparse c(n, std::max(col, 1));
    c.setFromTriplets(ct.begin(), ct.end());
    c.makeCompressed();
    return c;
  };
  const Sparse c_up = update_matrix(true), c_down = update_matrix(false);
  double best_updown = std::numeric_limits<double>::infinity(), best_simplicial = std::numeric_limits<double>::infinity();
  for (int rep = 0; rep < 2; ++rep) {
    double c0 = nmm::bench::thread_cpu_seconds();
    cholmod_factorize(&v0, l, &cc);
    best_simplicial = std::min(best_simplicial, 1e3 * (nmm::bench::thread_cpu_seconds() - c0));
    Sparse cu = c_up, cd = c_down;
    cholmod_sparse vu = Eigen::viewAsCholmod(cu), vd = Eigen::viewAsCholmod(cd);
    c0 = nmm::bench::thread_cpu_seconds();
    if (c_up.nonZeros() > 0) cholmod_updown(1, &vu, l, &cc);
    if (c_down.nonZeros() > 0) cholmod_updown(0, &vd, l, &cc);
    best_updown = std::min(best_updown, 1e3 * (nmm::bench::thread_cpu_seconds() - c0));
  }
  out.updown_ms = best_updown;
  out.simplicial_ms = best_simplicial;
  // The updated factor solves H1: relative residual of one solve. The right-hand side is step
  // k+1's (its loads: the contact solve's first residual).
  Eigen::VectorXd b = rhs;
  {
    cholmod_dense bd = Eigen::viewAsCholmod(b);
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, l, &bd, &cc);
    const Eigen::Map<Eigen::VectorXd> xv(static_cast<double*>(x->x), n);
    const Eigen::VectorXd res = h1.selfadjointView<Eigen::Lower>() * xv - b;
    out.updown_error = res.norm() / b.norm();
    cholmod_free_dense(&x, &cc);
  }
  cholmod_free_factor(&l, &cc);
  cholmod_finish(&cc);

  out.cg_forcing = pcg_iterations(h1, super0, b, 1e-2);
  out.cg_tight = pcg_iterations(h1, super0, b, 1e-8);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  std::vector<int> sizes{10, 20, 30};
  double h = 2;
  int steps = 30, from = 10;
  std::string csv_path = "factor_update.csv";
  bool kinds = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) sizes = nmm::bench::parse_sizes(argv[++i]);
    else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc) h = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--from") && i + 1 < argc) from = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else if (!std::strcmp(argv[i], "--kinds")) kinds = true;
    else {
      std::fprintf(stderr, "usage: factor_update_bench [--sizes 10,20,30] [--mesh 2] [--steps 30] [--from 10] [--csv FILE] [--kinds]\n");
      return 2;
    }
  }
  if (from < 1 || steps <= from) {
    std::fprintf(stderr, "factor_update_bench: --from must be at least 1 and below --steps\n");
    return 2;
  }
  std::ofstream csv = nmm::bench::start_csv(
      csv_path,
      kinds ? "mode,wall_n,mesh_size_m,unknowns,step_pairs,flops_per_factor_nonzero,supernodal_factor_nonzeros,"
              "simplicial_factor_nonzeros,supernodal_factorise_ms,simplicial_llt_factorise_ms,simplicial_ldlt_factorise_ms,"
              "supernodal_solve_ms,simplicial_llt_solve_ms,simplicial_ldlt_solve_ms,solution_difference_max,load_average\n"
            : "mode,wall_n,mesh_size_m,unknowns,closed_contacts_mean,step_pairs,changed_normal_mean,changed_shear_mean,switched_on_off_mean,changed_max,"
      "factorise_ms,updown_ms,updown_per_term_us,simplicial_build_ms,updown_relative_residual_max,"
      "cg_iterations_forcing,cg_iterations_1e-8,load_average\n");
  for (const bool dynamic : {false, true})
    for (const int n : sizes) {
      const nmm::SceneDef s = nmm::reference::peer_wall(n, n, dynamic, h);
      const nmm::Mesh m = nmm::pre::build_mesh(s, "bench");
      nmm::solve::TimeStepper st(m, s, "bench");
      st.set_threads(1);
      Springs last;
      Kinds ksum;
      Pair sum;
      int pairs = 0, worst = 0, cg_failed = 0;
      double err = 0;
      for (int k = 1; k <= steps; ++k) {
        const nmm::Outcome ran = st.run_until(k * s.solver.time_step, [](std::int64_t) {});
        if (!ran.ok()) {
          std::fprintf(stderr, "wall %d: %s\n", n, ran.reason.c_str());
          break;
        }
        Springs now = springs_of(nmm::solve::TimeStepperProbe::contact_problem(st));
        if (k > from && kinds) {
          const Kinds q = factor_kinds(with_springs(Sparse(st.view().system.saved_matrix().transpose()), now),
                                       nmm::solve::TimeStepperProbe::rhs(st));
          ksum.flops_per_lnz += q.flops_per_lnz, ksum.super_lnz += q.super_lnz, ksum.simplicial_lnz += q.simplicial_lnz;
          ksum.super_ms += q.super_ms, ksum.ll_ms += q.ll_ms, ksum.ldl_ms += q.ldl_ms;
          ksum.super_solve_ms += q.super_solve_ms, ksum.ll_solve_ms += q.ll_solve_ms, ksum.ldl_solve_ms += q.ldl_solve_ms;
          ksum.max_difference = std::max(ksum.max_difference, q.max_difference);
          ++pairs;
        } else if (k > from) {
          // The system keeps the upper triangle; this bench works on the lower one.
          const Pair p = measure(Sparse(st.view().system.saved_matrix().transpose()), last, now,
                                 nmm::solve::TimeStepperProbe::rhs(st));
          sum.r_normal += p.r_normal;
          sum.r_on_off += p.r_on_off;
          sum.closed += p.closed;
          sum.r_shear += p.r_shear;
          worst = std::max(worst, p.r_normal + p.r_shear);
          sum.factorise_ms += p.factorise_ms;
          sum.updown_ms += p.updown_ms;
          sum.simplicial_ms += p.simplicial_ms;
          err = std::max(err, p.updown_error);
          if (p.cg_forcing < 0 || p.cg_tight < 0) ++cg_failed;
          sum.cg_forcing += p.cg_forcing;
          sum.cg_tight += p.cg_tight;
          ++pairs;
        }
        last = std::move(now);
      }
      if (pairs == 0) continue;
      if (kinds) {
        const double q = pairs;
        char line[600];
        std::snprintf(line, sizeof line, "%s,%d,%.3g,%d,%d,%.1f,%.0f,%.0f,%.3f,%.3f,%.3f,%.4f,%.4f,%.4f,%.1e,%.2f\n",
                      dynamic ? "dynamic" : "static", n, h, st.view().space.unknowns(), pairs, ksum.flops_per_lnz / q,
                      ksum.super_lnz / q, ksum.simplicial_lnz / q, ksum.super_ms / q, ksum.ll_ms / q, ksum.ldl_ms / q,
                      ksum.super_solve_ms / q, ksum.ll_solve_ms / q, ksum.ldl_solve_ms / q, ksum.max_difference,
                      nmm::bench::load_average());
        csv << line;
        std::fputs(line, stdout);
        std::fflush(stdout);
        continue;
      }
      const double q = pairs, terms = sum.r_normal + sum.r_shear;
      char line[600];
      std::snprintf(line, sizeof line, "%s,%d,%.3g,%d,%.0f,%d,%.1f,%.1f,%.1f,%d,%.3f,%.3f,%.2f,%.3f,%.1e,%.1f,%.1f,%.2f%s\n",
                    dynamic ? "dynamic" : "static", n, h, st.view().space.unknowns(), sum.closed / q, pairs, sum.r_normal / q,
                    sum.r_shear / q, sum.r_on_off / q, worst, sum.factorise_ms / q, sum.updown_ms / q,
                    terms > 0 ? 1e3 * sum.updown_ms / terms : 0.0, sum.simplicial_ms / q, err, sum.cg_forcing / q,
                    sum.cg_tight / q, nmm::bench::load_average(), cg_failed ? ",some CG runs over 500 iterations" : "");
      csv << line;
      std::fputs(line, stdout);
      std::fflush(stdout);
    }
  return 0;
}
