// CHOLMOD's supernodal factor held in single precision, and its triangular solves.
//
// A conjugate-gradient iteration of the contact solve (contact_solve.cpp) is a solve pair with
// the kept factor, L Lᵀ z = r: a pass forward and a pass back through every value of L. On the
// largest walls that pair reads 22–172 M factor values per iteration and runs at the memory's
// speed (docs/performance.md (h)); stored as float, L takes half the bytes to read and to hold.
//
// What it changes. With L̃ = fl32(L), L̃ L̃ᵀ = P + F with |F| ≲ 2u·|L||L|ᵀ (u = 2⁻²⁴ ≈ 6e-8),
// so as a preconditioner L̃ L̃ᵀ differs from P by a relative O(u·κ(P)) in the P-norm: CG on it
// converges as on P once u·κ ≪ 1, with a few more iterations where the springs did not switch.
// A solve that must be exact (after a factorisation) is refined against the factorised matrix
// in double (system_matrix.cpp): x ← x + (L̃ L̃ᵀ)⁻¹ (b − P x), each pass gaining −log10(u·κ)
// digits. The vectors and the sums stay in double; only L's values are rounded.
//
// In place: the float values take the first half of CHOLMOD's own value array (value k, 8 bytes
// at 8k, is read before float k, 4 bytes at 4k, is written), and the pages of the second half
// go back to the system (madvise): at once, or (keep_spare) when the matrix's pattern changes
// (release_spare()), since the next factorisation of the same pattern writes them again and a
// page given back comes back zero-filled by the kernel on that write. CHOLMOD's next numeric
// factorisation writes every value of that array again, so the factor's structure (supernodes,
// rows, permutation) is shared and the double values no longer exist: every solve of a
// SystemMatrix in this mode comes here.
//
// Subnormals. The factor of a brick wall holds many values far below its scale (fill between
// nearly decoupled blocks: at 930k unknowns 12–15 % of the 204 M values lie below 1.18e-38,
// float's smallest normal, most of them above 1e-290), which rounding makes subnormal floats;
// each product with one costs the CPU a microcode assist in the solves' passes. A lean run's
// factor (system_matrix.h) takes such a value as 0 (flush_subnormal): |ΔL| < 1.2e-38 against
// values of order 1, far inside the rounding's own 2⁻²⁴.
//
// DoubleFactor: the same passes over CHOLMOD's own double factor, read where CHOLMOD keeps it
// (system_matrix.cpp: below kOwnSolveUnknowns where NMM_OWN_SOLVE=1 sets it on, instead of cholmod_solve). CHOLMOD's solve calls
// dtrsv and dgemv per supernode and pass, on narrow blocks here (87 supernodes of 11 columns on
// average, 10 × 10 wall at h = 2 m), and makes and frees dense vectors per solve; these passes
// loop over the supernodes with a work vector kept per thread: a solve pair there 503k → 303k
// instructions (callgrind, 2026-12-02, docs/performance.md (e)). The sums run in another order
// than CHOLMOD's (and multiply by 1/L_kk): the same solution to round-off, not the same bits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <cholmod.h>

namespace nmm::solve {

class SingleFactor {
 public:
  /// Rounds the numeric supernodal LLᵀ factor `l` (int indices, real) to float in place; `l`
  /// must then not be solved by CHOLMOD until it is factorised again. False (and nothing done)
  /// for a factor of another kind.
  /// The pages of the array's second half (the double values' tail) go back to the system now,
  /// or with `keep_spare` at release_spare().
  /// With `flush_subnormal` a value below float's smallest normal (1.18e-38) becomes 0, not a
  /// subnormal float (below).
  bool take(cholmod_factor* l, bool keep_spare = false, bool flush_subnormal = false);
  /// Gives back the pages of the second half that take() kept (nothing if none are kept).
  void release_spare();
  /// Bytes of the second half kept resident (take's keep_spare), 0 once given back.
  std::size_t spare_bytes() const { return spare_end_ - spare_begin_; }
  /// Forgets the factor (before CHOLMOD refactorises or frees it: the kept pages are its).
  void clear() {
    l_ = nullptr;
    spare_begin_ = spare_end_ = 0;
  }
  bool ready() const { return l_ != nullptr; }
  /// x = (L̃ L̃ᵀ)⁻¹ b in the unknowns' order (the permutation undone), in double.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// The passes' kernels: AVX where the CPU has it (the default), else SSE2; both give the same
  /// bits (single_factor.cpp). Returns whether AVX is used now; a test compares the two.
  static bool use_avx(bool on);
  /// Bytes the factor holds: float values, supernodes' row indices, per-column integers.
  std::size_t bytes() const;

 private:
  const cholmod_factor* l_ = nullptr;
  const float* x_ = nullptr;  // [xsize] the values, supernode by supernode, column-major
  std::vector<double> inv_;   // [n] 1 / L_kk in the factor's column order
  int max_rows_ = 0;          // the tallest supernode's rows (work vector size)
  std::uintptr_t spare_begin_ = 0, spare_end_ = 0;  // the kept pages of the second half (take)
};

/// A view of CHOLMOD's supernodal double LLᵀ factor, solved by SingleFactor's passes. Valid
/// until CHOLMOD refactorises or frees it: view() again after each factorisation.
class DoubleFactor {
 public:
  /// Reads the numeric supernodal LLᵀ factor `l` (int indices, real, complete); false (and not
  /// ready) for a factor of another kind.
  bool view(const cholmod_factor* l);
  void clear() { l_ = nullptr; }
  bool ready() const { return l_ != nullptr; }
  /// x = (L Lᵀ)⁻¹ b in the unknowns' order (the permutation undone).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

 private:
  const cholmod_factor* l_ = nullptr;
  std::vector<double> inv_;  // [n] 1 / L_kk in the factor's column order
  int max_rows_ = 0;
};

}  // namespace nmm::solve
