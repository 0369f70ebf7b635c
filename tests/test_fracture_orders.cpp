// Fracturing at cover order n ≥ 1 (docs/higher-order-covers.md "Fracturing"), checked against what
// the order-0 rule guarantees and against closed forms:
//   - a crack cut into a cantilever bent at cover order 1 and 2 carries its fields over: each
//     piece's stress polynomial gives at every point of the piece what its parent's gave (to
//     round-off, re-expanded where the piece's origin is another node), so the strain energy
//     ½∫σᵀD⁻¹σ dA (exact quadrature) is the same before and after; every cover keeps its parent's
//     cover function; the crack's own vertices lie where the parent's loop is now (on its edges
//     exactly), within O(h²·|∇²u|) of where the parent's field puts them;
//   - a body force on the cut cantilever (gravity plus a linear field: the inertia of a linear
//     acceleration) opens nothing: the crack release's share of it per piece is the integral over
//     the piece (crack_release.h, by the pieces' mass moments);
//   - a bar pulled apart at order 1 and 2 cracks once across at its tensile strength (within 2 %,
//     as at order 0), normal to σ1, and unloads to nothing; energy.csv's residual stays under 1 %
//     of the work through the crack;
//   - a run restarted from a checkpoint written after its crack formed continues bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/mesh_file.h"
#include "common/ring_geometry.h"
#include "common/scene.h"
#include "common/whole_file.h"
#include "preprocess/cover_cutter.h"
#include "preprocess/recut.h"
#include "solver/discretisation/configuration.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/stress_field.h"
#include "solver/fracture/crack_release.h"
#include "solver/fracture/state_transfer.h"
#include "solver/output/solve_run.h"
#include "solver/stepping/fracture_effect.h"
#include "solver/stepping/restart.h"
#include "solver/stepping/time_stepper.h"
#include "tests/cut_crack.h"
#include "tests/ended_ok.h"
#include "tests/rock_stress.h"
#include "tests/temp_dir.h"

namespace nmm {
namespace {

using solve::CrackSegment;
using solve::RunState;
using solve::TimeStepper;

constexpr double kE = 1e10, kNu = 0.2;  // Pa, –: the rock of every scene here (plane stress)

nlohmann::json rock(const nlohmann::json& strength, int order) {
  nlohmann::json d;
  d["plane"] = "stress";
  d["materials"]["rock"] = {{"density", 2500}, {"young", kE}, {"poisson", kNu}, {"strength", strength}};
  d["joint_sets"]["crack"] = {{"friction_deg", 30},
                              {"normal", {{"model", "constant"}, {"kn", 1e11}}},
                              {"shear", {{"model", "constant"}, {"ks", 4e10}}}};
  d["fracture"] = {{"crack_set", "crack"}};
  d["solver"] = {{"time_step", 1e-3}, {"steps", 1}, {"dynamic", false}, {"cover_order", order}};
  return d;
}

// A 4 m × 1 m cantilever held along x = 0, 200 kN/m down at its free end's mid-height, mesh 0.25
// m, solved to equilibrium in one static step: bending, so that the stress varies across every
// element (σxx linear in x and y), too strong to crack.
nlohmann::json cantilever(int order) {
  nlohmann::json d = rock({{"tensile", 1e9}, {"cohesion", 1e9}, {"friction_deg", 35}}, order);
  d["bodies"] = {{{"material", "rock"}, {"outer", {{0, 0}, {4, 0}, {4, 1}, {0, 1}}}}};
  d["mesh"]["size"] = 0.25;
  d["supports"] = {{{"points", {{0, 0}, {0, 1}}}, {"fix", "xy"}}};
  d["loads"] = {{{"point", {4, 0.5}}, {"force", {0, -2e5}}}};
  d["solver"]["static_mode"] = "equilibrium";
  return d;
}

// The bar of tests/test_fracture.cpp (4 m × 1 m, σt 1 MPa, its end x = 4 pulled 1 µm a static
// step): the tension cut-off is reached at step 400 (2.5 kPa a step).
nlohmann::json bar(int order, int steps = 1) {
  nlohmann::json d = rock({{"tensile", 1e6}, {"cohesion", 4e6}, {"friction_deg", 35}}, order);
  d["solver"]["steps"] = steps;
  d["bodies"] = {{{"material", "rock"}, {"outer", {{0, 0}, {4, 0}, {4, 1}, {0, 1}}}}};
  d["mesh"]["size"] = 0.25;
  d["supports"] = {{{"points", {{0, 0}, {0, 1}}}, {"fix", "x"}},
                   {{"points", {{4, 0}, {4, 1}}}, {"fix", "x"}, {"velocity", {1e-3, 0}}}};
  d["fixed_points"] = {{0, 0.5}};
  return d;
}

// J/m, ½ ∫ σᵀ D⁻¹ σ dA over the elements of `m` in the state s (plane stress), each element's
// loop as it is now fanned into triangles, each integrated by Dunavant's six-point rule (exact to
// degree 4: σ² at order 2).
double strain_energy(const Mesh& m, const solve::CoverSpace& space, const RunState& s) {
  constexpr double kA = 0.445948490915965, kB = 0.091576213509771;
  constexpr double kWa = 0.223381589678011, kWb = 0.109951743655322;
  const double bary[6][3] = {{kA, kA, 1 - 2 * kA}, {kA, 1 - 2 * kA, kA}, {1 - 2 * kA, kA, kA},
                             {kB, kB, 1 - 2 * kB}, {kB, 1 - 2 * kB, kB}, {1 - 2 * kB, kB, kB}};
  double U = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    const std::int32_t b = m.element_loop_offset[e], n = m.element_loop_offset[e + 1] - b;
    const double* xy = s.loop_xy.data() + 2 * b;
    auto w = [&](double x, double y) {
      const auto sg = solve::stress_at(m, space, s, e, x, y);
      return (sg[0] * sg[0] + sg[1] * sg[1] - 2 * kNu * sg[0] * sg[1] + 2 * (1 + kNu) * sg[2] * sg[2]) / kE;
    };
    for (std::int32_t i = 1; i + 1 < n; ++i) {
      const double px[3] = {xy[0], xy[2 * i], xy[2 * i + 2]}, py[3] = {xy[1], xy[2 * i + 1], xy[2 * i + 3]};
      const double area = 0.5 * ((px[1] - px[0]) * (py[2] - py[0]) - (px[2] - px[0]) * (py[1] - py[0]));
      double q = 0;
      for (int k = 0; k < 6; ++k)
        q += (k < 3 ? kWa : kWb) * w(bary[k][0] * px[0] + bary[k][1] * px[1] + bary[k][2] * px[2],
                                     bary[k][0] * py[0] + bary[k][1] * py[1] + bary[k][2] * py[2]);
      U += 0.5 * area * q;
    }
  }
  return U;
}

// m, the displacement of cover function c at the point (x, y) (cover_space.h: Σ_j p_j((x − c)/h)·d_j
// about its basis node c = (cx, cy)).
std::array<double, 2> cover_function(const solve::CoverSpace& space, const RunState& s, std::size_t c, double x,
                                     double y, double cx, double cy) {
  const std::size_t P = static_cast<std::size_t>(space.terms());
  const double xi = (x - cx) / space.scale(), eta = (y - cy) / space.scale();
  std::array<double, 2> u{0, 0};
  for (std::size_t j = 0; j < P; ++j) {
    const double pj = std::pow(xi, solve::kMonomials.p[j]) * std::pow(eta, solve::kMonomials.q[j]);
    u[0] += pj * s.cover_u[2 * P * c + 2 * j];
    u[1] += pj * s.cover_u[2 * P * c + 2 * j + 1];
  }
  return u;
}

// The cantilever at `order`, and the same state carried onto its mesh with a crack cut across it
// at mid-span (through elements and nodes' stars).
test::CutCrack cut_cantilever(int order) {
  return test::cut_crack(scene_from_json(cantilever(order), "cantilever"), "cantilever", 1e-3,
                         {Vec2{2.03, -0.01}, Vec2{2.11, 1.01}}, 2 * solve::monomial_count(order));
}

}  // namespace

class FractureAtHigherOrder : public ::testing::TestWithParam<int> {};

// The cut carries the fields over: stress polynomials point by point, the strain energy, the
// cover functions; the crack's vertices where the loop is now.
TEST_P(FractureAtHigherOrder, CuttingACrackCarriesTheFieldsOver) {
  const int order = GetParam();
  const test::CutCrack c = cut_cantilever(order);
  ASSERT_PRED1(test::ended_ok, c.outcome);
  ASSERT_GT(c.now.element_count(), c.before_mesh.element_count());
  const solve::CoverSpace old_space(c.before_mesh, order, c.scene.solver.sliver_cover_weight);
  const solve::CoverSpace new_space(c.now, order, c.scene.solver.sliver_cover_weight);

  // Each piece's stress at its own vertices (where they are now) against its parent's there.
  double worst_stress = 0, peak_stress = 0;
  std::size_t reexpanded = 0;
  for (std::size_t e = 0; e < c.now.element_count(); ++e) {
    const std::size_t p = static_cast<std::size_t>(c.map.element_parent[e]);
    if (c.map.cover_parent[static_cast<std::size_t>(c.now.element_covers[3 * e])] !=
        c.before_mesh.element_covers[3 * p])
      ++reexpanded;
    for (std::int32_t v = c.now.element_loop_offset[e]; v < c.now.element_loop_offset[e + 1]; ++v) {
      const double x = c.after.loop_xy[2 * v], y = c.after.loop_xy[2 * v + 1];
      const auto is = solve::stress_at(c.now, new_space, c.after, e, x, y);
      const auto was = solve::stress_at(c.before_mesh, old_space, c.before, p, x, y);
      for (int k = 0; k < 3; ++k)
        worst_stress = std::max(worst_stress, std::abs(is[k] - was[k])), peak_stress = std::max(peak_stress, std::abs(was[k]));
    }
  }
  // Every cover's function, at its node, against its parent's.
  double worst_u = 0, peak_u = 0;
  for (std::size_t k = 0; k < c.now.cover_count(); ++k) {
    const std::size_t p = static_cast<std::size_t>(c.map.cover_parent[k]);
    if (new_space.basis_cover(k) != static_cast<int>(k) || old_space.basis_cover(p) != static_cast<int>(p)) continue;
    const double x = c.after.cover_xy[2 * k] + 0.1, y = c.after.cover_xy[2 * k + 1] - 0.07;
    const auto node = [](const RunState& st, int b) { return std::array<double, 2>{st.cover_xy[2 * b], st.cover_xy[2 * b + 1]}; };
    const auto cn = node(c.after, new_space.basis_cover(k)), cp = node(c.before, old_space.basis_cover(p));
    const auto is = cover_function(new_space, c.after, k, x, y, cn[0], cn[1]);
    const auto was = cover_function(old_space, c.before, p, x, y, cp[0], cp[1]);
    for (int i = 0; i < 2; ++i) worst_u = std::max(worst_u, std::abs(is[i] - was[i])), peak_u = std::max(peak_u, std::abs(was[i]));
  }
  // The crack's vertices: on the parent's loop edges as they are now (a vertex the crack made on
  // an edge), and near where the parent's field puts them.
  double worst_vertex = 0, peak_vertex = 0;
  std::size_t made = 0;
  for (std::size_t e = 0; e < c.now.element_count(); ++e) {
    const std::size_t p = static_cast<std::size_t>(c.map.element_parent[e]);
    for (std::int32_t v = c.now.element_loop_offset[e]; v < c.now.element_loop_offset[e + 1]; ++v) {
      if (c.map.vertex_parent[v] >= 0) continue;
      ++made;
      const double X = c.now.loop_xy[2 * v], Y = c.now.loop_xy[2 * v + 1];
      // The parent's field: Σ_k λ_k(X) u_k(X) over its covers, as cut (the one step's field was
      // solved on the mesh as cut: its bases about the nodes as cut).
      const std::int32_t tri = c.before_mesh.element_triangle[p];
      double n[3][2];
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 2; ++i)
          n[k][i] = c.before_mesh.node_xy[2 * c.before_mesh.triangle_nodes[3 * static_cast<std::size_t>(tri) + k] + i];
      const double a2 = (n[1][0] - n[0][0]) * (n[2][1] - n[0][1]) - (n[2][0] - n[0][0]) * (n[1][1] - n[0][1]);
      std::array<double, 2> u{0, 0};
      for (int k = 0; k < 3; ++k) {
        const double* b = n[(k + 1) % 3];
        const double* q = n[(k + 2) % 3];
        const double l = ((b[0] - X) * (q[1] - Y) - (q[0] - X) * (b[1] - Y)) / a2;
        const std::size_t cov = static_cast<std::size_t>(c.before_mesh.element_covers[3 * p + static_cast<std::size_t>(k)]);
        const std::size_t bn = static_cast<std::size_t>(c.before_mesh.cover_node[static_cast<std::size_t>(old_space.basis_cover(cov))]);
        const auto uk = cover_function(old_space, c.before, cov, X, Y, c.before_mesh.node_xy[2 * bn], c.before_mesh.node_xy[2 * bn + 1]);
        u[0] += l * uk[0];
        u[1] += l * uk[1];
      }
      for (int i = 0; i < 2; ++i)
        worst_vertex = std::max(worst_vertex, std::abs(c.after.loop_u[2 * static_cast<std::size_t>(v) + i] - u[i])),
        peak_vertex = std::max(peak_vertex, std::abs(u[i]));
    }
  }
  const double U0 = strain_energy(c.before_mesh, old_space, c.before), U1 = strain_energy(c.now, new_space, c.after);
  std::printf("order %d: %zu → %zu elements (%zu pieces' stress re-expanded); stress differs by %.3g Pa of %.3g; "
              "cover functions by %.3g m of %.3g; %zu new vertices within %.3g m of the field (of %.3g m); "
              "strain energy %.12g → %.12g J/m\n",
              order, c.before_mesh.element_count(), c.now.element_count(), reexpanded, worst_stress, peak_stress,
              worst_u, peak_u, made, worst_vertex, peak_vertex, U0, U1);
  EXPECT_GT(peak_stress, 1e6);       // it is bent: the clamped end's σxx ≈ 6·M/h² = 4.8 MPa
  EXPECT_LT(worst_stress, 1e-9 * peak_stress);
  EXPECT_LT(worst_u, 1e-12 * peak_u);
  EXPECT_GT(made, 4u);
  // The loop's chords against the parent's field: an edge of length h under the curvature
  // κ = M/EI of the beam at the crack (M = P·(4 − 2.03) m) sags κh²/8 from its chord; the crack's
  // vertices on edges lie on the chords, where the loops are now (not moved at all: 1.9 mm off).
  const double kappa = 2e5 * (4 - 2.03) / (kE / 12), h = 0.25;
  EXPECT_LT(worst_vertex, 2 * kappa * h * h / 8);
  EXPECT_NEAR(U1, U0, 1e-10 * U0);
  // A cantilever's strain energy is its end load's work: ½·P·δ, δ = P·L³/(3EI) + shear; within 10 %
  // of the beam's δ = 4PL³/(E·b·t³) + 1.2·P·L/(G·A) at this mesh.
  const double P = 2e5, L = 4, G = kE / (2 * (1 + kNu));
  const double delta = 4 * P * L * L * L / kE + 1.2 * P * L / G;
  EXPECT_NEAR(U0, 0.5 * P * delta, 0.1 * 0.5 * P * delta);
}

// A body force opens nothing: the start of a step out of balance by a body force per unit mass
// f(x) alone (gravity, or the inertia −a(x) of an acceleration field) on the cantilever cut
// across releases r = 0 (crack_release.h: each piece's share M_i M_P⁻¹ B_P is the integral over
// the piece where f has degree ≤ n). B = ∫ ρ φ f dA is integrated here on its own, by Dunavant's
// six-point rule on each element's loop fanned into triangles (exact to degree 4: φ·f has degree
// n + 2), and f is linear. The mass share of the linear terms, the earlier rule, misses by the
// pieces' first moments.
TEST_P(FractureAtHigherOrder, ReleaseOfABodyForceIsNothing) {
  const int order = GetParam();
  const test::CutCrack c = cut_cantilever(order);
  ASSERT_PRED1(test::ended_ok, c.outcome);
  const solve::Model model(c.now, c.cracked, "cantilever");
  const solve::CoverSpace space(c.now, order, c.scene.solver.sliver_cover_weight);
  solve::Configuration config(c.now, &space);
  ASSERT_LT(config.place(c.after.cover_xy), 0);
  const auto f = [](double x, double y) {  // N/kg: gravity plus a linear field
    return std::array<double, 2>{0.3 + 1.1 * x - 0.7 * y, -9.81 + 0.4 * x + 0.9 * y};
  };
  constexpr double kA = 0.445948490915965, kB = 0.091576213509771;
  constexpr double kWa = 0.223381589678011, kWb = 0.109951743655322;
  const double bary[6][3] = {{kA, kA, 1 - 2 * kA}, {kA, 1 - 2 * kA, kA}, {1 - 2 * kA, kA, kA},
                             {kB, kB, 1 - 2 * kB}, {kB, 1 - 2 * kB, kB}, {1 - 2 * kB, kB, kB}};
  const int P = space.terms(), dpc = space.dofs_per_cover();
  Eigen::VectorXd B = Eigen::VectorXd::Zero(space.unknowns());
  std::vector<double> mass(static_cast<std::size_t>(space.unknowns() / dpc), 0.0), phi(static_cast<std::size_t>(3 * P));
  for (std::size_t e = 0; e < c.now.element_count(); ++e) {
    const std::int32_t b = c.now.element_loop_offset[e], n = c.now.element_loop_offset[e + 1] - b;
    const double* xy = c.after.loop_xy.data() + 2 * b;
    const int* unknown = space.element_unknowns(e);
    const double rho = model.density(e);
    for (std::int32_t i = 1; i + 1 < n; ++i) {
      const double px[3] = {xy[0], xy[2 * i], xy[2 * i + 2]}, py[3] = {xy[1], xy[2 * i + 1], xy[2 * i + 3]};
      const double area = 0.5 * ((px[1] - px[0]) * (py[2] - py[0]) - (px[2] - px[0]) * (py[1] - py[0]));
      for (int q = 0; q < 6; ++q) {
        const double x = bary[q][0] * px[0] + bary[q][1] * px[1] + bary[q][2] * px[2];
        const double y = bary[q][0] * py[0] + bary[q][1] * py[1] + bary[q][2] * py[2];
        const double w = rho * area * (q < 3 ? kWa : kWb);
        config.shape_values(e, x, y, phi.data());
        const auto fx = f(x, y);
        for (int a = 0; a < 3 * P; ++a)
          for (int d = 0; d < 2; ++d) B[unknown[2 * a + d]] += w * phi[static_cast<std::size_t>(a)] * fx[static_cast<std::size_t>(d)];
        for (int k = 0; k < 3; ++k) mass[static_cast<std::size_t>(unknown[2 * k * P] / dpc)] += w * phi[static_cast<std::size_t>(k * P)];
      }
    }
  }
  const Eigen::VectorXd r = solve::cut_release_force(model, config, c.after, {}, c.map.cover_parent, B);
  // The earlier rule: each piece's B less its mass's share of its parent's, every term alike.
  std::map<std::int32_t, std::pair<double, Eigen::VectorXd>> parents;  // parent: mass, Σ B
  std::map<std::int32_t, int> pieces;
  std::vector<std::int32_t> parent_of(mass.size(), -1);
  for (std::size_t k = 0; k < c.now.cover_count(); ++k) {
    const std::size_t u = static_cast<std::size_t>(space.first_unknown(k) / dpc);
    if (space.cover_of_unknown(static_cast<int>(u) * dpc) != static_cast<int>(k)) continue;
    parent_of[u] = c.map.cover_parent[k];
    auto& [m, sum] = parents.try_emplace(parent_of[u], 0.0, Eigen::VectorXd::Zero(dpc)).first->second;
    m += mass[u];
    sum += B.segment(static_cast<Eigen::Index>(u) * dpc, dpc);
    ++pieces[parent_of[u]];
  }
  double worst = 0, worst_mass_share = 0, peak = 0;
  std::size_t split = 0;
  for (std::size_t u = 0; u < mass.size(); ++u) {
    const Eigen::VectorXd Bu = B.segment(static_cast<Eigen::Index>(u) * dpc, dpc);
    peak = std::max(peak, Bu.cwiseAbs().maxCoeff());
    worst = std::max(worst, r.segment(static_cast<Eigen::Index>(u) * dpc, dpc).cwiseAbs().maxCoeff());
    if (parent_of[u] < 0 || pieces[parent_of[u]] < 2) continue;
    ++split;
    const auto& [m, sum] = parents[parent_of[u]];
    worst_mass_share = std::max(worst_mass_share, (Bu - (mass[u] / m) * sum).cwiseAbs().maxCoeff());
  }
  std::printf("order %d: %zu pieces of split covers; a linear body force's release: at most %.3g N/m (moments), "
              "%.3g N/m (mass share), of forces up to %.3g N/m\n",
              order, split, worst, worst_mass_share, peak);
  EXPECT_GE(split, 8u);
  EXPECT_LT(worst, 1e-10 * peak);
  EXPECT_GT(worst_mass_share, 1e-3 * peak);  // the test tells the two rules apart
}

// The bar cracks once across at its tensile strength and unloads; the energy balance closes: what
// the bar held before its first crack (U + S of that row; σt²·A·L/(2E) = 200 J/m of strain) leaves
// through the crack's release (fracture) and the motion DDA's static steps throw away as the bar
// springs back over the next steps (damped), as at order 0 (tests/test_fracture.cpp
// TensionBarReleasesItsStrainEnergyIntoTheFractureColumn).
TEST_P(FractureAtHigherOrder, BarCracksAcrossAtItsTensileStrengthAndBalances) {
  const int order = GetParam();
  nlohmann::json doc = bar(order, 600);
  doc["solver"]["output_every"] = 1;
  const SceneDef s = scene_from_json(doc, "bar");
  Mesh m = pre::build_mesh(s, "bar");
  m.scene_text = doc.dump();
  m.scene_sha256 = sha256(m.scene_text);
  const test::TempDir dir;
  solve::SolveOptions o;
  o.out_dir = dir.path("run");
  solve::SolveRun run(m, "bar", o);
  double peak = 0, last = 0;
  std::int64_t peak_step = 0;
  solve::StepFunction watch([&](const solve::RunView& v, std::int64_t n, bool) {
    last = std::abs(test::rock_mean_stress(v, 0));  // Pa: its end reaction per unit width
    if (last > peak) peak = last, peak_step = n;
  });
  run.add(watch);
  const nlohmann::json summary = run.run();
  const Outcome outcome = run.outcome();
  ASSERT_PRED1(test::ended_ok, outcome);
  ASSERT_GT(summary["fracture"]["segments"].get<int>(), 0);
  const std::int64_t first = summary["fracture"]["first_crack_step"].get<std::int64_t>();
  // energy.csv: the row before the first crack, the last row, the largest |residual| against the
  // work done so far.
  std::ifstream csv(dir.path("run/energy.csv"));
  std::string line, cell;
  std::getline(csv, line);
  std::vector<std::string> names;
  for (std::istringstream head(line); std::getline(head, cell, ',');) names.push_back(cell);
  std::map<std::string, double> before, end;
  double worst = 0, work = 0;
  while (std::getline(csv, line)) {
    std::istringstream in(line);
    std::map<std::string, double> row;
    for (const std::string& n : names) {
      std::getline(in, cell, ',');
      row[n] = std::stod(cell);
    }
    if (row["step"] == static_cast<double>(first - 1)) before = row;
    work = std::max(work, std::abs(row["load_work"]));
    if (work > 0) worst = std::max(worst, 100 * std::abs(row["residual"]) / work);
    end = row;
  }
  const double held = before["strain"] + before["springs"];
  const double released = end["fracture"] + end["damped"] - before["damped"];
  const std::vector<CrackSegment> segments = fracture_of(run.view()).segments();
  double length = 0;
  for (const CrackSegment& c : segments) length += std::hypot(c.b.x - c.a.x, c.b.y - c.a.y);
  if (std::getenv("ORDERS_TRACE"))  // the segments, to see where the order-1 bar's crack scatters
    for (const CrackSegment& c : segments)
      std::printf("  segment crack %d step %lld (%.4f, %.4f) → (%.4f, %.4f)\n", c.crack, static_cast<long long>(c.step),
                  c.a.x, c.a.y, c.b.x, c.b.y);
  std::printf("order %d: peak %.6g Pa at step %lld, end %.4g Pa; %zu segments, %.4f m of crack; held %.5g J/m "
              "(strain %.5g), released %.5g (fracture %.5g + damped since %.5g); residual at worst %.3g %% of the "
              "work (%.5g J/m)\n",
              order, peak, static_cast<long long>(peak_step), last, segments.size(), length, held, before["strain"],
              released, end["fracture"], end["damped"] - before["damped"], worst, work);
  EXPECT_NEAR(peak, 1e6, 0.02e6);
  EXPECT_LT(last, 0.02e6);           // cracked through: it carries nothing
  EXPECT_NEAR(length, 1.0, 0.02);    // one crack across the 1 m bar
  EXPECT_NEAR(before["strain"], 200, 0.02 * 200);
  EXPECT_NEAR(released, held, 0.02 * held);
  EXPECT_LT(worst, 1.0);
}

// A checkpoint written after the crack formed: the restarted run continues bit for bit.
TEST_P(FractureAtHigherOrder, RestartAfterTheCrackContinuesBitForBit) {
  const int order = GetParam();
  const nlohmann::json doc = bar(order);
  const SceneDef s = scene_from_json(doc, "bar");
  Mesh m = pre::build_mesh(s, "bar");
  m.scene_text = doc.dump();
  m.scene_sha256 = sha256(m.scene_text);
  TimeStepper straight(m, s, "bar"), first(m, s, "bar"), second(m, s, "bar");
  ASSERT_PRED1(test::ended_ok, straight.run_until(0.42, [](std::int64_t) {}));
  ASSERT_PRED1(test::ended_ok, first.run_until(0.405, [](std::int64_t) {}));
  ASSERT_FALSE(fracture_of(first.view()).segments().empty()) << "the checkpoint must hold the crack";
  const std::string path = ::testing::TempDir() + "/cracked_order.nmmstate";
  solve::write_checkpoint(first.view(), path);
  second.restart_from(path);
  EXPECT_EQ(solve::state_hash(second.view()), solve::state_hash(first.view()));
  ASSERT_PRED1(test::ended_ok, second.run_until(0.42, [](std::int64_t) {}));
  EXPECT_EQ(second.view().mesh.element_count(), straight.view().mesh.element_count());
  EXPECT_EQ(solve::state_hash(second.view()), solve::state_hash(straight.view()));
}

INSTANTIATE_TEST_SUITE_P(Orders, FractureAtHigherOrder, ::testing::Values(1, 2),
                         [](const ::testing::TestParamInfo<int>& i) { return "n" + std::to_string(i.param); });

}  // namespace nmm
