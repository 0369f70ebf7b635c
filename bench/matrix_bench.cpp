// Know the matrix (issue 11): nonzeros of the system matrix and of its Cholesky factor, flops of
// one factorisation and the factorisation's time, for the brick walls of contact_bench under
// CHOLMOD's fill-reducing orderings, against a plain elasticity pattern.
//
//   matrix_bench [--sizes 10,20,30,50] [--reps 3] [--csv FILE]
//
// For each staggered brick wall of N × N bricks (reference/brick_wall.h, the wall of
// contact_bench) the wall settles 3 static steps, so that its pattern holds the contact coupling
// of a settling wall (one 12 × 12 block per element pair that has had a contact: docs/contact.md,
// "Sparse pattern"; until issue 11's speed work also every pair within the search distance, which
// the committed CSV's "wall" rows show); the matrix of its last step is then analysed and
// factorised (supernodal LLᵀ, as nmm-solve does) with
//   amd     approximate minimum degree,
//   metis   METIS's nested dissection (Debian's CHOLMOD is built with METIS),
//   nesdis  CHOLMOD's own nested dissection (METIS bisection, constrained minimum degree),
//   auto    CHOLMOD's default strategy (AMD; METIS as well when AMD's fill is high; the better),
// each run `reps` times (fastest factorisation kept). How much of the wall's pattern is contact
// coupling: the same unknowns with the pattern of the elements alone plus the element pairs of
// the step's contacts only (all found, open or closed: "wall_contact_pairs") or of its closed
// contacts only ("wall_closed_pairs"), instead of every pair that has had a contact since the
// start (the pattern only grows). Against it, the same outline as one body
// with no joints (base and wall one continuum, fixed at the bottom): the "plain elasticity
// pattern", once on the same mesh (fewer unknowns: no covers doubled along joints) and once on
// a finer mesh with about as many unknowns as the wall.
//
// Counts (nonzeros, flops) do not depend on the machine or its load; times do (the CSV carries
// the load average at each row). Run with OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1: one core.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/CholmodSupport>

#include "bench/bench_common.h"
#include "preprocess/cover_cutter.h"
#include "reference/brick_wall.h"
#include "solver/stepping/time_stepper.h"
#include "common/stopwatch.h"
#include "solver/discretisation/blas_kernels.h"

namespace {
using Sparse = nmm::solve::SystemMatrix::Sparse;

struct Ordered {
  double factor_nnz = 0, flops = 0, analyse_ms = 0, factor_ms = 0;
  std::string selected;
  bool ok = false;
};

// ordering: CHOLMOD_AMD, CHOLMOD_METIS, CHOLMOD_NESDIS, -1 for CHOLMOD's default strategy, or
// -2 for AMD and METIS both tried, CHOLMOD keeping the better.
Ordered factorise(const Sparse& a, int ordering, int reps) {
  Ordered r;
  double best = std::numeric_limits<double>::infinity();
  for (int rep = 0; rep < reps; ++rep) {
    Eigen::CholmodSupernodalLLT<Sparse, Eigen::Upper> llt;
    cholmod_common& c = llt.cholmod();
    c.print = 0;
    if (ordering >= 0) {
      c.nmethods = 1;
      c.method[0].ordering = ordering;
      c.postorder = 1;
    } else if (ordering == -2) {
      c.nmethods = 2;
      c.method[0].ordering = CHOLMOD_AMD;
      c.method[1].ordering = CHOLMOD_METIS;
      c.postorder = 1;
    }
    const nmm::Stopwatch t0;
    llt.analyzePattern(a);
    const double analyse = t0.seconds();
    const nmm::Stopwatch t1;
    llt.factorize(a);
    const double fact = t1.seconds();
    r.ok = llt.info() == Eigen::Success;
    r.factor_nnz = c.lnz;
    r.flops = c.fl;
    const int m = c.selected >= 0 && c.selected < CHOLMOD_MAXMETHODS ? c.method[c.selected].ordering : -1;
    r.selected = m == CHOLMOD_AMD ? "amd" : m == CHOLMOD_METIS ? "metis" : m == CHOLMOD_NESDIS ? "nesdis" : "other";
    if (rep == 0) r.analyse_ms = 1e3 * analyse;
    r.analyse_ms = std::min(r.analyse_ms, 1e3 * analyse);
    best = std::min(best, fact);
  }
  r.factor_ms = 1e3 * best;
  return r;
}

// The wall's outline as one continuum: base and bricks' extent [0, n + ½] × [0, n/2], no joints.
nmm::SceneDef monolith(int n, double h) {
  nmm::SceneDef s = nmm::reference::brick_wall(n, false);
  s.name = "monolith " + std::to_string(n);
  s.bodies.clear();
  nmm::BodyDef b;
  b.material = 0;
  b.outer = {{-1, -1}, {n + 1.5, -1}, {n + 1.5, 0}, {n + 0.5, 0}, {n + 0.5, 0.5 * n}, {0, 0.5 * n}, {0, 0}, {-1, 0}};
  s.bodies.push_back(b);
  s.mesh_size = h;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  std::vector<int> sizes{10, 20, 30, 50};
  int reps = 3;
  std::string csv_path = "matrix_bench.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) sizes = nmm::bench::parse_sizes(argv[++i]);
    else if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) reps = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: matrix_bench [--sizes 10,20,30,50] [--reps 3] [--csv FILE]\n");
      return 2;
    }
  }
  const char* header =
      "wall_n,scene,mesh_size_m,unknowns,matrix_nnz_lower,nnz_per_unknown,ordering,selected,"
      "factor_nnz,factor_nnz_per_unknown,factor_mflops,analyse_ms,factor_ms,load_average\n";
  std::ofstream csv = nmm::bench::start_csv(csv_path, header);
  const struct {
    const char* name;
    int id;
  } orderings[] = {{"amd", CHOLMOD_AMD}, {"metis", CHOLMOD_METIS}, {"nesdis", CHOLMOD_NESDIS}, {"auto", -1}, {"amd+metis", -2}};
  for (int n : sizes) {
    // The wall, after 3 static steps.
    const nmm::SceneDef wall = nmm::reference::brick_wall(n, false);
    const nmm::Mesh wm = nmm::pre::build_mesh(wall, "wall");
    nmm::solve::TimeStepper st(wm, wall, "wall");
    st.set_threads(1);
    const nmm::Outcome ran = st.run_until(3e-3, [](std::int64_t) {});
    if (!ran.ok()) std::fprintf(stderr, "wall %d: %s\n", n, ran.reason.c_str());
    const Sparse wall_matrix = st.view().system.matrix();
    const int unknowns = st.view().space.unknowns();

    struct Case {
      std::string scene;
      double h;
      Sparse a;
    };
    std::vector<Case> cases;
    cases.push_back({"wall", wall.mesh_size, wall_matrix});
    // The wall's unknowns with the elements' pattern plus the pairs of its contacts (all, closed).
    for (const bool closed_only : {false, true}) {
      std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
      for (const nmm::solve::Contact& c : st.view().contacts.contacts())
        if (!closed_only || c.state != nmm::solve::ContactState::open)
          pairs.emplace_back(std::min(c.at.elem_a, c.at.elem_b), std::max(c.at.elem_a, c.at.elem_b));
      std::sort(pairs.begin(), pairs.end());
      pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
      std::vector<int> offsets{0}, dofs;
      const int md = st.view().space.element_dofs();
      for (std::size_t e = 0; e < wm.element_count(); ++e) {
        dofs.insert(dofs.end(), st.view().space.element_unknowns(e), st.view().space.element_unknowns(e) + md);
        offsets.push_back(static_cast<int>(dofs.size()));
      }
      for (const auto& [a, b] : pairs) {
        dofs.insert(dofs.end(), st.view().space.element_unknowns(a), st.view().space.element_unknowns(a) + md);
        dofs.insert(dofs.end(), st.view().space.element_unknowns(b), st.view().space.element_unknowns(b) + md);
        offsets.push_back(static_cast<int>(dofs.size()));
      }
      nmm::solve::SystemMatrix sm;
      sm.build_pattern(unknowns, offsets, dofs);
      // Values: an SPD matrix of that pattern (diagonally dominant), only its structure matters.
      Sparse a = sm.matrix();
      for (int j = 0; j < a.outerSize(); ++j)
        for (Sparse::InnerIterator it(a, j); it; ++it) it.valueRef() = it.row() == it.col() ? 1e3 : -1e-3;
      cases.push_back({closed_only ? "wall_closed_pairs" : "wall_contact_pairs", wall.mesh_size, a});
    }
    // The monolith on the same mesh, then on a mesh with about the wall's unknowns.
    double h = wall.mesh_size;
    for (int pass = 0; pass < 3; ++pass) {
      const nmm::SceneDef s = monolith(n, h);
      const nmm::Mesh mm = nmm::pre::build_mesh(s, "monolith");
      nmm::solve::TimeStepper ms(mm, s, "monolith");
      ms.set_threads(1);
      ms.run_until(1e-3, [](std::int64_t) {});
      if (pass == 0) cases.push_back({"monolith_same_mesh", h, ms.view().system.matrix()});
      const double ratio = static_cast<double>(ms.view().space.unknowns()) / unknowns;
      if (pass > 0 && std::abs(ratio - 1) < 0.03) {
        cases.push_back({"monolith_same_unknowns", h, ms.view().system.matrix()});
        break;
      }
      if (pass == 2) cases.push_back({"monolith_same_unknowns", h, ms.view().system.matrix()});
      h *= std::sqrt(ratio);
    }
    for (const Case& c : cases) {
      for (const auto& o : orderings) {
        const Ordered r = factorise(c.a, o.id, reps);
        const double nu = static_cast<double>(c.a.rows());
        char line[600];
        std::snprintf(line, sizeof line, "%d,%s,%.4f,%ld,%ld,%.2f,%s,%s,%.0f,%.1f,%.2f,%.2f,%.2f,%.2f%s\n", n,
                      c.scene.c_str(), c.h, static_cast<long>(c.a.rows()), static_cast<long>(c.a.nonZeros()),
                      c.a.nonZeros() / nu, o.name, r.selected.c_str(), r.factor_nnz, r.factor_nnz / nu,
                      r.flops / 1e6, r.analyse_ms, r.factor_ms, nmm::bench::load_average(), r.ok ? "" : ",not positive definite");
        csv << line;
        std::fputs(line, stdout);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
