#include "solver/discretisation/system_matrix.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <string>

#if defined(__x86_64__) || defined(__SSE2__)
#include <xmmintrin.h>
#endif

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "common/error.h"
#include "common/memory_marks.h"
#include "solver/discretisation/fill_ordering.h"
#include "solver/discretisation/parked_array.h"
#include "solver/discretisation/state_bytes.h"

namespace nmm::solve {

namespace {
// Marks the kept ordering in factor_source()'s bytes, after the matrix ("ORDERING" in ASCII: an
// older checkpoint's note there starts with its length, far smaller).
constexpr std::uint64_t kOrderingTag = 0x474E49524544524FULL;

// A placed order (analyse_kept) serves while its factor's flops stay within this factor of the
// last analysis's. The new pairs joined under the kept order as it is cost 2.2–2.9 × METIS's
// flops anew (the 10,000-block walls' first growth); METIS's own flops grow with the pattern, by
// 9.9 % on the 100,000-block wall between steps 1 and 14, where a bound of 1.10 sent the placed
// order to METIS; a placed factor's extra flops (+3 to +12 % at 222k unknowns) cost less than a
// METIS ordering (6 s at 930k unknowns against a numeric factorisation's 10–15 s).
constexpr double kPlacedFlops = 1.25;

// A grown scatter's arrays keep 1/kScatterRoom of their size as room for the next growths
// (grow_in_place).
constexpr std::size_t kScatterRoom = 64;

// A lean run's numeric factorisation (factorize_lean) runs with the SSE control register's
// flush-to-zero and denormals-are-zero bits set: a result below 2.2e-308 is 0, an operand there
// is read as 0. The wall's factor holds tens of millions of values between 1e-290 and 1e-38
// (fill between nearly decoupled blocks, single_factor.h), whose products fall below the
// double range, and each such product costs the CPU a microcode assist inside the dense
// kernels. At 930k unknowns they grow over the run (values below 1.18e-38: 25 M of 204 M at
// step 1, 51 M of 219 M at step 14, with 44,548 subnormal doubles in the factor), and the
// numeric factorisation's CPU with them (5.5 s at step 1, 13.1 s at step 14, 163 against 141
// Gflop; `perf`: the time in dgemm's kernel, 2.8 × per flop); with the two bits step 1's three
// factorisations took 5.7 / 5.2 / 5.2 s against 5.5 / 5.6 / 6.1 s (docs/notes/2026-11-scale.md,
// 2026-12-01). The values lost are below 1e-300 of the factor's scale. The bits stay the same on every x86-64 CPU (the two bits
// are SSE's, and AVX follows them); a restart refactorises under them too. OpenBLAS's own
// threads (more than one solver thread) keep their register as it is: deterministic per
// thread count, as the partition of CHOLMOD's and OpenBLAS's loops already is.
class FlushSubnormals {
 public:
#if defined(__x86_64__) || defined(__SSE2__)
  FlushSubnormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFtz | kDaz); }
  ~FlushSubnormals() { _mm_setcsr(saved_); }

 private:
  static constexpr unsigned kFtz = 0x8000, kDaz = 0x0040;
  unsigned saved_;

 public:
#else
  FlushSubnormals() = default;
#endif
  FlushSubnormals(const FlushSubnormals&) = delete;
  FlushSubnormals& operator=(const FlushSubnormals&) = delete;
};

// y ← y + α·A v (α = ±1) for the symmetric A whose upper triangle is (outer, inner, values),
// diagonal last in each column. The sums run in the order of Eigen's product with the lower
// triangle in columns (the storage before the upper one): into y_i the terms of the columns
// left of i one by one, then the diagonal's, then the terms of the columns right of i summed
// apart from zero and added at once. So every result is the same, bit for bit, as with the
// lower storage.
void add_upper_times(int n, const int* outer, const int* inner, const double* values, const Eigen::VectorXd& v,
                     double alpha, Eigen::VectorXd& y) {
  // [i] Σ over columns j > i of A_ij·v_j; all zero between calls (the last loop zeroes what it
  // reads: one pass less over the vector per product).
  thread_local std::vector<double> right;
  if (right.size() != static_cast<std::size_t>(n)) right.assign(static_cast<std::size_t>(n), 0.0);
  const double* vv = v.data();
  double* yy = y.data();
  double* rr = right.data();
  for (int j = 0; j < n; ++j) {
    const int diagonal = outer[j + 1] - 1;
    const double vj = vv[j];
    double yj = yy[j];  // summed in a register, term by term as into y_j itself
    for (int p = outer[j]; p < diagonal; ++p) {
      const int i = inner[p];
      yj += values[p] * (alpha * vv[i]);
      rr[i] += values[p] * vj;
    }
    yy[j] = yj + alpha * values[diagonal] * vj;
  }
  for (int i = 0; i < n; ++i) {
    yy[i] += alpha * rr[i];
    rr[i] = 0.0;
  }
}
}  // namespace

// Entries of a group's m × m block that the upper triangle stores: (i, j) with dof i ≥ dof j
// (the mirror of each off-diagonal pair is left out; a repeated unknown keeps both copies).
std::int64_t SystemMatrix::stored_entries(const int* d, int m) {
  std::int64_t count = 0;
  for (int jj = 0; jj < m; ++jj)
    for (int ii = 0; ii < m; ++ii) count += d[ii] >= d[jj] ? 1 : 0;
  return count;
}

bool SystemMatrix::grow_in_place(int n, const std::vector<int>& offsets, const std::vector<int>& dofs) {
  // The groups of the last build, in order, among the new ones (a pattern that grew by pairs of
  // elements in contact: the pairs are sorted, so the old groups keep their relative order).
  // Then the nonzeros a build from scratch would give are the old ones and the new groups'
  // entries that are not among them: those are merged into their columns, the old groups'
  // positions follow the shift, and the new groups' positions are found by a search in their
  // columns. Work ~ nonzeros + Σ (group size)² of copying, against a build's incidence lists and
  // sorted columns (a build took about 4 ms of a 48 ms static step on the DDA code's 20 × 20 wall
  // at h = 2 m, where the pattern grows in most steps; growing, about 1 ms). A dropped group (the
  // pattern shrank) needs the build.
  if (k_.rows() != n || group_offsets_.empty()) return false;
  const std::size_t ng = offsets.size() - 1, old_ng = group_offsets_.size() - 1;
  if (ng < old_ng) return false;
  const int* outer = k_.outerIndexPtr();
  const int* inner = k_.innerIndexPtr();
  const auto find = [](const int* o, const int* in, int row, int col) {
    const int* first = in + o[col];
    const int* last = in + o[col + 1];
    const int* at = std::lower_bound(first, last, row);
    return at == last || *at != row ? -1 : static_cast<int>(at - in);
  };
  constexpr std::size_t kNew = static_cast<std::size_t>(-1);
  std::vector<std::size_t> old_of(ng, kNew);  // the old group a group is, or kNew
  std::vector<std::pair<int, int>> added;     // (column, row) of entries not in the matrix
  std::size_t o = 0;
  for (std::size_t g = 0; g < ng; ++g) {
    const int m = offsets[g + 1] - offsets[g];
    const int* d = dofs.data() + offsets[g];
    if (o < old_ng && group_offsets_[o + 1] - group_offsets_[o] == m &&
        std::equal(d, d + m, group_dofs_.data() + group_offsets_[o])) {
      old_of[g] = o++;
      continue;
    }
    for (int jj = 0; jj < m; ++jj)
      for (int ii = 0; ii < m; ++ii)
        if (d[ii] >= d[jj] && find(outer, inner, d[jj], d[ii]) < 0) added.emplace_back(d[ii], d[jj]);
  }
  if (o != old_ng) return false;
  const auto room = [](std::size_t size) { return size + size / kScatterRoom + 64; };
  // The new entries are merged into the matrix's own arrays, from the last column to the first:
  // every old entry moves up (never down) by the new entries before it, so nothing still to be
  // read is overwritten. The arrays keep a little room to grow (kScatterRoom), as the slots do:
  // a growth that made new arrays (the matrix's rows and values, a map of the old positions,
  // 0.37 GB at 930k unknowns) had the kernel fault in and clear them in every static step there.
  // `shift[c]`: the new entries in the columns before c, by which column c's old entries move
  // up, plus those above each entry's row in its own column (shifted_position).
  std::vector<int> shift;  // [column + 1] (empty: nothing added)
  if (!added.empty()) {
    std::sort(added.begin(), added.end());
    added.erase(std::unique(added.begin(), added.end()), added.end());
    const auto nnz = static_cast<std::size_t>(k_.nonZeros());
    const std::size_t grown = nnz + added.size();
    shift.assign(static_cast<std::size_t>(n) + 1, 0);
    for (const auto& [col, row] : added) ++shift[static_cast<std::size_t>(col) + 1];
    for (int c = 0; c < n; ++c) shift[static_cast<std::size_t>(c) + 1] += shift[static_cast<std::size_t>(c)];
    const auto capacity = static_cast<std::size_t>(k_.data().allocatedSize());
    if (capacity < grown) k_.data().reserve(static_cast<Eigen::Index>(room(grown) - nnz));
    k_.resizeNonZeros(static_cast<Eigen::Index>(grown));  // within the room: the same arrays
    int* outer_w = k_.outerIndexPtr();
    int* inner_w = k_.innerIndexPtr();
    std::size_t a = added.size();
    for (int c = n; c-- > 0;) {
      int p = outer_w[c + 1];  // the old end of column c (not yet shifted)
      const int begin = outer_w[c];
      auto w = static_cast<std::size_t>(p) + static_cast<std::size_t>(shift[static_cast<std::size_t>(c) + 1]);
      while (p > begin || (a > 0 && added[a - 1].first == c)) {
        if (a > 0 && added[a - 1].first == c && (p == begin || added[a - 1].second > inner_w[p - 1]))
          inner_w[--w] = added[--a].second;
        else
          inner_w[--w] = inner_w[--p];
      }
    }
    for (int c = 0; c <= n; ++c) outer_w[c] += shift[static_cast<std::size_t>(c)];
    if (in_factor_) added_since_.insert(added_since_.end(), added.begin(), added.end());
    analysed_ = false;
    outer = k_.outerIndexPtr();
    inner = k_.innerIndexPtr();
  }
  // Where an old entry (row, col) at old position p lies now.
  const auto shifted_position = [&](std::int32_t p, int row, int col) {
    const auto c = static_cast<std::size_t>(col);
    int up = shift[c];
    // The new entries of column col lie in `added` at [shift[c], shift[c + 1]), sorted by row.
    if (shift[c + 1] > shift[c]) {
      const auto first = added.begin() + shift[c], last = added.begin() + shift[c + 1];
      up += static_cast<int>(std::lower_bound(first, last, std::make_pair(col, row)) - first);
    }
    return p + up;
  };
  std::vector<std::int64_t> slot_offset(ng + 1, 0);
  for (std::size_t g = 0; g < ng; ++g)
    slot_offset[g + 1] = slot_offset[g] + (old_of[g] != kNew ? slot_offset_[old_of[g] + 1] - slot_offset_[old_of[g]]
                                                              : stored_entries(dofs.data() + offsets[g], offsets[g + 1] - offsets[g]));
  // The slots are grown in their own array, from the last group to the first: only groups are
  // inserted, so each old group's slots move up (never down) past the new groups before it, and
  // a group moved or placed never lands on an old group's slots still to move. The array keeps
  // a little room to grow (kScatterRoom), so that most growths neither allocate nor fault in a
  // second array of the slots' size (0.24 GB at 930k unknowns, where the pattern grows by pairs
  // of already coupled covers in most static steps); the groups' unknowns likewise.
  const auto total = static_cast<std::size_t>(slot_offset[ng]);
  if (slots_.capacity() < total) slots_.reserve(room(total));
  slots_.resize(total);
  for (std::size_t g = ng; g-- > 0;) {
    std::int32_t* out = slots_.data() + slot_offset[g];
    if (old_of[g] != kNew) {
      const std::int32_t* first = slots_.data() + slot_offset_[old_of[g]];
      const std::ptrdiff_t len = slot_offset_[old_of[g] + 1] - slot_offset_[old_of[g]];
      if (shift.empty()) {
        if (out != first) std::copy_backward(first, first + len, out + len);
      } else {
        // The group's stored entries in build_pattern's order (row d[jj], column d[ii] for
        // d[ii] ≥ d[jj]), walked backwards: out lies at or above first, so each slot is read
        // before anything is written over it.
        const int m = offsets[g + 1] - offsets[g];
        const int* d = dofs.data() + offsets[g];
        std::ptrdiff_t k = len;
        for (int jj = m; jj-- > 0;)
          for (int ii = m; ii-- > 0;)
            if (d[ii] >= d[jj]) {
              --k;
              out[k] = shifted_position(first[k], d[jj], d[ii]);
            }
      }
    } else {
      const int m = offsets[g + 1] - offsets[g];
      const int* d = dofs.data() + offsets[g];
      for (int jj = 0; jj < m; ++jj)
        for (int ii = 0; ii < m; ++ii)
          if (d[ii] >= d[jj]) *out++ = find(outer, inner, d[jj], d[ii]);
    }
  }
  slot_offset_ = std::move(slot_offset);
  group_offsets_ = offsets;
  if (group_dofs_.capacity() < dofs.size()) group_dofs_.reserve(room(dofs.size()));
  group_dofs_.assign(dofs.begin(), dofs.end());
  set_zero();
  return true;
}

void SystemMatrix::build_pattern(int n, const std::vector<int>& offsets, const std::vector<int>& dofs) {
  // The single-precision factor's spare pages (keep_single) go back before the new pattern's
  // arrays are made: a new pattern is the run's memory peak, and its factor is a new array.
  single_.release_spare();
  memory_mark("before pattern");
  if (grow_in_place(n, offsets, dofs)) {
    memory_mark("pattern grown");
    return;
  }
  ++builds_;
  // Column by column, without sorting the whole pattern or searching it: the groups of each
  // unknown (dof → groups incidence), then column c's rows are the unknowns ≥ c of c's groups,
  // marked once each; a group's entries (i, j) with dof j = c land at the positions of their rows
  // in column c. Work ~ Σ (group size)², no binary search (with per-column row lists and a
  // search per entry this took 30–40 ms at 20k unknowns, 8 ms now). A pattern that only grew
  // (a contact reached a new pair of elements, in most steps of a settling brick wall) is grown
  // in place instead (grow_in_place).
  const std::size_t ng = offsets.size() - 1;
  std::vector<std::int32_t> group_offset(static_cast<std::size_t>(n) + 1, 0), groups;
  {
    std::vector<std::int32_t> last(static_cast<std::size_t>(n), -1);  // an unknown may repeat in a group
    for (std::size_t g = 0; g < ng; ++g)
      for (int i = offsets[g]; i < offsets[g + 1]; ++i)
        if (last[dofs[i]] != static_cast<std::int32_t>(g)) {
          last[dofs[i]] = static_cast<std::int32_t>(g);
          ++group_offset[dofs[i] + 1];
        }
    for (int c = 0; c < n; ++c) group_offset[c + 1] += group_offset[c];
    groups.resize(static_cast<std::size_t>(group_offset[n]));
    std::vector<std::int32_t> fill(group_offset.begin(), group_offset.end() - 1);
    std::fill(last.begin(), last.end(), -1);
    for (std::size_t g = 0; g < ng; ++g)
      for (int i = offsets[g]; i < offsets[g + 1]; ++i)
        if (last[dofs[i]] != static_cast<std::int32_t>(g)) {
          last[dofs[i]] = static_cast<std::int32_t>(g);
          groups[fill[dofs[i]]++] = static_cast<std::int32_t>(g);
        }
  }
  // Slots: entry (i, j) of a group's block (column-major) lands at (dof j, dof i) of the upper
  // triangle when dof i ≥ dof j; its mirror (j, i) then does not (-1), so each global entry gets
  // each local entry once. (The entry below the block's diagonal, not its mirror: an element's
  // block is symmetric only to round-off, and these are the values the lower triangle held.) An
  // unknown repeated in a group maps all its copies to the same entries, which sums them.
  // Built first for all m² entries of each group (`full`, -1 where the mirror stands), then
  // kept for the stored ones only (stored_entries).
  slots_.clear();
  slots_.shrink_to_fit();
  std::vector<std::int64_t> full_offset(ng + 1, 0);
  for (std::size_t g = 0; g < ng; ++g) {
    const int m = offsets[g + 1] - offsets[g];
    full_offset[g + 1] = full_offset[g] + m * m;
  }
  std::vector<std::int32_t> full(static_cast<std::size_t>(full_offset[ng]), -1);
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0), inner;
  inner.reserve(static_cast<std::size_t>(n) * 16);
  std::vector<std::int32_t> mark(static_cast<std::size_t>(n), -1), pos(static_cast<std::size_t>(n), -1);
  for (int c = 0; c < n; ++c) {
    const std::size_t first = inner.size();
    inner.push_back(c);  // every diagonal, even of a lone unknown (sorted last)
    mark[c] = c;
    for (std::int32_t k = group_offset[c]; k < group_offset[c + 1]; ++k) {
      const std::int32_t g = groups[k];
      for (int i = offsets[g]; i < offsets[g + 1]; ++i)
        if (dofs[i] < c && mark[dofs[i]] != c) {
          mark[dofs[i]] = c;
          inner.push_back(dofs[i]);
        }
    }
    std::sort(inner.begin() + static_cast<std::ptrdiff_t>(first), inner.end());
    for (std::size_t p = first; p < inner.size(); ++p) pos[inner[p]] = static_cast<std::int32_t>(p);
    outer[c + 1] = static_cast<int>(inner.size());
    for (std::int32_t k = group_offset[c]; k < group_offset[c + 1]; ++k) {
      const std::int32_t g = groups[k];
      const int m = offsets[g + 1] - offsets[g];
      const int* d = dofs.data() + offsets[g];
      std::int32_t* slot = full.data() + full_offset[g];
      for (int ii = 0; ii < m; ++ii) {
        if (d[ii] != c) continue;
        for (int jj = 0; jj < m; ++jj)
          if (d[jj] <= c) slot[jj * m + ii] = pos[d[jj]];
      }
    }
  }
  slot_offset_.assign(ng + 1, 0);
  for (std::size_t g = 0; g < ng; ++g)
    slot_offset_[g + 1] = slot_offset_[g] + stored_entries(dofs.data() + offsets[g], offsets[g + 1] - offsets[g]);
  slots_.resize(static_cast<std::size_t>(slot_offset_[ng]));
  {
    std::int32_t* out = slots_.data();
    for (const std::int32_t v : full)
      if (v >= 0) *out++ = v;
  }
  std::vector<std::int32_t>().swap(full);
  // New pairs of elements whose covers were already coupled (neighbours along a joint share two
  // of their three covers) leave the pattern of unknowns as it was: CHOLMOD's symbolic analysis
  // then still holds.
  const bool same = k_.rows() == n && k_.nonZeros() == static_cast<Eigen::Index>(inner.size()) &&
                    std::equal(outer.begin(), outer.end(), k_.outerIndexPtr()) &&
                    std::equal(inner.begin(), inner.end(), k_.innerIndexPtr());
  if (!same) {
    in_factor_ = false;
    k_ = Sparse(n, n);
    k_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
    std::copy(outer.begin(), outer.end(), k_.outerIndexPtr());
    std::copy(inner.begin(), inner.end(), k_.innerIndexPtr());
    analysed_ = false;
  }
  std::fill(k_.valuePtr(), k_.valuePtr() + inner.size(), 0.0);
  group_offsets_ = offsets;
  group_dofs_ = dofs;
  // A matrix that is not positive definite is reported by us (failed_unknown), on one line;
  // CHOLMOD itself must not print.
  llt_.cholmod().print = 0;
  memory_mark("pattern built");
}

// AMD alone. CHOLMOD's default strategy tries METIS after AMD when AMD's factor is dense
// (flops / nnz(L) ≥ 500 and nnz(L) / nnz(A) ≥ 5) and keeps the ordering with the fewer factor
// nonzeros. On the DDA code's 10,000-block wall (contact_bench --trace 100 --sizes 100 --peer
// --mesh 2, one thread, 2026-11-28) the first analysis stayed with AMD and the later ones, past
// the threshold, took METIS — 13.3 M factor nonzeros and 4.6 Gflop against AMD's 15.7 M and
// 8.1 Gflop — yet the step took 749 ms against 686 ms with AMD alone: factorisations with their
// analyses 194 ms per step against 128 (17 analyses against 14), and the final matrix's
// factorisation timed 465 ms with the METIS ordering against 346 ms with AMD's, despite its
// fewer flops. The walls up to 30 × 30 never reach the threshold, so their orderings, and their
// results, are the same either way.
void SystemMatrix::set_amd_only(bool on) {
  cholmod_common& c = llt_.cholmod();
  c.nmethods = on ? 1 : 0;
  c.method[0].ordering = on ? CHOLMOD_AMD : CHOLMOD_GIVEN;  // CHOLMOD_GIVEN: cholmod_defaults'
}

void SystemMatrix::set_zero() { std::fill(k_.valuePtr(), k_.valuePtr() + k_.nonZeros(), 0.0); }

void SystemMatrix::add_group(std::size_t g, const double* k) {
  // The stored entries in the block's column-major order, as slots_ lists them: each lands once
  // per group on its global entry, in the same order as when every m² entry had a slot.
  const std::int32_t* s = slots_.data() + slot_offset_[g];
  const int* d = group_dofs_.data() + group_offsets_[g];
  const int m = group_offsets_[g + 1] - group_offsets_[g];
  double* v = k_.valuePtr();
  for (int jj = 0; jj < m; ++jj, k += m) {
    const int dj = d[jj];
    for (int ii = 0; ii < m; ++ii)
      if (d[ii] >= dj) v[*s++] += k[ii];
  }
}

void SystemMatrix::add_diagonal(int i, double value) { k_.valuePtr()[diagonal(i)] += value; }

int SystemMatrix::Llt::failed_column() const {
  // CHOLMOD records the column where the factorisation stopped (L->minor) in its fill-reducing
  // order; L->Perm maps it back to our unknown.
  const cholmod_factor* f = this->m_cholmodFactor;
  if (!f || f->minor >= f->n) return -1;
  return f->Perm ? static_cast<const int*>(f->Perm)[f->minor] : static_cast<int>(f->minor);
}

std::size_t SystemMatrix::Llt::bytes() const {
  const cholmod_factor* f = this->m_cholmodFactor;
  if (!f) return 0;
  // Supernodal: xsize values, ssize row indices, and per column or supernode a few integers.
  return f->xsize * sizeof(double) + f->ssize * sizeof(int) + (4 * f->n + 4 * f->nsuper) * sizeof(int);
}

void SystemMatrix::Llt::analyze_given(const Sparse& a, std::vector<int>& perm) {
  cholmod_common& c = this->cholmod();
  if (this->m_cholmodFactor) cholmod_free_factor(&this->m_cholmodFactor, &c);
  cholmod_sparse view = Eigen::viewAsCholmod(a.selfadjointView<Eigen::Upper>());
  const int methods = c.nmethods, ordering = c.method[0].ordering;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_GIVEN;
  this->m_cholmodFactor = cholmod_analyze_p(&view, perm.data(), nullptr, 0, &c);
  c.nmethods = methods;
  c.method[0].ordering = ordering;
  this->m_isInitialized = true;
  this->m_info = Eigen::Success;
  this->m_analysisIsOk = true;
  this->m_factorizationIsOk = false;
}

// METIS on the covers from kBlockOrderingUnknowns unknowns. Nested dissection's factor is the
// smaller the larger the wall, while finding a METIS ordering costs several AMD analyses and a
// run with contact analyses again whenever its pattern grows. Measured on the DDA code's static
// walls (contact_bench --trace, one thread, 2026-11-29; docs/notes/2026-11-scale.md), with a
// new ordering at every analysis:
//   316 × 316 bricks, h = 2 m, 929,502 unknowns: factor 172 M nonzeros and 141 Gflop against
//     AMD's 231 M and 310 Gflop; step 1 (3 factorisations) 34.1 s against 50.2 s
//   100 × 100, h = 0.5 m, 222,516 unknowns: 0.94 × AMD's CPU over steps 1–15 (the first
//     pattern's factor: 35 M nonzeros), 1.145 × over steps 16–61, where the pattern has shed
//     its unused pairs and grows again every third step (METIS's ordering 709 ms against a
//     factorisation's 650)
//   100 × 100, h = 2 m, 93,350 unknowns: 4.4 against 6.3 Gflop, but 370 ms per analysis
//     against 85 ms, at 0.13 analyses and 0.17 factorisations per step
//
// So an ordering, once found, is kept for the patterns that follow. A grown pattern adds the
// element pairs of new contacts: entries between covers a few elements apart, which a nested
// dissection's separators rarely had to keep apart, so its fill grows little; a pattern that
// shed pairs has less. An analysis under the kept ordering (cholmod_analyze_p, with CHOLMOD's
// postordering) costs less than AMD's; when its factor has more than kOrderingRefill times the
// nonzeros the ordering had when it was found, or the pattern has shed pairs since, a new one
// is found. Which ordering an analysis
// uses depends on the patterns of the run so far, not on this one's alone: a checkpoint keeps
// the ordering and its fill with the factorisation (factor_source), so that a restarted run
// analyses as the straight one did.
bool SystemMatrix::analyse_kept(const Sparse& a) {
  if (kept_perm_.size() != static_cast<std::size_t>(a.rows())) return false;
  // A lean run (the largest) does not analyse a pattern that does not lie within the last
  // factor (keeps_symbolic: that one keeps the ordering, its factor does not grow) under the
  // kept ordering as it is: there the kept ordering's factor, 1.06–1.07 × the nonzeros, took
  // 31–37 s to factorise against 13–14 s under a new ordering (7–8 s to find) and raised the
  // run's memory peak by its 0.11 GB more double values (316 × 316 bricks, h = 2 m, steps 15
  // and 22 against 6, 13 and 20; docs/performance.md (h)): the new pairs join paths of the
  // elimination tree (fill_ordering.cpp placed_ordering), their flops twice the nonzeros' share.
  // It places the new pairs' covers in it instead, or orders it anew. (A restored checkpoint,
  // and a pattern within the last factor, keeps_symbolic, are analysed under the kept ordering
  // in any run: restoring_.)
  const auto n = static_cast<int>(a.rows());
  if (!restoring_ && single_from_ > 0 && n >= single_from_ && n >= lean_from_) {  // as factorize()'s `lean`
    // A grown pattern with its new pairs placed (keeps_symbolic, placed_ordering): kept while
    // its factor's nonzeros stay within kOrderingRefill of the nested dissection's when found
    // (so that a restart, analysing under it, keeps it too), and its flops within kPlacedFlops
    // of the last analysis's (a restart's too: it analyses the same pattern under the same
    // order). On the 10,000-block wall at h = 2 m the placed orders' factors stayed within
    // -1 to +3 % of METIS's anew in nonzeros and flops over 40 steps, a METIS ordering's
    // nonzeros growing by 7 % with the pattern (bench/ordering_bench.cpp --growth).
    if (placed_.size() != static_cast<std::size_t>(n)) return false;
    llt_.analyze_given(a, placed_);
    if (llt_.cholmod().lnz > kOrderingRefill * kept_fill_ || llt_.cholmod().fl > kPlacedFlops * factor_flops_)
      return false;
    kept_perm_.swap(placed_);
    ++placed_analyses_;
    return true;
  }
  // A pattern with fewer nonzeros than the one the ordering was found on has shed pairs (it
  // only grows otherwise): a new ordering of the smaller pattern has less fill than the kept one.
  if (static_cast<double>(a.nonZeros()) < kept_nonzeros_) return false;
  llt_.analyze_given(a, kept_perm_);
  return llt_.cholmod().lnz <= kOrderingRefill * kept_fill_;
}

// A lean run (from kLeanFactorUnknowns) does not keep its order as it is for a new pattern
// (analyse_kept: it places the new pairs, or orders anew, METIS's 7–8 s at 930k unknowns),
// except for one grown within the last factor: every entry of the pattern
// lies within the rows of its supernodes, in its order. Such entries add no fill beyond that
// factor's structure (a supernode's rows below its columns lie within its parent's), so the
// analysis under the kept ordering (cholmod_analyze_p, without METIS) gives a factor no larger
// than the last one, and of its speed — not the kept orderings' 1.06–1.07 × the nonzeros that
// took twice as long to factorise (analyse_kept). (Factorising such a pattern with the last
// analysis itself, with no analysis at all, is exact too but not the factor a restart makes: a
// relaxed supernode holds explicit zeros, and an entry there changes the filled graph and
// with it the supernodes the restart's analysis finds; the 10,000-block wall at h = 0.5 m
// parted from the run with analyses at step 13, docs/notes/2026-11-scale.md.) A restart
// analyses under the checkpoint's ordering in any run, as the straight run did. Only under a
// kept ordering (METIS on the covers), and not for a pattern that shed pairs since the ordering
// was found (fewer nonzeros than then): that one is ordered anew, its fill being less. Work: one
// search among its supernode's rows per entry added since the last analysis.
bool SystemMatrix::keeps_symbolic(const Sparse& a, std::vector<int>* placed) const {
  const auto n = static_cast<int>(a.rows());
  if (block_ <= 0 || n < block_from_ || kept_perm_.size() != static_cast<std::size_t>(n)) return false;
  if (static_cast<double>(a.nonZeros()) < kept_nonzeros_) return false;
  const cholmod_factor* f = const_cast<Llt&>(llt_).factor();
  if (!f || static_cast<int>(f->n) != n) return false;
  const FactorRows rows(*f);
  if (!rows.ready()) return false;
  const auto within = [&](int j, int i) { return rows.within(j, i); };
  // The entries outside, for placed_ordering (a lean run): a few per new pair of covers; past
  // n / kOutsideShare of them the pattern is ordered anew.
  std::vector<std::pair<int, int>> outside;
  const std::size_t limit = placed ? static_cast<std::size_t>(n) / kOutsideShare : 0;
  const auto note = [&](int j, int i) {
    if (outside.size() <= limit) outside.emplace_back(j, i);
  };
  // Where the pattern at the last analysis is known to lie within, the entries added since
  // (the same answer as checking every one, in a tenth of the time or less).
  if (in_factor_) {
    for (const auto& [j, i] : added_since_)
      if (!within(j, i)) {
        if (!placed) return false;
        note(j, i);
      }
  } else {
    const int* outer = a.outerIndexPtr();
    const int* inner = a.innerIndexPtr();
    for (int j = 0; j < n; ++j)
      for (int p = outer[j]; p < outer[j + 1]; ++p)
        if (!within(j, inner[p])) {
          if (!placed) return false;
          note(j, inner[p]);
        }
  }
  if (outside.empty()) return true;
  if (outside.size() <= limit) *placed = placed_ordering(*f, outside, block_, blocked_);
  return false;
}

void SystemMatrix::analyse(const Sparse& a) {
  ++analyses_;
  single_.clear();     // the analysis frees the factor
  own_.clear();
  permuted_.clear();   // and its permutation
  const cholmod_common& c = llt_.cholmod();
  if (block_ > 0 && a.rows() >= block_from_) {
    bool ok = analyse_kept(a);
    if (!ok) {
      std::vector<int> perm = block_ordering(static_cast<int>(a.rows()), a.outerIndexPtr(), a.innerIndexPtr(), block_,
                                             FillOrdering::metis, blocked_);
      if (!perm.empty()) {
        llt_.analyze_given(a, perm);
        kept_perm_ = std::move(perm);
        kept_fill_ = c.lnz;
        kept_nonzeros_ = static_cast<double>(a.nonZeros());
        ++orderings_;
        ok = true;
      }
    }
    if (ok) {
      factor_nonzeros_ = c.lnz;
      factor_flops_ = c.fl;
      ordering_ = "metis_covers";
      return;
    }
  }
  kept_perm_.clear();
  llt_.analyzePattern(a);
  factor_nonzeros_ = c.lnz;
  factor_flops_ = c.fl;
  const int method = c.selected >= 0 && c.selected < CHOLMOD_MAXMETHODS ? c.method[c.selected].ordering : -1;
  ordering_ = method == CHOLMOD_AMD      ? "amd"
              : method == CHOLMOD_METIS  ? "metis"
              : method == CHOLMOD_NESDIS ? "nesdis"
              : method == CHOLMOD_COLAMD ? "colamd"
              : method == CHOLMOD_NATURAL ? "natural"
                                         : "other";
}

bool SystemMatrix::factorize() {
  cholmod_common& cc = llt_.cholmod();
  cc.memory_usage = cc.memory_inuse;  // cholmod_peak_bytes(): this factorisation's
  memory_mark("before factorisation");
  // Every factorisation writes the factor's double values anew (a new pattern's are allocated,
  // a kept one's pages refaulted: single_factor.h): the run's peak of memory. With a
  // single-precision factor (the largest runs) the last factorised matrix is let go first (it
  // is copied again below, once this factorisation has succeeded), and before a new pattern's
  // analysis the heap's free pages are returned, so that the double values take their place.
  const bool single = single_from_ > 0 && size() >= single_from_;
  const bool lean = single && size() >= lean_from_;  // (analyse_kept: a new ordering for each pattern)
  if (single) {
    Sparse().swap(factored_);
    has_factor_ = false;
  }
  if (!analysed_) {
    if (single) {
#if defined(__GLIBC__)
      malloc_trim(0);
#endif
      memory_mark("released");
    }
    // A lean run analyses a pattern grown within the last factor under the kept ordering
    // (keeps_symbolic), instead of ordering it anew.
    const bool within = lean && keeps_symbolic(k_, &placed_);
    kept_analyses_ += within ? 1 : 0;
    restoring_ = within;
    analyse(k_);
    restoring_ = false;
    std::vector<int>().swap(placed_);
    analysed_ = true;
    in_factor_ = true;
    added_since_.clear();
    memory_mark("analysis");
  }
  // The perturbation lives only in the factor: the values keep K for the refinement.
  std::vector<double> delta(regularised_.size());
  if (!regularised_.empty()) {
    double dmax = 0;
    for (int i : regularised_) dmax = std::max(dmax, k_.valuePtr()[diagonal(i)]);
    for (std::size_t r = 0; r < regularised_.size(); ++r) {
      const double kii = k_.valuePtr()[diagonal(regularised_[r])];
      delta[r] = eps_ * (kii > 0 ? kii : dmax);
      k_.valuePtr()[diagonal(regularised_[r])] += delta[r];
    }
  }
  single_.clear();  // CHOLMOD writes the factor's values anew
  own_.clear();
  if (lean)
    factorize_lean();  // rounds the factor to single precision itself
  else if (!single)
    factorize_in_order();
  else
    llt_.factorize(k_);
  memory_mark("factorisation");
  failed_unknown_ = -1;
  has_factor_ = llt_.info() == Eigen::Success;
  // The matrix factorised, perturbation included: a restart refactorises exactly it (bitwise).
  if (has_factor_) {
    factored_ = k_;
    memory_mark("matrix copied");
    set_perturbation();
    keep_single();
    memory_mark("single precision");
  }
  for (std::size_t r = 0; r < regularised_.size(); ++r) k_.valuePtr()[diagonal(regularised_[r])] -= delta[r];
  if (!has_factor_) {
    failed_unknown_ = llt_.failed_column();
    return false;
  }
  return true;
}

std::string SystemMatrix::factor_source() const {
  if (!has_factor_) return {};
  // The checkpoint keeps the lower triangle (its format since the first version): the transpose
  // of the stored upper one, the same entries.
  const Sparse lower = factored_.transpose();
  const auto n = static_cast<std::size_t>(lower.rows()), nnz = static_cast<std::size_t>(lower.nonZeros());
  ByteWriter w;
  w.put_vector(std::vector<int>(lower.outerIndexPtr(), lower.outerIndexPtr() + n + 1));
  w.put_vector(std::vector<int>(lower.innerIndexPtr(), lower.innerIndexPtr() + nnz));
  w.put_vector(std::vector<double>(lower.valuePtr(), lower.valuePtr() + nnz));
  // The kept ordering it was analysed under, and that ordering's fill when found (analyse()).
  if (!kept_perm_.empty()) {
    w.put<std::uint64_t>(kOrderingTag);
    w.put_vector(kept_perm_);
    w.put<double>(kept_fill_);
    w.put<double>(kept_nonzeros_);
  }
  return w.take();
}

bool SystemMatrix::factor_from_source(const std::string& bytes) {
  const auto n = static_cast<std::int64_t>(k_.rows());
  std::vector<int> outer, inner;
  std::vector<double> values, note;
  std::vector<int> perm;
  double fill = 0, nonzeros = 0;
  try {
    ByteReader r(bytes, "", "FACTOR");
    outer = r.get_vector<int>(static_cast<std::size_t>(n + 1), "column starts");
    const std::int64_t nnz = outer.back();
    if (nnz < n || nnz > n * n) return false;
    inner = r.get_vector<int>(static_cast<std::size_t>(nnz), "rows");
    values = r.get_vector<double>(static_cast<std::size_t>(nnz), "values");
    if (r.peek<std::uint64_t>(0) == kOrderingTag) {
      r.get<std::uint64_t>();
      perm = r.get_vector<int>(static_cast<std::size_t>(n), "ordering");
      fill = r.get<double>();
      nonzeros = r.get<double>();
    }
    // Older checkpoints end with a note on the springs factorised (no longer used): skipped.
    if (!r.at_end()) note = r.get_vector<double>(SIZE_MAX, "note");
    r.expect_end();
  } catch (const InputError&) {
    return false;
  }
  const auto nnz = static_cast<std::int64_t>(inner.size());
  Sparse m(n, n);
  m.resizeNonZeros(nnz);
  std::copy(outer.begin(), outer.end(), m.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), m.innerIndexPtr());
  std::copy(values.begin(), values.end(), m.valuePtr());
  // Structure checks: columns in order, rows sorted, in the lower triangle, diagonal first.
  const int* o = m.outerIndexPtr();
  const int* in = m.innerIndexPtr();
  if (o[0] != 0 || o[n] != nnz) return false;
  for (std::int64_t c = 0; c < n; ++c) {
    if (o[c + 1] <= o[c] || in[o[c]] != c) return false;
    for (int k = o[c] + 1; k < o[c + 1]; ++k)
      if (in[k] <= in[k - 1] || in[k] >= n) return false;
  }
  for (std::int64_t k = 0; k < nnz; ++k)
    if (!std::isfinite(m.valuePtr()[k])) return false;
  if (!perm.empty()) {  // a permutation of the unknowns, and a fill a factor can have
    std::vector<char> seen(static_cast<std::size_t>(n), 0);
    for (const int i : perm)
      if (i < 0 || i >= n || seen[static_cast<std::size_t>(i)]++) return false;
    if (!(fill > 0) || !std::isfinite(fill) || !(nonzeros > 0) || !std::isfinite(nonzeros)) return false;
  }
  m = Sparse(m.transpose());  // stored as the upper triangle
  // The same analysis and numbers as the run that wrote it (under its kept ordering, if it had
  // one); the next factorize() of this run's own matrix analyses its pattern again
  // (deterministically: the same ordering).
  kept_perm_ = std::move(perm);
  kept_fill_ = fill;
  kept_nonzeros_ = nonzeros;
  restoring_ = true;
  analyse(m);
  restoring_ = false;
  in_factor_ = false;  // the next factorisation checks the run's own pattern whole
  added_since_.clear();
  llt_.factorize(m);
  analysed_ = false;
  has_factor_ = llt_.info() == Eigen::Success;
  if (has_factor_) {
    factored_ = std::move(m);
    set_perturbation();
    keep_single();  // the same rounding of the same factor: a restart stays bitwise
  }
  return has_factor_;
}

void SystemMatrix::set_perturbation() {
  // E from the factorised matrix itself (diagonal (1 + ε)·K_ii): the same numbers whether the
  // factor was made here or restored from a checkpoint, so a restart stays bitwise.
  perturbation_.setZero(factored_.rows());
  for (int i : regularised_)
    perturbation_[i] = factored_.valuePtr()[factored_.outerIndexPtr()[i + 1] - 1] * (eps_ / (1 + eps_));  // its diagonal
}

void SystemMatrix::remove_null_part(Eigen::VectorXd& x) const {
  if (regularised_.empty() || !has_factor_) return;
  x -= solve_factored(perturbation_.cwiseProduct(x));
}

// The saved matrix A (no contact springs) holds only the elements' and the effects' terms, while
// the pattern also holds the element pairs the contacts couple, zero in A: on the DDA code's
// static 10 × 10 wall at h = 2 m 4,094 of its 17,600-odd stored entries are nonzero. So
// saved_times() — about nine products a step there, one per CG iteration and per line search —
// runs over A's nonzero entries only, gathered here at each save. Leaving out a term 0·v_i changes
// no sum, not even the sign of a zero (a sum that starts at +0 stays +0 unless a nonzero term
// comes), so the product is the same bit for bit. Measured (callgrind, contact_bench --trace 100
// --sizes 10 --peer --mesh 2, 2026-12-01): the run's instructions 1,818 M → 1,687 M, the
// product's 211 M → 54 M, this gathering 24 M. The largest runs (from single_from_ on) keep no
// second copy of A: their memory counts more than these passes.
void SystemMatrix::save() {
  // The copy keeps room to grow (kScatterRoom), as the matrix's arrays do: a pattern grown by
  // a few entries (most static steps at 930k unknowns) made it a fresh 0.15 GB array each step,
  // faulted in and cleared by the kernel.
  const auto nnz = static_cast<std::size_t>(k_.nonZeros());
  if (saved_.capacity() < nnz) {
    saved_.clear();
    saved_.reserve(nnz + nnz / kScatterRoom + 64);
  }
  saved_.assign(k_.valuePtr(), k_.valuePtr() + nnz);
  const int n = static_cast<int>(k_.rows());
  if (single_from_ > 0 && n >= single_from_) {
    saved_outer_.clear();
    saved_inner_.clear();
    saved_nonzero_.clear();
    return;
  }
  const int* outer = k_.outerIndexPtr();
  const int* inner = k_.innerIndexPtr();
  saved_outer_.resize(static_cast<std::size_t>(n) + 1);
  saved_inner_.resize(saved_.size());
  saved_nonzero_.resize(saved_.size());
  int* to_inner = saved_inner_.data();
  double* to_value = saved_nonzero_.data();
  const double* from = saved_.data();
  int q = 0;
  saved_outer_[0] = 0;
  for (int j = 0; j < n; ++j) {
    const int diagonal = outer[j + 1] - 1;
    for (int p = outer[j]; p < diagonal; ++p) {  // written always, kept (q advanced) when nonzero
      to_inner[q] = inner[p];
      to_value[q] = from[p];
      q += from[p] != 0 ? 1 : 0;
    }
    to_inner[q] = j;  // the diagonal, last, whatever its value (add_upper_times reads it there)
    to_value[q] = from[diagonal];
    ++q;
    saved_outer_[static_cast<std::size_t>(j) + 1] = q;
  }
}

void SystemMatrix::saved_times(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  y.setZero(k_.rows());
  if (saved_outer_.size() == static_cast<std::size_t>(k_.rows()) + 1)
    add_upper_times(static_cast<int>(k_.rows()), saved_outer_.data(), saved_inner_.data(), saved_nonzero_.data(), v,
                    1.0, y);
  else
    add_upper_times(static_cast<int>(k_.rows()), k_.outerIndexPtr(), k_.innerIndexPtr(), saved_.data(), v, 1.0, y);
}

int own_solve_from_environment() {
  const char* v = std::getenv("NMM_OWN_SOLVE");
  return v != nullptr && std::string(v) == "1" ? kOwnSolveUnknowns : 0;
}

void SystemMatrix::keep_single() {
  // Below the lean factorisation's size the double values' spare half stays resident until the
  // pattern changes (build_pattern): the next factorisation of this pattern writes it without
  // the kernel's zeroing of fresh pages; the lean runs need that memory at once.
  own_.clear();
  if (!single_.ready() && single_from_ > 0 && size() >= single_from_)
    single_.take(llt_.factor(), /*keep_spare=*/size() < lean_from_, /*flush_subnormal=*/size() >= lean_from_);
  else if (!single_.ready() && size() < own_from_)
    own_.view(llt_.factor());
}

// cholmod_factorize_p's supernodal LLᵀ of an upper triangle, A1 = tril(P A Pᵀ) by
// cholmod_ptranspose and then cholmod_super_numeric on A1, with A1's layout kept from the
// analysis (permuted_lower.h): a factorisation gathers A's values into it, one pass, where
// cholmod_ptranspose counted, allocated and placed anew. The same A1, so the same factor bit
// for bit (test_system_matrix). Measured (perf over contact_bench --peer --sizes 10 --mesh 2
// --steps 200, both modes, 2026-11-30): cholmod_ptranspose was 1.8 % of the run and 22 % of
// cholmod_factorize_p (super_numeric 6.5 %); docs/performance.md (e).
void SystemMatrix::factorize_in_order() {
  cholmod_factor* l = llt_.factor();
  if (!l || !l->is_super) {  // (Eigen's supernodal wrapper: not met) CHOLMOD's own way
    llt_.factorize(k_);
    return;
  }
  if (!permuted_.ready())  // as cholmod_factorize_p: no permutation under the natural ordering
    permuted_.build(size(), k_.outerIndexPtr(), k_.innerIndexPtr(),
                    l->ordering == CHOLMOD_NATURAL ? nullptr : static_cast<const int*>(l->Perm));
  permuted_.fill(k_.valuePtr());
  cholmod_sparse a1 = permuted_.view();
  llt_.factorize_permuted(&a1);
}

void SystemMatrix::Llt::factorize_permuted(cholmod_sparse* a1) {
  double beta[2] = {0, 0};  // Eigen's shift, as its factorize() hands cholmod_factorize_p
  cholmod_super_numeric(a1, nullptr, beta, this->m_cholmodFactor, &this->cholmod());
  // As Eigen's factorize(): on success CHOLMOD leaves minor at n.
  this->m_info = this->m_cholmodFactor->minor == this->m_cholmodFactor->n ? Eigen::Success : Eigen::NumericalIssue;
  this->m_factorizationIsOk = true;
}

// What cholmod_factorize_p does for a supernodal LLᵀ of an upper triangle — A1 = tril(P A Pᵀ)
// by one permuted transpose, then cholmod_super_numeric on A1 — done here in its two parts, so
// that between them the matrix's own arrays (k_: 18.3 M entries, 0.22 GB at 930k unknowns) and
// the scatter's slots (0.24 GB) are let go: CHOLMOD reads only A1 while it writes the double
// factor (1.7–1.8 GB there). Meanwhile both wait in temporary files (parked_array.h); once the
// factor is rounded to float (half its bytes go back to the system) they are read back, bit for
// bit. Should a file not be written, that part comes back the first way: k_ from A1 by the
// inverse permuted transpose, each column's rows sorted, and the slots placed again in it by a
// search per stored entry. The factor is CHOLMOD's own, the same bits as through
// cholmod_factorize_p (test_system_matrix).
//
// Measured (contact_bench --trace --memory, one thread, 2026-11-30; docs/performance.md (h)):
//   316 × 316 bricks, h = 2 m, 929,502 unknowns: the run's peak (a new pattern's factorisation)
//     3,853 against 4,302 MB; giving back the matrix and the slots 1.5 s of CPU
//     against the numeric factorisation's 4.3–10.4 s; with the parking and the heap's return,
//     step 6's peak 3,680 against 3,855 MB (the same counts)
//   100 × 100, h = 0.5 m, 222,516 unknowns: 0.17 s (transpose 0.05, sort 0.03, slots 0.09)
//     against 0.61 s, for 0.07 GB of a 0.95 GB peak — not worth it there: from
//     kLeanFactorUnknowns on only.
void SystemMatrix::factorize_lean() {
  cholmod_common& c = llt_.cholmod();
  cholmod_factor* l = llt_.factor();
  const int n = size();
  const Sparse& values = k_;
  cholmod_sparse view = Eigen::viewAsCholmod(values.selfadjointView<Eigen::Upper>());
  cholmod_sparse* a1 = cholmod_ptranspose(&view, 2, static_cast<int*>(l->Perm), nullptr, 0, &c);
  if (!a1) {  // no memory for the copy: CHOLMOD's own way (which would need it too)
    llt_.factorize(k_);
    keep_single();
    return;
  }
  // The matrix's arrays and the slots are parked (parked_array.h) and read back once the factor
  // is rounded: the same bytes, where making them again from A1 (the inverse permuted
  // transpose, each column's rows sorted, a search per slot) took 2.8 s of CPU at 930k unknowns
  // against 0.2–0.3 s to write and read their 0.47 GB. Should a file not be written, that part
  // is let go and made again from A1 as before.
  const auto nnz = static_cast<std::size_t>(k_.nonZeros());
  ParkingFile outer_file, rows_file, values_file;
  const bool matrix_parked = outer_file.write(k_.outerIndexPtr(), (static_cast<std::size_t>(n) + 1) * sizeof(int)) &&
                             rows_file.write(k_.innerIndexPtr(), nnz * sizeof(int)) &&
                             values_file.write(k_.valuePtr(), nnz * sizeof(double));
  ParkedArray<std::int32_t> slots;
  const bool slots_parked = slots.park(slots_);
  Sparse().swap(k_);
  std::vector<std::int32_t>().swap(slots_);
  // The heap's free pieces go back to the system too: a new pattern's analysis (METIS's and
  // CHOLMOD's workspace) leaves about 0.1 GB of them held, resident under the double factor
  // (docs/performance.md (h)). Those pages fault in again when the heap reuses them.
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
  // Nothing reads the saved values without springs or the groups' unknowns until the factor is
  // rounded: parked in a temporary file meanwhile (parked_array.h), 0.19 GB at 930k unknowns.
  ParkedArray<double> saved;
  ParkedArray<int> dofs;
  saved.park(saved_);
  dofs.park(group_dofs_);
  memory_mark("matrix let go");
  const auto matrix_back = [&]() {
    k_ = Sparse(n, n);
    k_.resizeNonZeros(static_cast<Eigen::Index>(nnz));
    outer_file.read(k_.outerIndexPtr());
    rows_file.read(k_.innerIndexPtr());
    values_file.read(k_.valuePtr());
  };
  try {
    {
      const FlushSubnormals flush;
      llt_.factorize_permuted(a1);
    }
    memory_mark("numeric factorisation");
    // (keep_single() reads size(): k_ is let go)
    if (llt_.info() == Eigen::Success) single_.take(l, /*keep_spare=*/false, /*flush_subnormal=*/true);
  } catch (...) {
    cholmod_free_sparse(&a1, &c);
    saved.unpark(saved_);
    dofs.unpark(group_dofs_);
    if (matrix_parked) matrix_back();
    slots.unpark(slots_);
    throw;
  }
  memory_mark("rounded");
  saved.unpark(saved_);
  dofs.unpark(group_dofs_);
  if (matrix_parked) {
    cholmod_free_sparse(&a1, &c);
    matrix_back();
    memory_mark("matrix read back");
  } else {
    // k_ = A1(q, q)ᵀ with q the inverse permutation: the upper triangle of A again.
    std::vector<int> inverse(static_cast<std::size_t>(n));
    const int* perm = static_cast<const int*>(l->Perm);
    for (int k = 0; k < n; ++k) inverse[static_cast<std::size_t>(perm[k])] = k;
    cholmod_sparse* back = cholmod_ptranspose(a1, 2, inverse.data(), nullptr, 0, &c);
    cholmod_free_sparse(&a1, &c);
    if (!back) throw std::bad_alloc();
    const auto* bp = static_cast<const int*>(back->p);
    k_ = Sparse(n, n);
    k_.resizeNonZeros(static_cast<Eigen::Index>(bp[n]));
    std::copy(bp, bp + n + 1, k_.outerIndexPtr());
    std::copy(static_cast<const int*>(back->i), static_cast<const int*>(back->i) + bp[n], k_.innerIndexPtr());
    std::copy(static_cast<const double*>(back->x), static_cast<const double*>(back->x) + bp[n], k_.valuePtr());
    cholmod_free_sparse(&back, &c);
    memory_mark("matrix transposed");
    // A permuted symmetric transpose leaves each column's rows in the order it met them: sorted
    // here (a column holds a few dozen), so that every entry is where it was.
    int* rows = k_.innerIndexPtr();
    double* vals = k_.valuePtr();
    for (int col = 0; col < n; ++col)
      for (int p = k_.outerIndexPtr()[col] + 1; p < k_.outerIndexPtr()[col + 1]; ++p)
        for (int q = p; q > k_.outerIndexPtr()[col] && rows[q - 1] > rows[q]; --q) {
          std::swap(rows[q - 1], rows[q]);
          std::swap(vals[q - 1], vals[q]);
        }
    memory_mark("rows sorted");
  }
  if (slots_parked)
    slots.unpark(slots_);
  else
    place_slots();
  memory_mark("matrix back");
}

void SystemMatrix::place_slots() {
  const int* outer = k_.outerIndexPtr();
  const int* inner = k_.innerIndexPtr();
  const std::size_t ng = group_offsets_.size() - 1;
  slots_.resize(static_cast<std::size_t>(slot_offset_[ng]));
  for (std::size_t g = 0; g < ng; ++g) {
    std::int32_t* out = slots_.data() + slot_offset_[g];
    const int m = group_offsets_[g + 1] - group_offsets_[g];
    const int* d = group_dofs_.data() + group_offsets_[g];
    for (int jj = 0; jj < m; ++jj)
      for (int ii = 0; ii < m; ++ii)
        if (d[ii] >= d[jj]) {  // row d[jj] of column d[ii], as build_pattern placed it
          const int* first = inner + outer[d[ii]];
          const int* last = inner + outer[d[ii] + 1];
          *out++ = static_cast<std::int32_t>(std::lower_bound(first, last, d[jj]) - inner);
        }
  }
}

Eigen::VectorXd SystemMatrix::solve_unrefined(const Eigen::VectorXd& b) const {
  Eigen::VectorXd x;
  solve_unrefined(b, x);
  return x;
}

void SystemMatrix::solve_unrefined(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  if (own_.ready()) {
    own_.solve(b, x);
    return;
  }
  if (!single_.ready()) {
    x = llt_.solve(b);
    return;
  }
  single_.solve(b, x);
}

Eigen::VectorXd SystemMatrix::solve_factored(const Eigen::VectorXd& b) const {
  if (own_.ready()) {
    Eigen::VectorXd x;
    own_.solve(b, x);
    return x;
  }
  if (!single_.ready()) return llt_.solve(b);
  // Iterative refinement of the single-precision factor's solve against the factorised matrix,
  // in double, until the residual is at round-off (1e-13 of b) or stops halving. Each pass
  // divides the error by about 1/(u·κ) (single_factor.h).
  Eigen::VectorXd x, dx;
  single_.solve(b, x);
  const int n = static_cast<int>(factored_.rows());
  const double bn = b.norm();
  double prev = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 20; ++it) {
    Eigen::VectorXd r = b;
    add_upper_times(n, factored_.outerIndexPtr(), factored_.innerIndexPtr(), factored_.valuePtr(), x, -1.0, r);
    const double rn = r.norm();
    if (!(rn > 1e-13 * bn) || !(rn < 0.5 * prev)) break;
    prev = rn;
    single_.solve(r, dx);
    x += dx;
    ++single_refinements_;
  }
  return x;
}

Eigen::VectorXd SystemMatrix::solve(const Eigen::VectorXd& b) {
  Eigen::VectorXd x = solve_factored(b);
  refinements_ = 0;
  if (regularised_.empty()) return x;
  // Iterative refinement against the unperturbed K, until the residual stops falling or is at
  // round-off (1e-13 of b); a handful of passes (the contraction is ε/λ_min per pass).
  const double bn = b.norm();
  double prev = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 20; ++it) {
    Eigen::VectorXd r = b;
    add_upper_times(static_cast<int>(k_.rows()), k_.outerIndexPtr(), k_.innerIndexPtr(), k_.valuePtr(), x, -1.0, r);
    const double rn = r.norm();
    if (!(rn > 1e-13 * bn) || !(rn < 0.5 * prev)) break;
    prev = rn;
    x += solve_factored(r);
    ++refinements_;
  }
  return x;
}

}  // namespace nmm::solve
