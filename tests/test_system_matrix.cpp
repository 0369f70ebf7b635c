// The system matrix's pattern (solver/discretisation/system_matrix.h): a pattern that grows by groups is grown
// in place, and must give bit for bit what a build from scratch gives — the same nonzeros,
// every group's values at the same places — with no new symbolic analysis where the new groups
// couple only unknowns already coupled.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#if defined(__x86_64__) || defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include "preprocess/cover_cutter.h"
#include "reference/brick_wall.h"
#include "solver/discretisation/fill_ordering.h"
#include "solver/discretisation/parked_array.h"
#include "solver/discretisation/system_matrix.h"
#include "solver/stepping/time_stepper.h"

namespace {

using nmm::solve::ParkedArray;
using nmm::solve::SingleFactor;
using nmm::solve::SystemMatrix;

struct Groups {
  std::vector<int> offsets{0}, dofs;
  Groups& add(std::initializer_list<int> g) {
    dofs.insert(dofs.end(), g);
    offsets.push_back(static_cast<int>(dofs.size()));
    return *this;
  }
};

// Each group adds a block of its own numbers (column-major m × m, symmetric), and every
// diagonal a weight, so a misplaced entry shows in the values; returns the assembled matrix.
SystemMatrix::Sparse assembled(SystemMatrix& k, const Groups& g, int n) {
  k.set_zero();
  for (std::size_t e = 0; e + 1 < g.offsets.size(); ++e) {
    const int m = g.offsets[e + 1] - g.offsets[e];
    std::vector<double> block(static_cast<std::size_t>(m * m));
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        block[static_cast<std::size_t>(j * m + i)] = i == j ? 10.0 + static_cast<double>(e) : 0.1 * static_cast<double>(e + 1) / (1 + i + j);
    k.add_group(e, block.data());
  }
  for (int i = 0; i < n; ++i) k.add_diagonal(i, 1.0 + i);
  return k.matrix();
}

void expect_same(const SystemMatrix::Sparse& a, const SystemMatrix::Sparse& b) {
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  for (int c = 0; c <= a.cols(); ++c) ASSERT_EQ(a.outerIndexPtr()[c], b.outerIndexPtr()[c]) << "column " << c;
  for (int p = 0; p < a.nonZeros(); ++p) {
    ASSERT_EQ(a.innerIndexPtr()[p], b.innerIndexPtr()[p]) << "entry " << p;
    ASSERT_EQ(a.valuePtr()[p], b.valuePtr()[p]) << "entry " << p;  // bit for bit
  }
}

constexpr int kN = 9;

Groups base() { return Groups{}.add({0, 1, 2}).add({2, 3, 4}).add({4, 5, 6}).add({6, 7, 8}).add({0, 1, 4, 5}); }

// k's checkpoint restored into a matrix (set up by set_up) of the pattern g: analysed under the
// checkpoint's ordering (none found anew), with k's fill, it solves b bit for bit as k does, and
// so does the next factorisation of new values in both. k is refactorised.
template <class SetUp>
void expect_restored_bitwise(SystemMatrix& k, const SetUp& set_up, const Groups& g, int n, const Eigen::VectorXd& b) {
  const Eigen::VectorXd x = k.solve(b);
  SystemMatrix restored;
  set_up(restored);
  restored.build_pattern(n, g.offsets, g.dofs);
  ASSERT_TRUE(restored.factor_from_source(k.factor_source()));
  EXPECT_EQ(restored.orderings(), 0u);
  EXPECT_EQ(restored.factor_nonzeros(), k.factor_nonzeros());
  const Eigen::VectorXd y = restored.solve(b);
  for (int i = 0; i < n; ++i) ASSERT_EQ(y[i], x[i]) << "unknown " << i;
  for (SystemMatrix* m : {&k, &restored}) {
    assembled(*m, g, n);
    for (int i = 0; i < n; i += 3) m->add_diagonal(i, 0.5);
    ASSERT_TRUE(m->factorize());
  }
  const Eigen::VectorXd x2 = k.solve(b), y2 = restored.solve(b);
  for (int i = 0; i < n; ++i) ASSERT_EQ(y2[i], x2[i]) << "unknown " << i;
  EXPECT_EQ(restored.orderings(), 0u);
}

}  // namespace

TEST(SystemMatrixPattern, GrowthByCoupledUnknownsKeepsPatternAndAnalysis) {
  SystemMatrix k;
  k.build_pattern(kN, base().offsets, base().dofs);
  assembled(k, base(), kN);
  ASSERT_TRUE(k.factorize());
  ASSERT_EQ(k.analyses(), 1u);
  // New groups inside the old ones' couplings (one with a repeated unknown), among the old ones.
  const Groups grown = Groups{}.add({0, 1, 2}).add({1, 2}).add({2, 3, 4}).add({4, 5, 6}).add({5, 4, 5}).add({6, 7, 8}).add({0, 1, 4, 5}).add({7, 8});
  k.build_pattern(kN, grown.offsets, grown.dofs);
  EXPECT_EQ(k.builds(), 1u) << "grown in place";
  SystemMatrix fresh;
  fresh.build_pattern(kN, grown.offsets, grown.dofs);
  expect_same(assembled(k, grown, kN), assembled(fresh, grown, kN));
  ASSERT_TRUE(k.factorize());
  EXPECT_EQ(k.analyses(), 1u) << "the pattern did not change: its analysis holds";
}

TEST(SystemMatrixPattern, SuccessiveGrowthsInPlaceAssembleAsAFreshBuild) {
  // The scatter grows within its own arrays, from the last group to the first, into the room
  // kept by the growth before (system_matrix.cpp grow_in_place): growths in a row, by groups
  // inside the old couplings and by new couplings, before, among and after the old groups, must
  // assemble each pattern as a build from scratch does, bit for bit.
  SystemMatrix k;
  k.build_pattern(kN, base().offsets, base().dofs);
  const std::vector<Groups> growths = {
      Groups{}.add({0, 1, 2}).add({1, 2}).add({2, 3, 4}).add({4, 5, 6}).add({6, 7, 8}).add({0, 1, 4, 5}),
      Groups{}.add({0, 1}).add({0, 1, 2}).add({1, 2}).add({2, 3, 4}).add({4, 5, 6}).add({5, 4, 5}).add({6, 7, 8}).add({0, 1, 4, 5}).add({7, 8}),
      Groups{}.add({0, 1}).add({0, 1, 2}).add({1, 2}).add({2, 3, 4}).add({3, 6}).add({4, 5, 6}).add({5, 4, 5}).add({6, 7, 8}).add({0, 1, 4, 5}).add({7, 8}).add({8, 0, 7}),
      Groups{}.add({2, 8}).add({0, 1}).add({0, 1, 2}).add({1, 2}).add({2, 3, 4}).add({3, 6}).add({4, 5, 6}).add({5, 4, 5}).add({6, 7, 8}).add({0, 1, 4, 5}).add({7, 8}).add({8, 0, 7}).add({3, 4})};
  for (std::size_t i = 0; i < growths.size(); ++i) {
    SCOPED_TRACE("growth " + std::to_string(i + 1));
    k.build_pattern(kN, growths[i].offsets, growths[i].dofs);
    EXPECT_EQ(k.builds(), 1u) << "grown in place";
    SystemMatrix fresh;
    fresh.build_pattern(kN, growths[i].offsets, growths[i].dofs);
    expect_same(assembled(k, growths[i], kN), assembled(fresh, growths[i], kN));
  }
}

TEST(SystemMatrixPattern, ManyNewCouplingsMergedWithinTheMatrixArraysAssembleAsAFreshBuild) {
  // A growth merges its new entries into the matrix's own arrays, from the last column to the
  // first, and moves each old group's slots by the new entries before them (grow_in_place):
  // many new couplings per growth, several in one column, in the first and the last columns,
  // over growths in a row that reuse the arrays' room, must assemble as a fresh build, and the
  // saved values (save(), whose copy keeps room too) must be the assembled ones.
  constexpr int n = 240;
  Groups g;
  for (int e = 0; e + 2 < n; e += 2) g.add({e, e + 1, e + 2});  // a chain of elements
  SystemMatrix k;
  k.build_pattern(n, g.offsets, g.dofs);
  std::uint32_t state = 12345;  // a fixed pseudo-random sequence: the same pairs every run
  const auto next = [&state](int below) {
    state = state * 1664525u + 1013904223u;
    return static_cast<int>((state >> 8) % static_cast<std::uint32_t>(below));
  };
  std::size_t last_nonzeros = k.nonzeros();
  for (int growth = 1; growth <= 5; ++growth) {
    SCOPED_TRACE("growth " + std::to_string(growth));
    // New pairs after the old groups (a contact's pair of elements), each coupling two distant
    // unknowns; some share an unknown (several new entries in one column).
    for (int p = 0; p < 30; ++p) {
      const int a = next(n), b = (a + 7 + next(n - 14)) % n;
      g.add({a, b, p % 3 == 0 ? 0 : n - 1});
    }
    k.build_pattern(n, g.offsets, g.dofs);
    EXPECT_EQ(k.builds(), 1u) << "grown in place";
    EXPECT_GT(k.nonzeros(), last_nonzeros);
    last_nonzeros = k.nonzeros();
    SystemMatrix fresh;
    fresh.build_pattern(n, g.offsets, g.dofs);
    const SystemMatrix::Sparse a = assembled(k, g, n);
    expect_same(a, assembled(fresh, g, n));
    k.save();
    k.set_zero();
    expect_same(k.saved_matrix(), a);
    k.restore();
    expect_same(k.matrix(), a);
  }
}

TEST(SystemMatrixPattern, NewCouplingsAreMergedAndDroppedGroupsRebuild) {
  // Groups coupling unknowns not yet coupled (3 with 6; 0 with 8 and 7, the first and last
  // columns): new nonzeros merged into their columns, and a new analysis.
  SystemMatrix k;
  k.build_pattern(kN, base().offsets, base().dofs);
  assembled(k, base(), kN);
  ASSERT_TRUE(k.factorize());
  const Groups wider = Groups{}.add({0, 1, 2}).add({2, 3, 4}).add({3, 6}).add({4, 5, 6}).add({6, 7, 8}).add({0, 1, 4, 5}).add({8, 0, 7});
  k.build_pattern(kN, wider.offsets, wider.dofs);
  EXPECT_EQ(k.builds(), 1u) << "grown in place";
  SystemMatrix fresh;
  fresh.build_pattern(kN, wider.offsets, wider.dofs);
  const auto a = assembled(k, wider, kN);
  expect_same(a, assembled(fresh, wider, kN));
  EXPECT_EQ(static_cast<std::size_t>(a.nonZeros()), k.nonzeros());
  ASSERT_TRUE(k.factorize());
  EXPECT_EQ(k.analyses(), 2u);
  // Dropping a group (the pattern shrinks to the pairs in use) builds afresh: the coupling of
  // 0, 1 with 4, 5 goes.
  k.build_pattern(kN, base().offsets, base().dofs);
  EXPECT_EQ(k.builds(), 2u);
  SystemMatrix again;
  const Groups fewer = Groups{}.add({0, 1, 2}).add({2, 3, 4}).add({4, 5, 6}).add({6, 7, 8});
  k.build_pattern(kN, fewer.offsets, fewer.dofs);
  EXPECT_EQ(k.builds(), 3u);
  again.build_pattern(kN, fewer.offsets, fewer.dofs);
  expect_same(assembled(k, fewer, kN), assembled(again, fewer, kN));
  EXPECT_LT(k.nonzeros(), static_cast<std::size_t>(a.nonZeros()));
}

namespace {
// The hexahedra of a k × k × k grid of nodes, one unknown per node, one group per cell: a
// pattern whose factor is dense enough (nnz(L) / nnz(A) ≥ 5, flops / nnz(L) ≥ 500) for
// CHOLMOD's default strategy to try METIS after AMD.
Groups cube_grid(int k) {
  Groups g;
  const auto node = [k](int i, int j, int l) { return (l * k + j) * k + i; };
  for (int l = 0; l + 1 < k; ++l)
    for (int j = 0; j + 1 < k; ++j)
      for (int i = 0; i + 1 < k; ++i)
        g.add({node(i, j, l), node(i + 1, j, l), node(i, j + 1, l), node(i + 1, j + 1, l), node(i, j, l + 1),
               node(i + 1, j, l + 1), node(i, j + 1, l + 1), node(i + 1, j + 1, l + 1)});
  return g;
}
}  // namespace

TEST(SystemMatrixOrdering, AmdAloneWhereTheDefaultWouldTryMetis) {
  constexpr int kSide = 20;
  const Groups g = cube_grid(kSide);
  const int n = kSide * kSide * kSide;
  SystemMatrix by_default, amd;
  amd.set_amd_only(true);
  for (SystemMatrix* k : {&by_default, &amd}) {
    k->build_pattern(n, g.offsets, g.dofs);
    assembled(*k, g, n);
    ASSERT_TRUE(k->factorize());
  }
  // The precondition: here CHOLMOD's own strategy tries METIS and keeps it (fewer nonzeros).
  ASSERT_EQ(by_default.ordering(), "metis");
  EXPECT_EQ(amd.ordering(), "amd");
  EXPECT_GT(amd.factor_nonzeros(), by_default.factor_nonzeros());
  // Back to the default: METIS again at the next analysis.
  amd.set_amd_only(false);
  Groups other;
  other.dofs = {0, n - 1};
  other.offsets = {0, 2};
  amd.build_pattern(n, other.offsets, other.dofs);  // another pattern, then the grid's again
  amd.build_pattern(n, g.offsets, g.dofs);
  assembled(amd, g, n);
  ASSERT_TRUE(amd.factorize());
  EXPECT_EQ(amd.ordering(), "metis");
}

namespace {
// The triangles of a k × k grid of covers with `dofs` unknowns each (a cover's unknowns
// consecutive, as cover_space.h numbers them), one group per triangle.
Groups plane_grid(int k, int dofs) {
  Groups g;
  const auto add = [&](int a, int b, int c) {
    for (const int v : {a, b, c})
      for (int s = 0; s < dofs; ++s) g.dofs.push_back(v * dofs + s);
    g.offsets.push_back(static_cast<int>(g.dofs.size()));
  };
  for (int j = 0; j + 1 < k; ++j)
    for (int i = 0; i + 1 < k; ++i) {
      add(j * k + i, j * k + i + 1, (j + 1) * k + i + 1);
      add(j * k + i, (j + 1) * k + i + 1, (j + 1) * k + i);
    }
  return g;
}
}  // namespace

TEST(SystemMatrixOrdering, BlockOrderingKeepsEachCoverTogether) {
  // 3 covers of 2 unknowns, then 2 unknowns of their own (an effect's): a permutation of all 8,
  // each cover's unknowns consecutive and in order.
  const Groups g = Groups{}.add({0, 1, 2, 3}).add({2, 3, 4, 5, 6}).add({0, 1, 7});
  SystemMatrix k;
  k.build_pattern(8, g.offsets, g.dofs);
  const SystemMatrix::Sparse& a = k.matrix();
  for (const auto method : {nmm::solve::FillOrdering::amd, nmm::solve::FillOrdering::metis}) {
    const std::vector<int> perm = nmm::solve::block_ordering(8, a.outerIndexPtr(), a.innerIndexPtr(), 2, method, 6);
    ASSERT_EQ(perm.size(), 8u);
    std::vector<int> sorted = perm;
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < 8; ++i) EXPECT_EQ(sorted[static_cast<std::size_t>(i)], i);
    for (std::size_t p = 0; p < perm.size(); ++p)
      if (perm[p] < 6 && perm[p] % 2 == 0) {
        ASSERT_LT(p + 1, perm.size());
        EXPECT_EQ(perm[p + 1], perm[p] + 1) << "cover " << perm[p] / 2 << " split";
      }
  }
}

TEST(SystemMatrixOrdering, MetisOnCoversFromItsSizeSolvesAsAmdAndRestartsBitwise) {
  // 100 × 100 covers of 2 unknowns, METIS from 20,000 unknowns on (the default,
  // kBlockOrderingUnknowns, is larger: a test of its size would take long).
  constexpr int kSide = 100;
  const Groups g = plane_grid(kSide, 2);
  const int n = 2 * kSide * kSide;
  SystemMatrix amd, metis;
  amd.set_amd_only(true);
  metis.set_amd_only(true);
  metis.set_block_ordering(2, n, n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.37 * i) + 0.1;
  std::vector<Eigen::VectorXd> x;
  for (SystemMatrix* k : {&amd, &metis}) {
    k->build_pattern(n, g.offsets, g.dofs);
    assembled(*k, g, n);
    ASSERT_TRUE(k->factorize());
    x.push_back(k->solve(b));
    // The solve answers K x = b to round-off.
    const Eigen::VectorXd r = b - k->matrix().selfadjointView<Eigen::Upper>() * x.back();
    EXPECT_LT(r.norm(), 1e-12 * b.norm());
  }
  EXPECT_EQ(amd.ordering(), "amd");
  EXPECT_EQ(metis.ordering(), "metis_covers");
  EXPECT_LT((x[0] - x[1]).norm(), 1e-10 * x[0].norm());
  // A checkpoint's factorisation, restored into a matrix of the same ordering, solves bit for
  // bit as the one it was taken from (the ordering is a function of the pattern alone).
  SystemMatrix restored;
  restored.set_amd_only(true);
  restored.set_block_ordering(2, n, n);
  restored.build_pattern(n, g.offsets, g.dofs);
  ASSERT_TRUE(restored.factor_from_source(metis.factor_source()));
  EXPECT_EQ(restored.ordering(), "metis_covers");
  const Eigen::VectorXd y = restored.solve(b);
  for (int i = 0; i < n; ++i) ASSERT_EQ(y[i], x[1][i]) << "unknown " << i;
  // Below its size the matrix keeps AMD.
  const Groups small = plane_grid(20, 2);
  SystemMatrix few;
  few.set_amd_only(true);
  few.set_block_ordering(2, 800, 801);
  few.build_pattern(800, small.offsets, small.dofs);
  assembled(few, small, 800);
  ASSERT_TRUE(few.factorize());
  EXPECT_EQ(few.ordering(), "amd");
}

namespace {
// Groups of two covers of 2 unknowns each (a contact's pair, reduced to one cover per side).
Groups with_pairs(Groups g, const std::vector<std::pair<int, int>>& pairs) {
  for (const auto& [a, b] : pairs) g.add({2 * a, 2 * a + 1, 2 * b, 2 * b + 1});
  return g;
}

// 100 × 100 covers of 2 unknowns (METIS on the covers from 20,000 unknowns), the pattern grown by
// pairs of covers two columns apart (contacts between near elements), and a right-hand side.
struct GrownGrid {
  static constexpr int kSide = 100;
  int n = 2 * kSide * kSide;
  Groups g = plane_grid(kSide, 2);
  Groups grown;
  Eigen::VectorXd b;
  GrownGrid() : b(n) {
    std::vector<std::pair<int, int>> near;
    for (int j = 5; j < kSide; j += 10)
      for (int i = 3; i + 2 < kSide; i += 7) near.emplace_back(j * kSide + i, j * kSide + i + 2);
    grown = with_pairs(g, near);
    for (int i = 0; i < n; ++i) b[i] = std::cos(0.21 * i) - 0.2;
  }
};
}  // namespace

TEST(SystemMatrixOrdering, AKeptOrderingServesGrownPatternsAndRestartsBitwise) {
  // 100 × 100 covers, METIS on the covers from 20,000 unknowns. The pattern grows by pairs of
  // covers two columns apart (contacts between near elements): the ordering found at the first
  // analysis is kept, and a factorisation under it solves as an ordering found anew.
  constexpr int kSide = GrownGrid::kSide;
  const GrownGrid grid;
  const int n = grid.n;
  const Groups& g = grid.g;
  const Groups& grown = grid.grown;
  const Eigen::VectorXd& b = grid.b;
  const auto set_up = [&](SystemMatrix& k) {
    k.set_amd_only(true);
    k.set_block_ordering(2, n, n);
  };
  SystemMatrix k;
  set_up(k);
  k.build_pattern(n, g.offsets, g.dofs);
  assembled(k, g, n);
  ASSERT_TRUE(k.factorize());
  EXPECT_EQ(k.orderings(), 1u);
  const double first_fill = k.factor_nonzeros();
  k.build_pattern(n, grown.offsets, grown.dofs);
  assembled(k, grown, n);
  ASSERT_TRUE(k.factorize());
  EXPECT_EQ(k.analyses(), 2u);
  EXPECT_EQ(k.orderings(), 1u) << "fill " << k.factor_nonzeros() << " against " << first_fill;
  EXPECT_EQ(k.ordering(), "metis_covers");
  EXPECT_GT(k.factor_nonzeros(), first_fill);  // the new couplings fill in
  EXPECT_LE(k.factor_nonzeros(), nmm::solve::kOrderingRefill * first_fill);
  const Eigen::VectorXd x = k.solve(b);
  EXPECT_LT((b - k.matrix().selfadjointView<Eigen::Upper>() * x).norm(), 1e-12 * b.norm());
  // A matrix that orders the grown pattern anew gets the same solution to round-off.
  SystemMatrix fresh;
  set_up(fresh);
  fresh.build_pattern(n, grown.offsets, grown.dofs);
  assembled(fresh, grown, n);
  ASSERT_TRUE(fresh.factorize());
  EXPECT_LT((fresh.solve(b) - x).norm(), 1e-10 * x.norm());

  // The checkpoint carries the kept ordering: restored into a matrix of the grown pattern, the
  // factorisation solves bit for bit as the straight one, and so does the next factorisation
  // of new values (which analyses the pattern again, under the restored ordering).
  expect_restored_bitwise(k, set_up, grown, n, b);

  // Couplings across the whole plane fill the kept ordering's factor beyond kOrderingRefill:
  // a new ordering is found.
  std::vector<std::pair<int, int>> far;
  for (int i = 0; i < 400; ++i) far.emplace_back((i * 37) % (kSide * kSide), (i * 7919 + 5000) % (kSide * kSide));
  const Groups wide = with_pairs(grown, far);
  k.build_pattern(n, wide.offsets, wide.dofs);
  assembled(k, wide, n);
  ASSERT_TRUE(k.factorize());
  EXPECT_EQ(k.orderings(), 2u);
  const Eigen::VectorXd z = k.solve(b);
  EXPECT_LT((b - k.matrix().selfadjointView<Eigen::Upper>() * z).norm(), 1e-12 * b.norm());

  // A pattern that shed pairs (built anew from fewer groups) is ordered anew.
  k.build_pattern(n, grown.offsets, grown.dofs);
  assembled(k, grown, n);
  ASSERT_TRUE(k.factorize());
  EXPECT_EQ(k.orderings(), 3u);

  // A FACTOR section whose ordering is not a permutation of the unknowns is refused.
  std::string bytes = k.factor_source();
  const std::size_t at = bytes.size() - 2 * sizeof(double) - static_cast<std::size_t>(n) * sizeof(int);
  std::memcpy(&bytes[at], &bytes[at + sizeof(int)], sizeof(int));  // the first entry twice
  SystemMatrix bad;
  set_up(bad);
  bad.build_pattern(n, grown.offsets, grown.dofs);
  EXPECT_FALSE(bad.factor_from_source(bytes));
}

TEST(SystemMatrixSingle, ASinglePrecisionFactorHalvesItsBytesSolvesRefinedAndRestartsBitwise) {
  // 100 × 100 covers of 2 unknowns, METIS on the covers (as the large runs with contact), the
  // factor kept in single precision from 20,000 unknowns (the default, kSingleFactorUnknowns,
  // is larger: a test of its size would take long), against the same matrix in double.
  constexpr int kSide = 100;
  const Groups g = plane_grid(kSide, 2);
  const int n = 2 * kSide * kSide;
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.37 * i) + 0.1;
  const auto set_up = [&](SystemMatrix& k, bool single) {
    k.set_amd_only(true);
    k.set_block_ordering(2, n, n);
    if (single) {
      k.set_single_precision(n);
      k.set_lean_factorisation(n);  // the factor of the largest runs (restored: CHOLMOD's own path)
    }
    k.build_pattern(n, g.offsets, g.dofs);
  };
  SystemMatrix dbl, sgl;
  set_up(dbl, false);
  set_up(sgl, true);
  for (SystemMatrix* k : {&dbl, &sgl}) {
    assembled(*k, g, n);
    ASSERT_TRUE(k->factorize());
  }
  EXPECT_FALSE(dbl.single_precision());
  ASSERT_TRUE(sgl.single_precision());
  // The values take 4 bytes instead of 8; the row indices and per-column integers stay.
  EXPECT_LT(static_cast<double>(sgl.factor_bytes()), 0.6 * static_cast<double>(dbl.factor_bytes()));
  EXPECT_GT(static_cast<double>(sgl.factor_bytes()), 0.5 * static_cast<double>(dbl.factor_bytes()));
  const Eigen::VectorXd x = dbl.solve(b);
  // The preconditioner's solve is the rounded factor's: off the exact one by about u·κ (u = 6e-8),
  // not by double round-off, nor by a wrong factor's O(1).
  const Eigen::VectorXd z = sgl.solve_unrefined(b);
  const double off = (z - x).norm() / x.norm();
  EXPECT_GT(off, 1e-10);
  EXPECT_LT(off, 1e-5);
  // The passes' two kernel sets (AVX where the CPU has it, SSE2) give the same bits.
  const bool avx = SingleFactor::use_avx(true);
  SingleFactor::use_avx(false);
  const Eigen::VectorXd z_sse2 = sgl.solve_unrefined(b);
  SingleFactor::use_avx(avx);
  for (int i = 0; i < n; ++i) ASSERT_EQ(z_sse2[i], z[i]) << "unknown " << i << (avx ? "" : " (no AVX here)");
  // solve() refines against the factorised matrix in double: K x = b to round-off.
  const Eigen::VectorXd y = sgl.solve(b);
  EXPECT_LT((b - sgl.matrix().selfadjointView<Eigen::Upper>() * y).norm(), 1e-12 * b.norm());
  EXPECT_LT((y - x).norm(), 1e-11 * x.norm());
  EXPECT_GE(sgl.single_refinements(), 1u);
  // A checkpoint's factorisation restored: the same rounded factor, the same bits.
  SystemMatrix restored;
  set_up(restored, true);
  ASSERT_TRUE(restored.factor_from_source(sgl.factor_source()));
  ASSERT_TRUE(restored.single_precision());
  const Eigen::VectorXd zr = restored.solve_unrefined(b);
  for (int i = 0; i < n; ++i) ASSERT_EQ(zr[i], z[i]) << "unknown " << i;
  // A refactorisation after new values rounds the new factor (its structure reused).
  assembled(sgl, g, n);
  for (int i = 0; i < n; ++i) sgl.add_diagonal(i, 5.0);
  ASSERT_TRUE(sgl.factorize());
  ASSERT_TRUE(sgl.single_precision());
  const Eigen::VectorXd w = sgl.solve(b);
  EXPECT_LT((b - sgl.matrix().selfadjointView<Eigen::Upper>() * w).norm(), 1e-12 * b.norm());
}

namespace {
// A run whose factor is kept in single precision lets go of the matrix's arrays and the
// scatter's slots while CHOLMOD writes the double factor: parked in temporary files and read
// back, or, where no file can be written, made again from its permuted copy (system_matrix.cpp
// factorize_lean). Either way pattern, values and the assembly through the slots must be the
// ones before, bit for bit; a matrix that is not positive definite is reported at its unknown
// as on CHOLMOD's own path.
void expect_lean_factorisation_bitwise() {
  constexpr int kSide = 60;
  const Groups g = plane_grid(kSide, 2);
  const int n = 2 * kSide * kSide;
  SystemMatrix k;
  k.set_amd_only(true);
  k.set_block_ordering(2, n, n);
  k.set_single_precision(n);
  k.set_lean_factorisation(n);
  k.build_pattern(n, g.offsets, g.dofs);
  const SystemMatrix::Sparse before = assembled(k, g, n);
  // The saved values (the matrix without springs) differ from the factorised ones, as in a
  // contact step: they are parked in a file meanwhile and must come back unchanged.
  k.save();
  for (int i = 0; i < n; i += 7) k.add_diagonal(i, 0.1 * i);
  const SystemMatrix::Sparse with_springs = k.matrix();
  ASSERT_TRUE(k.factorize());
  ASSERT_TRUE(k.single_precision());
  expect_same(k.matrix(), with_springs);
  expect_same(k.saved_matrix(), before);
  k.restore();
  expect_same(k.matrix(), before);
  expect_same(assembled(k, g, n), before);  // through the slots placed again
  // The kept analysis, new values: the same again, and the solve refined to round-off.
  for (int i = 0; i < n; ++i) k.add_diagonal(i, 3.0);
  const SystemMatrix::Sparse shifted = k.matrix();
  ASSERT_TRUE(k.factorize());
  expect_same(k.matrix(), shifted);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::cos(0.21 * i);
  const Eigen::VectorXd x = k.solve(b);
  EXPECT_LT((b - k.matrix().selfadjointView<Eigen::Upper>() * x).norm(), 1e-12 * b.norm());
  // Not positive definite at unknown 777: reported there, the matrix given back unchanged.
  assembled(k, g, n);
  k.add_diagonal(777, -1e6);
  const SystemMatrix::Sparse broken = k.matrix();
  EXPECT_FALSE(k.factorize());
  EXPECT_EQ(k.failed_unknown(), 777);
  expect_same(k.matrix(), broken);
}
}  // namespace

TEST(SystemMatrixSingle, TheMatrixAndItsScatterComeBackBitwiseAfterALeanFactorisation) {
  expect_lean_factorisation_bitwise();  // parked in files
  // No folder for the files: made again from CHOLMOD's permuted copy.
  const char* old = std::getenv("TMPDIR");
  const std::string kept = old ? old : "";
  setenv("TMPDIR", "/nonexistent-nmm-folder", 1);
  {
    SCOPED_TRACE("no files: made again");
    expect_lean_factorisation_bitwise();
  }
  if (old) setenv("TMPDIR", kept.c_str(), 1); else unsetenv("TMPDIR");
}

TEST(SystemMatrixSingle, ALeanRunPlacesAGrownPatternsPairsInsteadOfOrderingAnew) {
  // The grown pattern of AKeptOrderingServesGrownPatterns… keeps its ordering as it is in a run
  // that is not lean; a lean one (the largest runs) keeps it with the new pairs' covers placed
  // (placed_ordering), its factor within kOrderingRefill of the first, and solves as before.
  const GrownGrid grid;
  const int n = grid.n;
  const Groups& g = grid.g;
  const Groups& grown = grid.grown;
  const Eigen::VectorXd& b = grid.b;
  for (const bool lean : {false, true}) {
    SCOPED_TRACE(lean ? "lean" : "not lean");
    SystemMatrix k;
    k.set_amd_only(true);
    k.set_block_ordering(2, n, n);
    k.set_single_precision(n);
    k.set_lean_factorisation(lean ? n : n + 1);
    k.build_pattern(n, g.offsets, g.dofs);
    assembled(k, g, n);
    ASSERT_TRUE(k.factorize());
    const double fill = k.factor_nonzeros();
    k.build_pattern(n, grown.offsets, grown.dofs);
    assembled(k, grown, n);
    ASSERT_TRUE(k.factorize());
    EXPECT_EQ(k.analyses(), 2u);
    EXPECT_EQ(k.orderings(), 1u);
    EXPECT_EQ(k.placed_analyses(), lean ? 1u : 0u);
    if (lean) {
      EXPECT_LE(k.factor_nonzeros(), nmm::solve::kOrderingRefill * fill);
    }
    const Eigen::VectorXd x = k.solve(b);
    EXPECT_LT((b - k.matrix().selfadjointView<Eigen::Upper>() * x).norm(), 1e-12 * b.norm());
  }
}

TEST(SystemMatrixSingle, ALeanFactorTakesValuesBelowFloatsNormalRangeAsZero) {
  // Two unknowns coupled by 1e-40, below float's smallest normal (1.18e-38): L = [1 0; 1e-40 1].
  // Rounded as it is, L̃'s off-diagonal value is a subnormal float and the solve of b = (1, 0)
  // gives z₁ ≈ −1e-40; a lean run's factor holds 0 there (single_factor.h), so z₁ = 0, and
  // leaves the control register (flush-to-zero for its numeric factorisation) as it found it.
  constexpr int n = 2;
  const Groups g = Groups{}.add({0, 1});
  const double block[4] = {1.0, 1e-40, 1e-40, 1.0};
  const auto set_up = [&](SystemMatrix& k, bool lean) {
    k.set_amd_only(true);
    k.set_single_precision(n);
    k.set_lean_factorisation(lean ? n : n + 1);
    k.build_pattern(n, g.offsets, g.dofs);
    k.set_zero();
    k.add_group(0, block);
  };
  SystemMatrix lean, kept;
  set_up(lean, true);
  set_up(kept, false);
#if defined(__x86_64__) || defined(__SSE2__)
  const unsigned csr = _mm_getcsr();
#endif
  for (SystemMatrix* k : {&lean, &kept}) {
    ASSERT_TRUE(k->factorize());
    ASSERT_TRUE(k->single_precision());
  }
#if defined(__x86_64__) || defined(__SSE2__)
  // The control bits (rounding, masks, FTZ, DAZ) as found; the low six bits are sticky exception
  // flags, which the kept factor's own underflow of 1e-40 sets (UE) whatever the guard does.
  constexpr unsigned kControl = ~0x3Fu;
  EXPECT_EQ(_mm_getcsr() & kControl, csr & kControl);
#endif
  const Eigen::VectorXd b = Eigen::Vector2d(1.0, 0.0);
  const Eigen::VectorXd zk = kept.solve_unrefined(b), zl = lean.solve_unrefined(b);
  EXPECT_EQ(zk[0], 1.0);
  EXPECT_LT(zk[1], -0.9e-40);
  EXPECT_GT(zk[1], -1.1e-40);
  EXPECT_EQ(zl[0], 1.0);
  EXPECT_EQ(zl[1], 0.0);
}

TEST(SystemMatrixSingle, TheSpareHalfStaysForTheSamePatternAndGoesWithANewOne) {
  // Below the lean size the pages of the rounded factor's second half stay resident for the
  // next factorisation of the same pattern (system_matrix.cpp keep_single) and go back when the
  // pattern changes; a lean run gives them back at once. The factor written over the kept pages
  // (which hold the old values' bytes) must be the one a fresh array gets: the same bits.
  const GrownGrid grid;
  const int n = grid.n;
  const auto set_up = [&](SystemMatrix& k, bool lean) {
    k.set_amd_only(true);
    k.set_block_ordering(2, n, n);
    k.set_single_precision(n);
    k.set_lean_factorisation(lean ? n : n + 1);
    k.build_pattern(n, grid.g.offsets, grid.g.dofs);
  };
  SystemMatrix lean, kept;
  set_up(lean, true);
  set_up(kept, false);
  for (SystemMatrix* k : {&lean, &kept}) {
    assembled(*k, grid.g, n);
    ASSERT_TRUE(k->factorize());
    ASSERT_TRUE(k->single_precision());
  }
  EXPECT_EQ(lean.factor_spare_bytes(), 0u);
  // About half the double values' bytes (whole pages only).
  EXPECT_GT(static_cast<double>(kept.factor_spare_bytes()), 0.3 * static_cast<double>(kept.factor_bytes()));
  // New values, the same pattern: refactorised over the kept pages, against a fresh matrix.
  SystemMatrix fresh;
  set_up(fresh, false);
  for (SystemMatrix* k : {&kept, &fresh}) {
    assembled(*k, grid.g, n);
    for (int i = 0; i < n; i += 5) k->add_diagonal(i, 2.0);
    ASSERT_TRUE(k->factorize());
  }
  EXPECT_EQ(kept.analyses(), 1u);
  EXPECT_GT(kept.factor_spare_bytes(), 0u);
  const Eigen::VectorXd z = kept.solve_unrefined(grid.b), zf = fresh.solve_unrefined(grid.b);
  for (int i = 0; i < n; ++i) ASSERT_EQ(z[i], zf[i]) << "unknown " << i;
  // A grown pattern: the spare pages go back before its arrays are made.
  kept.build_pattern(n, grid.grown.offsets, grid.grown.dofs);
  EXPECT_EQ(kept.factor_spare_bytes(), 0u);
  assembled(kept, grid.grown, n);
  ASSERT_TRUE(kept.factorize());
  EXPECT_EQ(kept.analyses(), 2u);
  EXPECT_GT(kept.factor_spare_bytes(), 0u);
  const Eigen::VectorXd x = kept.solve(grid.b);
  EXPECT_LT((grid.b - kept.matrix().selfadjointView<Eigen::Upper>() * x).norm(), 1e-12 * grid.b.norm());
}

TEST(SystemMatrixOrdering, APatternGrownWithinItsFactorKeepsItsOrderingAndRestartsBitwise) {
  // 100 × 100 covers, METIS on the covers from 20,000 unknowns. Two covers u, w that are both
  // coupled to a cover k and eliminated after it are coupled in the factor (the fill of k's
  // elimination): pairs of such covers, not coupled in the matrix, grow the pattern within the
  // factor. A lean run then analyses it under the kept ordering instead of ordering it anew, as a
  // run that is not lean does anyway, its factor no larger; a checkpoint restored from it solves
  // bit for bit as the straight run, now and after the next factorisation of new values. A
  // pair outside the factor is ordered anew in a lean run.
  constexpr int kSide = 100;
  const Groups g = plane_grid(kSide, 2);
  const int n = 2 * kSide * kSide;
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::cos(0.21 * i) - 0.2;
  for (const bool lean : {false, true}) {
    SCOPED_TRACE(lean ? "lean" : "not lean");
    const auto set_up = [&](SystemMatrix& k) {
      k.set_amd_only(true);
      k.set_block_ordering(2, n, n);
      k.set_single_precision(n);
      k.set_lean_factorisation(lean ? n : n + 1);
    };
    SystemMatrix k;
    set_up(k);
    k.build_pattern(n, g.offsets, g.dofs);
    const SystemMatrix::Sparse a = assembled(k, g, n);
    ASSERT_TRUE(k.factorize());
    ASSERT_EQ(k.orderings(), 1u);
    // The ordering, from the checkpoint's bytes (after it: its fill and the pattern's nonzeros).
    const std::string bytes = k.factor_source();
    std::vector<int> perm(static_cast<std::size_t>(n));
    std::memcpy(perm.data(), bytes.data() + bytes.size() - 2 * sizeof(double) - perm.size() * sizeof(int),
                perm.size() * sizeof(int));
    std::vector<int> at(static_cast<std::size_t>(n));
    for (int p = 0; p < n; ++p) at[static_cast<std::size_t>(perm[static_cast<std::size_t>(p)])] = p;
    const auto coupled = [&](int u, int w) {  // covers u, w share an entry of the matrix
      const int c = 2 * std::max(u, w), r = 2 * std::min(u, w);
      const int* first = a.innerIndexPtr() + a.outerIndexPtr()[c];
      const int* last = a.innerIndexPtr() + a.outerIndexPtr()[c + 1];
      return std::binary_search(first, last, r);
    };
    std::vector<std::pair<int, int>> within;
    for (int cover = 0; cover < kSide * kSide && within.size() < 40; cover += 97) {
      std::vector<int> later;  // covers coupled to `cover`, eliminated after it
      for (int other = std::max(0, cover - 2 * kSide); other < std::min(kSide * kSide, cover + 2 * kSide + 1); ++other)
        if (other != cover && coupled(cover, other) && at[static_cast<std::size_t>(2 * other)] > at[static_cast<std::size_t>(2 * cover)])
          later.push_back(other);
      for (std::size_t i = 0; i < later.size(); ++i)
        for (std::size_t j = i + 1; j < later.size(); ++j)
          if (!coupled(later[i], later[j])) within.emplace_back(later[i], later[j]);
    }
    ASSERT_GE(within.size(), 10u);
    const Groups grown = with_pairs(g, within);
    const double fill = k.factor_nonzeros();
    k.build_pattern(n, grown.offsets, grown.dofs);
    assembled(k, grown, n);
    ASSERT_GT(k.nonzeros(), static_cast<std::size_t>(a.nonZeros()));  // a new pattern
    ASSERT_TRUE(k.factorize());
    EXPECT_EQ(k.analyses(), 2u);
    EXPECT_EQ(k.kept_analyses(), lean ? 1u : 0u);  // (a run that is not lean does not ask)
    EXPECT_EQ(k.orderings(), 1u);
    EXPECT_EQ(k.factor_nonzeros(), fill);  // within the factor: no new fill
    const Eigen::VectorXd x = k.solve(b);
    EXPECT_LT((b - k.matrix().selfadjointView<Eigen::Upper>() * x).norm(), 1e-12 * b.norm());
    // Restored: analysed under the checkpoint's ordering, the same factor, the same bits.
    expect_restored_bitwise(k, set_up, grown, n, b);
    // Pairs across the plane lie outside the factor and fill the kept order as it is beyond
    // kOrderingRefill: a run that is not lean orders anew; a lean one places their covers in
    // the kept order (ALeanRunPlacesTheCoversOfNewPairs…).
    std::vector<std::pair<int, int>> far;
    for (int i = 0; i < 50; ++i) far.emplace_back((i * 37) % (kSide * kSide), (i * 7919 + 5000) % (kSide * kSide));
    const Groups wide = with_pairs(grown, far);
    k.build_pattern(n, wide.offsets, wide.dofs);
    assembled(k, wide, n);
    ASSERT_TRUE(k.factorize());
    EXPECT_EQ(k.analyses(), 3u);
    EXPECT_EQ(k.kept_analyses(), lean ? 1u : 0u);
    EXPECT_EQ(k.orderings(), lean ? 1u : 2u);
    EXPECT_EQ(k.placed_analyses(), lean ? 1u : 0u);
    EXPECT_GT(k.factor_nonzeros(), fill);
    const Eigen::VectorXd z = k.solve(b);
    EXPECT_LT((b - k.matrix().selfadjointView<Eigen::Upper>() * z).norm(), 1e-12 * b.norm());
  }
}

TEST(SystemMatrixOrdering, ALeanRunPlacesTheCoversOfNewPairsInItsOrderAndRestartsBitwise) {
  // 100 × 100 covers under METIS's nested dissection; a few pairs of covers across the plane
  // (new contacts far apart in the order's tree) grow the pattern outside the factor. Under the
  // kept order as it is, each pair joins two paths of the elimination tree below the top
  // separators; with the covers placed (placed_ordering) before the separator between them, a
  // lean run keeps its order, no METIS, with a factor within kOrderingRefill of the nested
  // dissection's and smaller than the kept order's as is; a restored checkpoint solves bit for
  // bit. Many such pairs are ordered anew.
  constexpr int kSide = 100;
  const Groups g = plane_grid(kSide, 2);
  const int n = 2 * kSide * kSide;
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.13 * i) + 0.1;
  const auto set_up = [&](SystemMatrix& k) {
    k.set_amd_only(true);
    k.set_block_ordering(2, n, n);
    k.set_single_precision(n);
    k.set_lean_factorisation(n);
  };
  SystemMatrix k;
  set_up(k);
  k.build_pattern(n, g.offsets, g.dofs);
  assembled(k, g, n);
  ASSERT_TRUE(k.factorize());
  ASSERT_EQ(k.orderings(), 1u);
  const double fill = k.factor_nonzeros();
  const std::string bytes = k.factor_source();
  std::vector<int> perm(static_cast<std::size_t>(n));
  std::memcpy(perm.data(), bytes.data() + bytes.size() - 2 * sizeof(double) - perm.size() * sizeof(int),
              perm.size() * sizeof(int));
  std::vector<std::pair<int, int>> far;
  for (int i = 0; i < 6; ++i) far.emplace_back((i * 1237 + 150) % (kSide * kSide), (i * 3571 + 5050) % (kSide * kSide));
  const Groups grown = with_pairs(g, far);
  k.build_pattern(n, grown.offsets, grown.dofs);
  const SystemMatrix::Sparse a = assembled(k, grown, n);
  // The kept order as it is, on the grown pattern.
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_GIVEN;
  c.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse view = Eigen::viewAsCholmod(a.selfadjointView<Eigen::Upper>());
  cholmod_factor* as_is = cholmod_analyze_p(&view, perm.data(), nullptr, 0, &c);
  ASSERT_NE(as_is, nullptr);
  const double kept_fill = c.lnz;
  cholmod_free_factor(&as_is, &c);
  cholmod_finish(&c);
  ASSERT_GT(kept_fill, 1.01 * fill);  // the pairs do fill under the kept order
  ASSERT_TRUE(k.factorize());
  EXPECT_EQ(k.analyses(), 2u);
  EXPECT_EQ(k.kept_analyses(), 0u);
  EXPECT_EQ(k.placed_analyses(), 1u);
  EXPECT_EQ(k.orderings(), 1u);
  EXPECT_LE(k.factor_nonzeros(), nmm::solve::kOrderingRefill * fill);
  EXPECT_LT(k.factor_nonzeros() - fill, 0.5 * (kept_fill - fill));
  const Eigen::VectorXd x = k.solve(b);
  EXPECT_LT((b - k.matrix().selfadjointView<Eigen::Upper>() * x).norm(), 1e-12 * b.norm());
  expect_restored_bitwise(k, set_up, grown, n, b);
  // Pairs by the thousand: ordered anew.
  std::vector<std::pair<int, int>> many;
  for (int i = 0; i < 1500; ++i) many.emplace_back((i * 37) % (kSide * kSide), (i * 7919 + 5000) % (kSide * kSide));
  const Groups wide = with_pairs(grown, many);
  k.build_pattern(n, wide.offsets, wide.dofs);
  assembled(k, wide, n);
  ASSERT_TRUE(k.factorize());
  EXPECT_EQ(k.placed_analyses(), 1u);
  EXPECT_EQ(k.orderings(), 2u);
}

TEST(ParkedArray, GivesBackTheSameBytesAndStaysInMemoryWhereNoFileCanBeMade) {
  std::vector<double> v(100003);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::sin(0.37 * static_cast<double>(i)) * 1e-300 + static_cast<double>(i);
  const std::vector<double> copy = v;
  ParkedArray<double> parked;
  ASSERT_TRUE(parked.park(v));
  EXPECT_TRUE(parked.parked());
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(v.capacity(), 0u);  // the memory itself let go
  parked.unpark(v);
  EXPECT_FALSE(parked.parked());
  ASSERT_EQ(v.size(), copy.size());
  EXPECT_EQ(std::memcmp(v.data(), copy.data(), v.size() * sizeof(double)), 0);
  // No folder for the file: the array stays where it was, and unpark() leaves it alone.
  const char* old = std::getenv("TMPDIR");
  const std::string kept = old ? old : "";
  setenv("TMPDIR", "/nonexistent-nmm-folder", 1);
  ParkedArray<double> nowhere;
  EXPECT_FALSE(nowhere.park(v));
  if (old) setenv("TMPDIR", kept.c_str(), 1); else unsetenv("TMPDIR");
  EXPECT_FALSE(nowhere.parked());
  nowhere.unpark(v);
  ASSERT_EQ(v.size(), copy.size());
  EXPECT_EQ(std::memcmp(v.data(), copy.data(), v.size() * sizeof(double)), 0);
  std::vector<int> empty;
  ParkedArray<int> none;
  EXPECT_FALSE(none.park(empty));  // nothing to gain
  EXPECT_FALSE(none.parked());
}

namespace {
// k's factorisation (its matrix gathered into the factor's order, permuted_lower.h) against
// CHOLMOD's own of the same matrix (cholmod_factorize_p, which permutes it itself), analysed
// with the same settings: the same solve, bit for bit.
// CHOLMOD's own factorisation of the matrix, its factor readable (solved by our passes below).
struct CholmodsOwn : Eigen::CholmodSupernodalLLT<SystemMatrix::Sparse, Eigen::Upper> {
  const cholmod_factor* factor() const { return this->m_cholmodFactor; }
};

// A plane grid of side × side covers of 2 unknowns under AMD, or a cube grid under CHOLMOD's
// default (METIS kept), its pattern built in k and its values assembled; returns the groups.
Groups grid_in(SystemMatrix& k, bool cube, int side, int& n) {
  Groups g = cube ? cube_grid(side) : plane_grid(side, 2);
  n = cube ? side * side * side : 2 * side * side;
  k.set_amd_only(!cube);
  k.build_pattern(n, g.offsets, g.dofs);
  assembled(k, g, n);
  return g;
}

void expect_cholmods_own(SystemMatrix& k, bool amd_only, int n) {
  CholmodsOwn own;
  own.cholmod().print = 0;
  if (amd_only) {
    own.cholmod().nmethods = 1;
    own.cholmod().method[0].ordering = CHOLMOD_AMD;
  }
  own.compute(k.matrix());
  ASSERT_EQ(own.info(), Eigen::Success);
  ASSERT_TRUE(k.factorize());
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.37 * i) + 0.5;
  // The same factor bits give the same bits through the same passes (k's solve is ours, set
  // on: DoubleFactor over its factor).
  ASSERT_TRUE(k.own_solve());
  nmm::solve::DoubleFactor passes;
  ASSERT_TRUE(passes.view(own.factor()));
  Eigen::VectorXd y;
  passes.solve(b, y);
  const Eigen::VectorXd x = k.solve(b);
  for (int i = 0; i < n; ++i) ASSERT_EQ(x[i], y[i]) << "unknown " << i;
  EXPECT_LT((x - own.solve(b)).norm(), 1e-13 * x.norm());  // and CHOLMOD's own solve to round-off
  EXPECT_LT((b - k.matrix().selfadjointView<Eigen::Upper>() * x).norm(), 1e-10 * b.norm());
}
}  // namespace

TEST(SystemMatrixPermuted, TheMatrixGatheredInItsFactorsOrderFactorisesAsCholmodsOwnBitwise) {
  // AMD on a plane grid, then CHOLMOD's default strategy on a cube grid (METIS kept there):
  // each factorised as cholmod_factorize_p would (the same bits), with the layout made at the
  // analysis, kept for new values, and laid out again for a grown pattern's new analysis.
  for (const bool cube : {false, true}) {
    SystemMatrix k;
    k.set_own_solve();  // the factor's bits read through DoubleFactor's passes (expect_cholmods_own)
    int n = 0;
    const Groups g = grid_in(k, cube, cube ? 20 : 40, n);
    expect_cholmods_own(k, !cube, n);
    EXPECT_EQ(k.ordering(), cube ? "metis" : "amd");
    // New values, the same analysis: the layout is reused.
    for (int i = 0; i < n; i += 5) k.add_diagonal(i, 0.3 * i);
    expect_cholmods_own(k, !cube, n);
    EXPECT_EQ(k.analyses(), 1u);
    // A grown pattern (the first unknown coupled with the last two): a new analysis, a new layout.
    Groups grown = g;
    grown.add({0, n - 2, n - 1});
    k.build_pattern(n, grown.offsets, grown.dofs);
    assembled(k, grown, n);
    expect_cholmods_own(k, !cube, n);
    EXPECT_EQ(k.analyses(), 2u);
    // Not positive definite at one unknown: reported there, as on CHOLMOD's own path.
    assembled(k, grown, n);
    k.add_diagonal(n / 3, -1e6);
    EXPECT_FALSE(k.factorize());
    EXPECT_EQ(k.failed_unknown(), n / 3);
  }
}

namespace {
// CHOLMOD's own factorisation of `a` (CHOLMOD's default ordering), its factor readable.
struct ExposedLlt : CholmodsOwn {
  explicit ExposedLlt(const SystemMatrix::Sparse& a) { this->compute(a); }
};

double relative_residual(const SystemMatrix::Sparse& upper, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (b - upper.selfadjointView<Eigen::Upper>() * x).norm() / b.norm();
}

// Our passes over CHOLMOD's double factor against cholmod_solve on the same factor: the same
// solution to round-off (the sums run in another order), both kernel sets the same bits, and a
// residual no larger than CHOLMOD's own but for a few units of round-off. Prints what it measured.
void expect_own_solve_as_cholmods(const SystemMatrix::Sparse& upper, const Eigen::VectorXd& b, double tol,
                                  const char* what) {
  const ExposedLlt llt(upper);
  ASSERT_EQ(llt.info(), Eigen::Success) << what;
  const cholmod_factor* l = llt.factor();
  ASSERT_TRUE(l->is_super) << what;
  nmm::solve::DoubleFactor own;
  ASSERT_TRUE(own.view(l)) << what;
  const Eigen::VectorXd ref = llt.solve(b);
  Eigen::VectorXd x;
  own.solve(b, x);
  const double off = (x - ref).norm() / ref.norm();
  const double r_own = relative_residual(upper, x, b), r_ref = relative_residual(upper, ref, b);
  int widest = 0;
  for (std::size_t s = 0; s < l->nsuper; ++s)
    widest = std::max(widest, static_cast<const int*>(l->super)[s + 1] - static_cast<const int*>(l->super)[s]);
  std::printf("%s: n %d, %d supernodes (widest %d columns): |x - x_cholmod| / |x| %.2e, residual %.2e (CHOLMOD's %.2e)\n",
              what, static_cast<int>(l->n), static_cast<int>(l->nsuper), widest, off, r_own, r_ref);
  EXPECT_GT(l->nsuper, 10u) << what;
  EXPECT_GE(widest, 8) << what << ": the four-column kernels and the columns left over both run";
  EXPECT_LT(off, tol) << what;
  EXPECT_LT(r_own, 4 * r_ref + 1e-15) << what;
  // AVX and SSE2 give the same bits over double values too.
  const bool avx = SingleFactor::use_avx(true);
  SingleFactor::use_avx(false);
  Eigen::VectorXd x_sse2;
  own.solve(b, x_sse2);
  SingleFactor::use_avx(avx);
  for (Eigen::Index i = 0; i < x.size(); ++i) ASSERT_EQ(x_sse2[i], x[i]) << what << ", unknown " << i;
}
}  // namespace

TEST(SystemMatrixOwnSolve, PassesOverCholmodsDoubleFactorSolveAsCholmodOnGridsOfManySupernodes) {
  // A plane grid under AMD (many small supernodes) and a cube grid under METIS (wide ones).
  for (const bool cube : {false, true}) {
    SystemMatrix k;
    EXPECT_FALSE(k.own_solve());
    k.set_own_solve();
    int n = 0;
    grid_in(k, cube, cube ? 14 : 60, n);
    ASSERT_TRUE(k.factorize());
    ASSERT_TRUE(k.own_solve()) << "set on, below kOwnSolveUnknowns a double factor is solved by our passes";
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = std::sin(0.37 * i) + 0.1;
    expect_own_solve_as_cholmods(k.matrix(), b, 1e-13, cube ? "cube grid" : "plane grid");
    // SystemMatrix's solve is ours: against an independent CHOLMOD factorisation of its matrix.
    const Eigen::VectorXd x = k.solve(b);
    const ExposedLlt ref(k.matrix());
    EXPECT_LT((x - ref.solve(b)).norm(), 1e-13 * x.norm());
    // A new factorisation of other values is read anew (not the last factor's inverse diagonal).
    for (int i = 0; i < n; ++i) k.add_diagonal(i, 50.0);
    ASSERT_TRUE(k.factorize());
    ASSERT_TRUE(k.own_solve());
    const Eigen::VectorXd y = k.solve(b);
    const ExposedLlt ref2(k.matrix());
    EXPECT_LT((y - ref2.solve(b)).norm(), 1e-13 * y.norm());
    EXPECT_GT((y - x).norm(), 1e-3 * x.norm());
  }
}

TEST(SystemMatrixOwnSolve, PassesOverAWallsFactorSolveAsCholmod) {
  // The DDA code's 10 × 10 brick wall at h = 2 m, its static step matrix after 20 steps (the
  // elements, the contact springs, the static support): the matrix of its last factorisation.
  for (const bool dynamic : {false, true}) {
    const nmm::SceneDef scene = nmm::reference::peer_wall(10, 10, dynamic, 2.0);
    const nmm::Mesh mesh = nmm::pre::build_mesh(scene, "wall");
    ::setenv("NMM_OWN_SOLVE", "1", 1);  // the stepper's SystemMatrix reads it when made
    nmm::solve::TimeStepper st(mesh, scene, "wall");
    ::unsetenv("NMM_OWN_SOLVE");
    st.set_threads(1);
    for (int s = 0; s < 20; ++s) st.step(1e-3);
    const SystemMatrix& sys = st.view().system;
    ASSERT_TRUE(sys.has_factor());
    ASSERT_TRUE(sys.own_solve());
    const SystemMatrix::Sparse& a = sys.factored_matrix();
    const int n = static_cast<int>(a.rows());
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = 1e3 * std::cos(0.11 * i);
    expect_own_solve_as_cholmods(a, b, 1e-13, dynamic ? "dynamic 10 x 10 wall" : "static 10 x 10 wall");
  }
}
