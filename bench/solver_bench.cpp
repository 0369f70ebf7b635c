// Time per step against unknowns, with its breakdown, next to one bare CHOLMOD factorisation and
// solve of the same matrix.
//
//   solver_bench [--quick] [--csv FILE]
//
// Scene: a square elastic body (h = 1 m) under gravity, held at its two bottom corners, dynamic;
// its side is chosen for about the wanted number of unknowns. Each size runs one warm-up step
// (it includes CHOLMOD's symbolic analysis, done once per pattern) and then times 5 steps. The
// reference is Eigen's CholmodSupernodalLLT on the last step's matrix: analysis first (not
// timed), then factorize + solve, best of 3. Issue-3 target: step / reference ≤ 1.5 at 200,000
// unknowns.
#include <Eigen/CholmodSupport>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "solver/stepping/time_stepper_probe.h"
#include "preprocess/cover_cutter.h"
#include "common/stopwatch.h"
#include "solver/stepping/time_stepper.h"
#include "solver/discretisation/blas_kernels.h"

namespace {
}  // namespace

int main(int argc, char** argv) {
  nmm::solve::choose_blas_kernels(argv);  // OpenBLAS's kernels, before any BLAS call (blas_kernels.h)
  bool quick = false;
  std::string csv_path = "solver_bench.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: solver_bench [--quick] [--csv FILE]\n");
      return 2;
    }
  }
  std::vector<double> targets = quick ? std::vector<double>{5e3, 2e4}
                                      : std::vector<double>{1e4, 2.5e4, 5e4, 1e5, 2e5};
  const char* header =
      "unknowns,elements,step_s,assembly_s,factorisation_s,solves_s,geometry_update_s,"
      "reference_factor_solve_s,step_over_reference\n";
  std::ofstream csv = nmm::bench::start_csv(csv_path, header);
  for (double target : targets) {
    const double h = 1.0, side = std::sqrt(target * h * h * std::sqrt(3.0) / 4);
    nmm::SceneDef s;
    s.materials.push_back({"rock", 2650, 1e10, 0.25, {}});
    nmm::BodyDef b;
    b.material = 0;
    b.outer = {{0, 0}, {side, 0}, {side, side}, {0, side}};
    s.bodies.push_back(b);
    s.mesh_size = h;
    s.has_gravity = true;
    s.gravity = {0, -9.81};
    s.fixed_points = {{0.1, 0.1}, {side - 0.1, 0.1}};
    const nmm::Mesh m = nmm::pre::build_mesh(s, "bench");
    nmm::solve::TimeStepper st(m, s, "bench");
    const double dt = 1e-3;
    st.step(dt);  // warm-up, with the symbolic analysis
    const nmm::solve::StepTimings t0 = st.view().timings;
    const int steps = 5;
    const nmm::Stopwatch w0;
    for (int i = 0; i < steps; ++i) st.step(dt);
    const double step_s = w0.seconds() / steps;
    const nmm::solve::StepTimings& t1 = st.view().timings;

    using Llt = Eigen::CholmodSupernodalLLT<nmm::solve::SystemMatrix::Sparse, Eigen::Upper>;
    Llt llt;
    const auto& k = st.view().system.matrix();
    llt.analyzePattern(k);
    double ref = std::numeric_limits<double>::infinity();
    for (int r = 0; r < 3; ++r) {
      const nmm::Stopwatch r0;
      llt.factorize(k);
      const Eigen::VectorXd x = llt.solve(nmm::solve::TimeStepperProbe::rhs(st));
      ref = std::min(ref, r0.seconds());
      if (llt.info() != Eigen::Success || !std::isfinite(x.norm())) return 1;
    }
    char line[512];
    std::snprintf(line, sizeof line, "%d,%zu,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f\n", st.view().space.unknowns(),
                  m.element_count(), step_s, (t1.assembly - t0.assembly) / steps,
                  (t1.factorisation - t0.factorisation) / steps, (t1.solves - t0.solves) / steps,
                  (t1.geometry_update - t0.geometry_update) / steps, ref, step_s / ref);
    csv << line;
    std::fputs(line, stdout);
    std::fflush(stdout);
  }
  return 0;
}
