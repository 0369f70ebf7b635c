// Fill-reducing orderings on the DDA code's large brick walls (issue 52): nonzeros and flops of
// the Cholesky factor, and the thread CPU time of the symbolic analysis, of one numeric
// factorisation and of one solve pair (what a CG iteration on the kept factor costs besides its
// product), for the system matrix of the wall after a few static steps.
//
//   ordering_bench [--sizes 100] [--mesh 0.5] [--steps 3] [--reps 3] [--csv FILE]
//   ordering_bench --growth [--sizes 100] [--mesh 0.5] [--steps 30] [--csv FILE]
//
// --growth: the wall step by step; at each step whose matrix pattern grew, the new pattern under
// METIS anew (metis_covers), under the order of the last one's factor as is (kept), and with the
// new pairs' covers placed in it (placed: fill_ordering.h placed_ordering, what a lean run does
// while its fill stays within bounds), one numeric factorisation each. The order carried to the
// next growth is the placed one while its nonzeros stay within kOrderingRefill of the last METIS
// ordering's and its flops within 1.25 × the last carried factor's, as in a lean run
// (system_matrix.cpp analyse_kept).
//
// Orderings, each analysed by CHOLMOD (supernodal LLᵀ, postordered, as nmm-solve factorises):
//   amd           CHOLMOD's AMD on the matrix (what runs with contact used before 2026-11-29)
//   metis         CHOLMOD's METIS nested dissection on the matrix
//   nesdis        CHOLMOD's own nested dissection
//   amd_covers    AMD on the graph of the covers (one node per cover, its unknowns together)
//   metis_covers  METIS on the graph of the covers
// A cover's unknowns (its two displacement directions, and its higher-order terms) share every
// row's pattern, so an ordering of the covers expanded to their unknowns loses nothing in fill;
// the graph is (dofs per cover)² times smaller to order. What was found, and why nmm-solve keeps
// AMD: docs/notes/2026-11-scale.md.
//
// Counts (nonzeros, flops) do not depend on the machine; times do (the CSV carries the load
// average). Run with OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <cholmod.h>

#include "bench/bench_common.h"
#include "preprocess/cover_cutter.h"
#include "reference/brick_wall.h"
#include "solver/discretisation/fill_ordering.h"
#include "solver/discretisation/solver_threads.h"
#include "solver/stepping/time_stepper.h"
#include "solver/discretisation/blas_kernels.h"

namespace {
using Sparse = nmm::solve::SystemMatrix::Sparse;

struct Result {
  double factor_nnz = 0, flops = 0, order_ms = 0, analyse_ms = 0, factor_ms = 0, solve_ms = 0;
  bool ok = false;
};

cholmod_sparse view(const Sparse& a) {
  cholmod_sparse m{};
  m.nrow = m.ncol = static_cast<std::size_t>(a.rows());
  m.nzmax = static_cast<std::size_t>(a.nonZeros());
  m.p = const_cast<int*>(a.outerIndexPtr());
  m.i = const_cast<int*>(a.innerIndexPtr());
  m.x = const_cast<double*>(a.valuePtr());
  m.stype = 1;  // upper triangle
  m.itype = CHOLMOD_INT;
  m.xtype = CHOLMOD_REAL;
  m.dtype = CHOLMOD_DOUBLE;
  m.sorted = 1;
  m.packed = 1;
  return m;
}

// ordering: a CHOLMOD ordering, or -1 / -2 for AMD / METIS on the cover graph (fill_ordering.h).
Result run(const Sparse& a, int ordering, int block, int reps) {
  Result r;
  r.order_ms = r.analyse_ms = r.factor_ms = r.solve_ms = std::numeric_limits<double>::infinity();
  cholmod_sparse m = view(a);
  std::vector<double> ones(static_cast<std::size_t>(a.rows()), 1.0);
  for (int rep = 0; rep < reps; ++rep) {
    cholmod_common c;
    cholmod_start(&c);
    c.print = 0;
    c.supernodal = CHOLMOD_SUPERNODAL;
    c.final_ll = 1;
    c.nmethods = 1;
    c.postorder = 1;
    std::vector<int> perm;
    double t = nmm::bench::thread_cpu_seconds();
    if (ordering < 0) {
      perm = nmm::solve::block_ordering(static_cast<int>(a.rows()), a.outerIndexPtr(), a.innerIndexPtr(), block,
                                        ordering == -2 ? nmm::solve::FillOrdering::metis : nmm::solve::FillOrdering::amd);
      c.method[0].ordering = CHOLMOD_GIVEN;
    } else {
      c.method[0].ordering = ordering;
    }
    r.order_ms = std::min(r.order_ms, 1e3 * (nmm::bench::thread_cpu_seconds() - t));
    if (ordering >= 0) r.order_ms = 0;
    t = nmm::bench::thread_cpu_seconds();
    cholmod_factor* l = cholmod_analyze_p(&m, perm.empty() ? nullptr : perm.data(), nullptr, 0, &c);
    r.analyse_ms = std::min(r.analyse_ms, 1e3 * (nmm::bench::thread_cpu_seconds() - t));
    r.factor_nnz = c.lnz;
    r.flops = c.fl;
    t = nmm::bench::thread_cpu_seconds();
    cholmod_factorize(&m, l, &c);
    r.factor_ms = std::min(r.factor_ms, 1e3 * (nmm::bench::thread_cpu_seconds() - t));
    r.ok = c.status == CHOLMOD_OK && l->minor == l->n;
    cholmod_dense b{};
    b.nrow = b.d = static_cast<std::size_t>(a.rows());
    b.ncol = 1;
    b.nzmax = b.nrow;
    b.x = ones.data();
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    for (int s = 0; s < 3; ++s) {
      t = nmm::bench::thread_cpu_seconds();
      cholmod_dense* x = cholmod_solve(CHOLMOD_A, l, &b, &c);
      r.solve_ms = std::min(r.solve_ms, 1e3 * (nmm::bench::thread_cpu_seconds() - t));
      cholmod_free_dense(&x, &c);
    }
    cholmod_free_factor(&l, &c);
    cholmod_finish(&c);
  }
  return r;
}
// cholmod_analyze_p under `perm` (CHOLMOD postorders it); the numeric factorisation timed too
// when `factor` is set. Returns the factor (symbolic, its values freed) for the next growth.
cholmod_factor* analyse(const Sparse& a, std::vector<int>& perm, bool factor, cholmod_common& c, Result& r) {
  cholmod_sparse m = view(a);
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_GIVEN;
  c.postorder = 1;
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.final_ll = 1;
  double t = nmm::bench::thread_cpu_seconds();
  cholmod_factor* l = cholmod_analyze_p(&m, perm.data(), nullptr, 0, &c);
  r.analyse_ms = 1e3 * (nmm::bench::thread_cpu_seconds() - t);
  r.factor_nnz = c.lnz;
  r.flops = c.fl;
  r.factor_ms = 0;
  if (factor) {
    t = nmm::bench::thread_cpu_seconds();
    cholmod_factorize(&m, l, &c);
    r.factor_ms = 1e3 * (nmm::bench::thread_cpu_seconds() - t);
    r.ok = c.status == CHOLMOD_OK && l->minor == l->n;
    // Back to a symbolic factor: the next growth reads its supernodes' rows alone.
    cholmod_change_factor(CHOLMOD_PATTERN, 1, 1, 1, 1, l, &c);
  } else {
    r.ok = l != nullptr;
  }
  return l;
}

int growth(const std::vector<int>& sizes, double h, int steps, const std::string& csv_path) {
  const char* header =
      "wall_n,mesh_size_m,step,unknowns,matrix_nnz_upper,outside_entries,ordering,factor_nnz,factor_gflops,"
      "order_ms,analyse_ms,factor_ms,carried,load_average,ok\n";
  std::ofstream csv = nmm::bench::start_csv(csv_path, header);
  for (int n : sizes) {
    const nmm::SceneDef wall = nmm::reference::peer_wall(n, n, false, h);
    const nmm::Mesh wm = nmm::pre::build_mesh(wall, "wall");
    nmm::solve::TimeStepper st(wm, wall, "wall");
    st.set_threads(1);
    const int block = st.view().space.dofs_per_cover(), blocked = st.view().space.unknowns();
    cholmod_common c;
    cholmod_start(&c);
    c.print = 0;
    std::vector<int> carried;   // the order the last pattern was analysed under
    cholmod_factor* last = nullptr;
    double metis_fill = 0;      // factor nonzeros of the last METIS ordering when found
    double last_flops = 0;      // flops of the last pattern's factor under the carried order
    std::size_t last_nnz = 0;
    for (int k = 1; k <= steps; ++k) {
      const nmm::Outcome ran = st.run_until(k * wall.solver.time_step, [](std::int64_t) {});
      if (!ran.ok()) {
        std::fprintf(stderr, "wall %d: %s\n", n, ran.reason.c_str());
        break;
      }
      const Sparse& a = st.view().system.matrix();
      if (static_cast<std::size_t>(a.nonZeros()) == last_nnz) continue;
      const bool grew = last && static_cast<std::size_t>(a.nonZeros()) > last_nnz;
      last_nnz = static_cast<std::size_t>(a.nonZeros());
      const auto line = [&](const char* name, const Result& r, std::size_t outside, bool kept) {
        char out[600];
        std::snprintf(out, sizeof out, "%d,%g,%d,%ld,%ld,%zu,%s,%.0f,%.3f,%.1f,%.1f,%.1f,%d,%.2f,%d\n", n, h, k,
                      static_cast<long>(a.rows()), static_cast<long>(a.nonZeros()), outside, name, r.factor_nnz,
                      r.flops / 1e9, r.order_ms, r.analyse_ms, r.factor_ms, kept ? 1 : 0, nmm::bench::load_average(),
                      r.ok ? 1 : 0);
        csv << out;
        std::fputs(out, stdout);
        std::fflush(stdout);
      };
      // METIS anew.
      Result rm;
      double t = nmm::bench::thread_cpu_seconds();
      std::vector<int> metis = nmm::solve::block_ordering(static_cast<int>(a.rows()), a.outerIndexPtr(),
                                                          a.innerIndexPtr(), block, nmm::solve::FillOrdering::metis,
                                                          blocked);
      rm.order_ms = 1e3 * (nmm::bench::thread_cpu_seconds() - t);
      cholmod_factor* lm = analyse(a, metis, true, c, rm);
      std::size_t outside_count = 0;
      bool keep_placed = false;
      double placed_flops = 0;
      cholmod_factor* lp = nullptr;
      std::vector<int> placed;
      if (grew) {
        // The entries outside the last factor, and the placed order.
        const nmm::solve::FactorRows rows(*last);
        std::vector<std::pair<int, int>> outside;
        const int* outer = a.outerIndexPtr();
        const int* inner = a.innerIndexPtr();
        for (int j = 0; j < a.cols(); ++j)
          for (int p = outer[j]; p < outer[j + 1]; ++p)
            if (!rows.within(j, inner[p])) outside.emplace_back(j, inner[p]);
        outside_count = outside.size();
        Result rk;
        cholmod_factor* lk = analyse(a, carried, true, c, rk);
        cholmod_free_factor(&lk, &c);
        line("kept", rk, outside_count, false);
        Result rp;
        t = nmm::bench::thread_cpu_seconds();
        placed = nmm::solve::placed_ordering(*last, outside, block, blocked);
        rp.order_ms = 1e3 * (nmm::bench::thread_cpu_seconds() - t);
        lp = analyse(a, placed, true, c, rp);
        keep_placed = rp.factor_nnz <= nmm::solve::kOrderingRefill * metis_fill && rp.flops <= 1.25 * last_flops;
        placed_flops = rp.flops;
        line("placed", rp, outside_count, keep_placed);
      }
      line("metis_covers", rm, outside_count, !keep_placed);
      cholmod_free_factor(&last, &c);
      if (keep_placed) {
        last_flops = placed_flops;
        last = lp;
        carried = std::move(placed);
        cholmod_free_factor(&lm, &c);
      } else {
        if (lp) cholmod_free_factor(&lp, &c);
        last = lm;
        carried = std::move(metis);
        metis_fill = rm.factor_nnz;
        last_flops = rm.flops;
      }
    }
    cholmod_free_factor(&last, &c);
    cholmod_finish(&c);
  }
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  std::vector<int> sizes{100};
  double h = 0.5;
  int steps = 3, reps = 3;
  std::string csv_path = "ordering_bench.csv";
  bool growths = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) sizes = nmm::bench::parse_sizes(argv[++i]);
    else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc) h = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) reps = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else if (!std::strcmp(argv[i], "--growth")) growths = true;
    else {
      std::fprintf(stderr, "usage: ordering_bench [--growth] [--sizes 100] [--mesh 0.5] [--steps 3] [--reps 3] [--csv FILE]\n");
      return 2;
    }
  }
  nmm::solve::set_solver_threads(1);
  if (growths) return growth(sizes, h, steps, csv_path);
  const char* header =
      "wall_n,mesh_size_m,steps,unknowns,matrix_nnz_upper,ordering,factor_nnz,factor_nnz_per_unknown,"
      "factor_gflops,order_ms,analyse_ms,factor_ms,solve_pair_ms,load_average,ok\n";
  std::ofstream csv = nmm::bench::start_csv(csv_path, header);
  const struct {
    const char* name;
    int id;
  } orderings[] = {{"amd", CHOLMOD_AMD}, {"metis", CHOLMOD_METIS}, {"nesdis", CHOLMOD_NESDIS},
                   {"amd_covers", -1}, {"metis_covers", -2}};
  for (int n : sizes) {
    const nmm::SceneDef wall = nmm::reference::peer_wall(n, n, false, h);
    const nmm::Mesh wm = nmm::pre::build_mesh(wall, "wall");
    nmm::solve::TimeStepper st(wm, wall, "wall");
    st.set_threads(1);
    const nmm::Outcome ran = st.run_until(steps * wall.solver.time_step, [](std::int64_t) {});
    if (!ran.ok()) std::fprintf(stderr, "wall %d: %s\n", n, ran.reason.c_str());
    const Sparse a = st.view().system.matrix();
    const int block = st.view().space.dofs_per_cover();
    for (const auto& o : orderings) {
      const Result r = run(a, o.id, block, reps);
      char line[600];
      std::snprintf(line, sizeof line, "%d,%g,%d,%ld,%ld,%s,%.0f,%.1f,%.3f,%.1f,%.1f,%.1f,%.2f,%.2f,%d\n", n, h, steps,
                    static_cast<long>(a.rows()), static_cast<long>(a.nonZeros()), o.name, r.factor_nnz,
                    r.factor_nnz / static_cast<double>(a.rows()), r.flops / 1e9, r.order_ms, r.analyse_ms, r.factor_ms,
                    r.solve_ms, nmm::bench::load_average(), r.ok ? 1 : 0);
      csv << line;
      std::fputs(line, stdout);
      std::fflush(stdout);
    }
  }
  return 0;
}
