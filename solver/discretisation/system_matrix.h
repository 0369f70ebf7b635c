// The global system matrix: symmetric, stored as its upper triangle in compressed columns, with
// a sparsity pattern built once from the element–cover incidence, and CHOLMOD's factorisation.
//
// Pattern and numbers are kept apart (deal.II step-8 style): build_pattern() fixes the nonzeros
// and precomputes, for every group, where each entry of its block lands in the value
// array, so assembly is a scatter with no search. CHOLMOD's symbolic analysis (fill-reducing
// ordering, supernodes) runs only when the pattern changes; each step refactors the numbers.
//
// The upper triangle, not the lower: CHOLMOD's supernodal factorisation first copies the matrix
// into its fill-reducing order, which takes one transpose of an upper triangle and two of a
// lower one (cholmod_factorize_p). The copy is the same matrix either way, and so is the factor.
// Below kSingleFactorUnknowns that copy's layout is kept from one factorisation to the next
// (permuted_lower.h): each factorisation gathers the values into it and hands it to CHOLMOD's
// numeric factorisation itself.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

#include "solver/discretisation/permuted_lower.h"
#include "solver/discretisation/single_factor.h"

namespace nmm::solve {

/// Unknowns from which set_block_ordering() orders by METIS on the covers (system_matrix.cpp).
inline constexpr int kBlockOrderingUnknowns = 150000;
/// A kept ordering serves a grown pattern while its factor has at most this many times the
/// nonzeros it had when the ordering was found (system_matrix.cpp).
inline constexpr double kOrderingRefill = 1.10;
/// A lean run's grown pattern keeps its order with the new pairs placed (fill_ordering.h
/// placed_ordering) while its factor stays within kOrderingRefill of the nested dissection's
/// nonzeros (a restart analyses under the kept order as long as that holds) and within 1.25 ×
/// the last analysis's flops, and while fewer than one entry in kOutsideShare unknowns lies
/// outside the last factor (system_matrix.cpp analyse_kept).
inline constexpr int kOutsideShare = 16;
/// Unknowns from which set_single_precision() keeps the factor in single precision (system_matrix.cpp).
inline constexpr int kSingleFactorUnknowns = 150000;
/// Below this many unknowns a double factor can be solved by our own passes over CHOLMOD's
/// supernodes (single_factor.h DoubleFactor) instead of cholmod_solve (system_matrix.cpp: where it
/// pays). Off unless the environment sets NMM_OWN_SOLVE=1 (own_solve_from_environment()): the new
/// order of the sums moves every state hash, and data/dfn_slope.json's figures on Prescott's
/// kernels by 7.7e-7 m (0.1–0.4 %, a contact path that parts), not yet traced (docs/performance.md (e)).
inline constexpr int kOwnSolveUnknowns = 150000;
/// kOwnSolveUnknowns where the environment sets NMM_OWN_SOLVE=1, else 0 (off).
int own_solve_from_environment();
/// Unknowns from which a single-precision run factorises lean (set_lean_factorisation(),
/// system_matrix.cpp factorize_lean: where it pays).
inline constexpr int kLeanFactorUnknowns = 500000;

class SystemMatrix {
 public:
  using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /// Builds the pattern of the n×n matrix (n = unknowns) coupling, for each group, all the
  /// unknowns in it: one group per element (its CoverSpace::element_dofs() unknowns), one per
  /// pair of elements in contact (both elements' unknowns; an unknown may appear twice in a group).
  /// Group g holds dofs[offsets[g] .. offsets[g+1]).
  /// A pattern that only grew by groups whose entries it already holds (new pairs of elements
  /// whose covers were already coupled: neighbours along a joint share covers) keeps its
  /// nonzeros and the old groups' positions, and only the new groups are placed.
  void build_pattern(int n, const std::vector<int>& offsets, const std::vector<int>& dofs);

  /// Unknowns whose diagonal is perturbed by eps·K_ii in the factorisation (linearly dependent
  /// ones); solve() then refines iteratively. Empty (the default): plain Cholesky.
  void set_regularised(std::vector<int> unknowns, double eps) {
    regularised_ = std::move(unknowns);
    eps_ = eps;
  }
  /// Fill-reducing ordering by AMD alone (true), or CHOLMOD's default (false: AMD, and METIS as
  /// well where AMD's fill is high, keeping the sparser factor). A run whose pattern changes with
  /// its contacts analyses it again every few steps, and there a METIS ordering costs more to
  /// find than its factorisations save (system_matrix.cpp).
  void set_amd_only(bool on);
  /// Orders by METIS's nested dissection on the graph of the covers (fill_ordering.h) instead,
  /// once the system has at least `from` unknowns: the first `blocked` unknowns form covers of
  /// `block` consecutive unknowns (cover_space.h), the others stand alone. `block` 0: off (the
  /// default). For runs with contact (system_matrix.cpp: where it pays). The ordering found is
  /// kept for the patterns grown from that one while their factor stays within kOrderingRefill
  /// of the fill it had when found (system_matrix.cpp); a checkpoint carries it (factor_source()).
  void set_block_ordering(int block, int blocked, int from = kBlockOrderingUnknowns) {
    block_ = block;
    blocked_ = blocked;
    block_from_ = from;
  }
  /// Keeps the factor in single precision once the system has at least `from` unknowns (0: never,
  /// the default): its solves read half the bytes; solve() refines against the factorised matrix
  /// in double (single_factor.h, system_matrix.cpp: where it pays).
  void set_single_precision(int from = kSingleFactorUnknowns) { single_from_ = from; }
  /// With a single-precision factor, from `from` unknowns on: the matrix's arrays and the
  /// scatter's slots are let go while CHOLMOD writes the double factor (the run's memory peak)
  /// and made again after, the same bits (system_matrix.cpp factorize_lean).
  void set_lean_factorisation(int from = kLeanFactorUnknowns) { lean_from_ = from; }
  /// The factor is held in single precision.
  bool single_precision() const { return single_.ready(); }
  /// Below `below` unknowns a double factor is solved by our own passes (0: by cholmod_solve;
  /// the default is own_solve_from_environment()).
  void set_own_solve(int below = kOwnSolveUnknowns) { own_from_ = below; }
  /// The double factor is solved by our own passes (DoubleFactor).
  bool own_solve() const { return own_.ready(); }
  /// The matrix the current factorisation was made from (its perturbation included).
  const Sparse& factored_matrix() const { return factored_; }
  /// Refinement passes of solves with a single-precision factor so far.
  std::size_t single_refinements() const { return single_refinements_; }
  /// Iterative-refinement passes of the last solve (0 without regularisation).
  int refinements() const { return refinements_; }

  /// Sets every value to zero, keeping the pattern.
  void set_zero();

  /// Adds the symmetric m×m block `k` (column-major, m = size of group g) of group g.
  void add_group(std::size_t g, const double* k);

  /// Saves the current values; restore() brings them back (the part of the matrix that does not
  /// change during the open–close iteration of a step).
  void save();
  void restore() { std::copy(saved_.begin(), saved_.end(), k_.valuePtr()); }
  /// The matrix with the saved values (pattern and values; a bench reads it).
  Sparse saved_matrix() const {
    Sparse a = k_;
    std::copy(saved_.begin(), saved_.end(), a.valuePtr());
    return a;
  }

  /// Adds `value` to the diagonal entry of unknown i.
  void add_diagonal(int i, double value);

  /// Factorises the current values (symbolic analysis only after a new pattern). Returns false if
  /// the matrix is not positive definite; failed_unknown() then names the unknown where it broke.
  bool factorize();

  /// Solves K·x = b with the last factorisation (of whatever values it was made from: also
  /// after the values or the pattern changed; refined against the current values when
  /// regularised, cover_space.h). A preconditioner uses solve_unrefined() instead.
  Eigen::VectorXd solve(const Eigen::VectorXd& b);
  /// Solves with the last factorisation only, no iterative refinement: a preconditioner's solve.
  Eigen::VectorXd solve_unrefined(const Eigen::VectorXd& b) const;
  /// The same into x, reusing its storage (a single-precision factor's solve allocates nothing:
  /// the CG runs call it once per iteration).
  void solve_unrefined(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// Removes from x its component in the null space of the factorised matrix P (the
  /// zero-field combinations of the cover coefficients, docs/higher-order-covers.md "Keeping
  /// the null space out"): x ← x − (P + E)⁻¹ E x with E the diagonal perturbation of the factor.
  /// In the generalised eigenvectors of P v = μ E v this multiplies each component by
  /// μ/(μ + 1): null vectors (μ = 0) go, kept ones change by at most 1/(1 + μ_min) ≈ ε/λ_min.
  /// A no-op without regularisation (n = 0).
  void remove_null_part(Eigen::VectorXd& x) const;
  /// A successful factorisation of this size exists.
  bool has_factor() const { return has_factor_; }
  /// Forgets the factorisation (the next solve must factorise first).
  void drop_factor() { has_factor_ = false; }
  /// The matrix the current factorisation was made from (pattern and values) as bytes, empty
  /// without one: a checkpoint keeps it so that a restarted run preconditions with the same
  /// factorisation as the straight run (bitwise equal results).
  std::string factor_source() const;
  /// Factorises the matrix of factor_source() bytes (from a checkpoint); false if the bytes do not
  /// describe a positive definite matrix of this size.
  bool factor_from_source(const std::string& bytes);

  /// y = A·v with the saved values A (save()), the part that does not change within a step.
  void saved_times(const Eigen::VectorXd& v, Eigen::VectorXd& y) const;

  /// Of the last symbolic analysis: nonzeros of the factor and flops of one factorisation.
  double factor_nonzeros() const { return factor_nonzeros_; }
  double factor_flops() const { return factor_flops_; }
  /// Nonzeros of the stored upper triangle of the matrix.
  std::size_t nonzeros() const { return static_cast<std::size_t>(k_.nonZeros()); }
  /// CHOLMOD's fill-reducing ordering of the last analysis ("amd", "metis", "nesdis", ...).
  std::string ordering() const { return ordering_; }
  /// METIS orderings on the covers found so far (the analyses that reused one are not counted).
  std::size_t orderings() const { return orderings_; }
  /// New patterns a lean run analysed under its kept ordering, not ordered anew, so far: every
  /// entry of theirs lay within the last analysis's factor (system_matrix.cpp keeps_symbolic).
  std::size_t kept_analyses() const { return kept_analyses_; }
  /// New patterns a lean run analysed under its last order with the new pairs' covers placed
  /// (fill_ordering.h placed_ordering), not ordered anew by METIS, so far.
  std::size_t placed_analyses() const { return placed_analyses_; }

  int failed_unknown() const { return failed_unknown_; }
  int size() const { return static_cast<int>(k_.rows()); }
  const Sparse& matrix() const { return k_; }
  std::size_t analyses() const { return analyses_; }  ///< symbolic analyses done so far
  std::size_t builds() const { return builds_; }  ///< patterns built from scratch so far (not grown in place)
  /// Bytes of CHOLMOD's factor (values, supernodes' row indices, permutation), 0 without one.
  std::size_t factor_bytes() const { return single_.ready() ? single_.bytes() : llt_.bytes(); }
  /// Bytes of a single-precision factor's spare half kept resident (keep_single: below the lean
  /// factorisation's size, until the pattern changes), else 0.
  std::size_t factor_spare_bytes() const { return single_.spare_bytes(); }
  /// Bytes of the matrix's copies: the pattern and values, the saved values, the factorised one.
  std::size_t matrix_bytes() const {
    const auto bytes = [](const Sparse& a) {
      return static_cast<std::size_t>(a.nonZeros()) * (sizeof(double) + sizeof(int)) +
             static_cast<std::size_t>(a.outerSize() + 1) * sizeof(int);
    };
    return bytes(k_) + saved_.capacity() * sizeof(double) + bytes(factored_) + permuted_.bytes();
  }
  /// Bytes CHOLMOD holds now (the factor, its symbolic parts, workspace), and the most it held
  /// since the last factorize() began (its working copies included): a bench reads them.
  std::size_t cholmod_bytes() const { return common().memory_inuse; }
  std::size_t cholmod_peak_bytes() const { return common().memory_usage; }
  /// Bytes held for the pattern's scatter (the groups' slots and unknowns): a bench reads it.
  std::size_t scatter_bytes() const {
    return slots_.capacity() * sizeof(std::int32_t) + slot_offset_.capacity() * sizeof(std::int64_t) +
           (group_offsets_.capacity() + group_dofs_.capacity()) * sizeof(int);
  }

 private:
  void set_perturbation();  // perturbation_ of factored_
  // CHOLMOD's counters (Eigen gives its common only to a non-const wrapper; read here, not written).
  const cholmod_common& common() const { return const_cast<Llt&>(llt_).cholmod(); }
  // Eigen's CHOLMOD wrapper, with the failing column exposed.
  struct Llt : Eigen::CholmodSupernodalLLT<Sparse, Eigen::Upper> {
    int failed_column() const;
    std::size_t bytes() const;
    /// analyzePattern() with the fill-reducing permutation `perm` (perm[k]: the unknown
    /// eliminated k-th) instead of CHOLMOD's own ordering; CHOLMOD still postorders it.
    void analyze_given(const Sparse& a, std::vector<int>& perm);
    cholmod_factor* factor() { return this->m_cholmodFactor; }
    /// factorize()'s numeric part on the permuted lower triangle `a1` (cholmod_ptranspose of the
    /// matrix by the factor's permutation: what cholmod_factorize_p makes and factorises).
    void factorize_permuted(cholmod_sparse* a1);
  };
  /// The numeric factorisation of a run whose factor is kept in single precision (the largest):
  /// the matrix's own arrays and the scatter's slots are let go while CHOLMOD's double factor
  /// exists, and made again, the same bits, once it is rounded (system_matrix.cpp).
  void factorize_lean();
  /// The numeric factorisation of the others: the matrix gathered into its factor's order
  /// (permuted_), which CHOLMOD factorises without copying it (system_matrix.cpp).
  void factorize_in_order();
  void place_slots();  // slots_ of every group of the last build in k_'s pattern
  /// (P + E)⁻¹ b with the factorisation, in double: CHOLMOD's solve, or the single-precision
  /// factor's refined against factored_.
  Eigen::VectorXd solve_factored(const Eigen::VectorXd& b) const;
  void keep_single();  // the factor just made goes to single precision, if set so, else to own_ (below own_from_)
  void analyse(const Sparse& a);  // CHOLMOD's symbolic analysis of a's pattern, under the ordering set
  Sparse k_;
  // Where each group's block lands: for the entries (i, j) of its m × m block, column-major,
  // that the upper triangle stores (dof i ≥ dof j; about half: 78 of 144 for a pair of 6-unknown
  // elements), the index into the values. The other entries are the mirrors of stored ones.
  std::vector<std::int64_t> slot_offset_;  // [group+1] CSR into slots_
  std::vector<std::int32_t> slots_;
  static std::int64_t stored_entries(const int* d, int m);
  std::vector<int> group_offsets_, group_dofs_;  // the groups of the last build (build_pattern's)
  bool grow_in_place(int n, const std::vector<int>& offsets, const std::vector<int>& dofs);
  std::vector<double> saved_;
  // The saved values' nonzero entries (every diagonal kept, last in its column), in k_'s order:
  // what saved_times() multiplies, below single_from_ (save()). Empty: it multiplies saved_.
  std::vector<int> saved_outer_, saved_inner_;
  std::vector<double> saved_nonzero_;
  Sparse factored_;  // the matrix of the current factorisation
  /// Value index of unknown i's diagonal entry: the last of its column (rows ≤ i, sorted).
  int diagonal(int i) const { return k_.outerIndexPtr()[i + 1] - 1; }
  Llt llt_;
  // The matrix in the factor's order (its layout from the last analysis; not ready: lay it out
  // before the next factorisation). Below single_from_ only: the largest runs keep no copy.
  PermutedLower permuted_;
  bool analysed_ = false;
  bool has_factor_ = false;
  std::size_t analyses_ = 0;
  std::size_t builds_ = 0;
  double factor_nonzeros_ = 0, factor_flops_ = 0;
  std::string ordering_;
  std::vector<int> kept_perm_;   // the METIS ordering on the covers kept for later analyses (empty: none)
  double kept_fill_ = 0;         // factor nonzeros of the analysis that found kept_perm_
  double kept_nonzeros_ = 0;     // the matrix's nonzeros (upper triangle) at that analysis
  std::size_t orderings_ = 0;    // kept_perm_ found anew so far
  bool analyse_kept(const Sparse& a);  // analyse a under kept_perm_; false if its fill has grown too far
  /// a's pattern lies within the factor of the last analysis under kept_perm_ (its supernodes'
  /// rows, in its order): analysed under kept_perm_, its factor stays within that one's
  /// structure, and a lean run keeps the ordering for it (system_matrix.cpp).
  /// With `placed` (a lean run), an order for a pattern that does not lie within: the last
  /// factor's, with the covers of the entries outside placed (placed_ordering; left empty when
  /// too many lie outside).
  bool keeps_symbolic(const Sparse& a, std::vector<int>* placed = nullptr) const;
  std::size_t kept_analyses_ = 0;  // kept_analyses()
  std::vector<int> placed_;        // keeps_symbolic's placed order for the analysis at hand
  std::size_t placed_analyses_ = 0;  // placed_analyses()
  // The pattern as it was at the last analysis or kept one lies within the factor, and these
  // (column, row) entries have been added to it since (grow_in_place); false: not known (a
  // pattern built anew, a restored factor), keeps_symbolic() checks every entry.
  bool in_factor_ = false;
  std::vector<std::pair<int, int>> added_since_;
  bool restoring_ = false;         // analyse() under kept_perm_ in any run (a restore; keeps_symbolic)
  int block_ = 0, blocked_ = 0, block_from_ = kBlockOrderingUnknowns;  // set_block_ordering()
  int failed_unknown_ = -1;
  std::vector<int> regularised_;
  double eps_ = 0;
  Eigen::VectorXd perturbation_;  // [n] E: the factor's diagonal perturbation (0 off regularised_)
  int refinements_ = 0;
  SingleFactor single_;  // the factor in single precision (set_single_precision), else not ready
  DoubleFactor own_;     // CHOLMOD's double factor read by our passes (below own_from_), else not ready
  int single_from_ = 0;
  int own_from_ = own_solve_from_environment();  // unknowns below which own_ solves (0: never)
  int lean_from_ = kLeanFactorUnknowns;  // set_lean_factorisation()
  mutable std::size_t single_refinements_ = 0;
};

}  // namespace nmm::solve
