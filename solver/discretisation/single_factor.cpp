// The triangular solves of a supernodal factor in single precision (single_factor.h).
//
// CHOLMOD's supernodal layout: supernode s holds the columns k1 = super[s] .. k2 = super[s+1] − 1
// of L (in the permuted order, L Lᵀ = Pᵀ A P with PermA's rows Perm[k]); its rows are
// Ls[pi[s] .. pi[s+1]), the first k2 − k1 of them k1 .. k2 − 1; its values a dense column-major
// block of those rows × its columns at Lx[px[s]], lower triangular on top.
//   forward,  L y = c:  per supernode, w = (c over its rows, 0 below its columns), then column by
//                       column w_j /= L_jj, w_i −= L_ij w_j (i > j); scatter w's lower rows back
//                       as additions (they are the other supernodes' updates)
//   backward, Lᵀ z = y: supernodes in reverse, w = z over its rows, then column by column from
//                       the last, w_j = (w_j − Σ_{i>j} L_ij w_i) / L_jj
// Each value of L is read once per pass, in storage order (the passes are memory-bound). The
// division by L_jj is a product with 1/L_jj, kept in double beside the factor (8 bytes per
// unknown): a division's latency sat on the passes' dependency chain, one per column of every
// small supernode (10 % of the solve's samples under `perf` on the 10,000-block wall).
#include "solver/discretisation/single_factor.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace nmm::solve {

namespace {
// The passes take a supernode's columns four at a time: each row's update (forward) or each
// row's term of the four sums (backward) then reads w_i once for four values of L. Two kernel
// sets, the same arithmetic: SSE2 (every x86-64) takes two rows at once, AVX (chosen at run time
// where the CPU has it) four; the products and sums are the same in the same order (no fused
// multiply-add; a dot product's four partial sums by row mod 4 in both), so either gives the same
// bits. AVX halves the instructions per value read, and the passes, bound by the memory, keep
// more loads in flight: a solve pair with the 10,000-block wall's factor at h = 0.5 m (222,516
// unknowns, 29.2 M factor nonzeros, after 3 static steps; one thread, load average 20) took
// 37.7 ms with AVX against 46.6 ms with SSE2 and 44.8 ms for the SSE2 passes that divided by
// the diagonal (docs/notes/2026-11-scale.md, 2026-11-30 morning).

// a_k[i] as doubles, k = 0..3, rows i, i + 1 (SSE2) or i .. i + 3 (AVX).
#if defined(__SSE2__)
inline __m128d two(const float* a) {
  return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(a))));
}
inline __m128d two(const double* a) { return _mm_loadu_pd(a); }
#endif

struct Sse2 {
  // w_i −= (a0[i]·c0 + a1[i]·c1) + (a2[i]·c2 + a3[i]·c3) over rows i in [from, to).
  template <class T>
  static void update4(const T* a0, const T* a1, const T* a2, const T* a3, const double* c,
                      double* w, int from, int to) {
    int i = from;
#if defined(__SSE2__)
    const __m128d c0 = _mm_set1_pd(c[0]), c1 = _mm_set1_pd(c[1]), c2 = _mm_set1_pd(c[2]), c3 = _mm_set1_pd(c[3]);
    for (; i + 2 <= to; i += 2) {
      const __m128d s = _mm_add_pd(_mm_add_pd(_mm_mul_pd(two(a0 + i), c0), _mm_mul_pd(two(a1 + i), c1)),
                                   _mm_add_pd(_mm_mul_pd(two(a2 + i), c2), _mm_mul_pd(two(a3 + i), c3)));
      _mm_storeu_pd(w + i, _mm_sub_pd(_mm_loadu_pd(w + i), s));
    }
#endif
    for (; i < to; ++i)
      w[i] -= (static_cast<double>(a0[i]) * c[0] + static_cast<double>(a1[i]) * c[1]) +
              (static_cast<double>(a2[i]) * c[2] + static_cast<double>(a3[i]) * c[3]);
  }
  // d_k = Σ a_k[i]·w_i over rows i in [from, to), k = 0..3: partial sums p_k,m over the rows
  // i − from ≡ m (mod 4) of the full quadruples, d_k = ((p_k,0 + p_k,2) + (p_k,1 + p_k,3)) + the
  // rest in row order.
  template <class T>
  static void dot4(const T* a0, const T* a1, const T* a2, const T* a3, const double* w, int from,
                   int to, double* d) {
    int i = from;
    double s[4][4] = {};
#if defined(__SSE2__)
    __m128d l0 = _mm_setzero_pd(), l1 = l0, l2 = l0, l3 = l0;  // rows m = 0, 1 of each quadruple
    __m128d h0 = l0, h1 = l0, h2 = l0, h3 = l0;                // rows m = 2, 3
    for (; i + 4 <= to; i += 4) {
      const __m128d wl = _mm_loadu_pd(w + i), wh = _mm_loadu_pd(w + i + 2);
      l0 = _mm_add_pd(l0, _mm_mul_pd(two(a0 + i), wl));
      h0 = _mm_add_pd(h0, _mm_mul_pd(two(a0 + i + 2), wh));
      l1 = _mm_add_pd(l1, _mm_mul_pd(two(a1 + i), wl));
      h1 = _mm_add_pd(h1, _mm_mul_pd(two(a1 + i + 2), wh));
      l2 = _mm_add_pd(l2, _mm_mul_pd(two(a2 + i), wl));
      h2 = _mm_add_pd(h2, _mm_mul_pd(two(a2 + i + 2), wh));
      l3 = _mm_add_pd(l3, _mm_mul_pd(two(a3 + i), wl));
      h3 = _mm_add_pd(h3, _mm_mul_pd(two(a3 + i + 2), wh));
    }
    _mm_storeu_pd(s[0], l0);
    _mm_storeu_pd(s[0] + 2, h0);
    _mm_storeu_pd(s[1], l1);
    _mm_storeu_pd(s[1] + 2, h1);
    _mm_storeu_pd(s[2], l2);
    _mm_storeu_pd(s[2] + 2, h2);
    _mm_storeu_pd(s[3], l3);
    _mm_storeu_pd(s[3] + 2, h3);
#else
    const T* a[4] = {a0, a1, a2, a3};
    for (; i + 4 <= to; i += 4)
      for (int k = 0; k < 4; ++k)
        for (int m = 0; m < 4; ++m) s[k][m] += static_cast<double>(a[k][i + m]) * w[i + m];
#endif
    finish(a0, a1, a2, a3, w, i, to, s, d);
  }
  template <class T>
  static void finish(const T* a0, const T* a1, const T* a2, const T* a3, const double* w, int i,
                     int to, const double (*s)[4], double* d) {
    const T* a[4] = {a0, a1, a2, a3};
    for (int k = 0; k < 4; ++k) {
      double v = (s[k][0] + s[k][2]) + (s[k][1] + s[k][3]);
      for (int r = i; r < to; ++r) v += static_cast<double>(a[k][r]) * w[r];
      d[k] = v;
    }
  }
};

#if defined(__x86_64__) && defined(__GNUC__)
#define NMM_SINGLE_FACTOR_AVX 1
#define NMM_AVX __attribute__((target("avx")))
struct Avx {
  NMM_AVX static __m256d four(const float* a) { return _mm256_cvtps_pd(_mm_loadu_ps(a)); }
  NMM_AVX static __m256d four(const double* a) { return _mm256_loadu_pd(a); }
  template <class T>
  NMM_AVX static void update4(const T* a0, const T* a1, const T* a2, const T* a3, const double* c,
                              double* w, int from, int to) {
    int i = from;
    const __m256d c0 = _mm256_set1_pd(c[0]), c1 = _mm256_set1_pd(c[1]), c2 = _mm256_set1_pd(c[2]),
                  c3 = _mm256_set1_pd(c[3]);
    for (; i + 4 <= to; i += 4) {
      const __m256d s =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(four(a0 + i), c0), _mm256_mul_pd(four(a1 + i), c1)),
                        _mm256_add_pd(_mm256_mul_pd(four(a2 + i), c2), _mm256_mul_pd(four(a3 + i), c3)));
      _mm256_storeu_pd(w + i, _mm256_sub_pd(_mm256_loadu_pd(w + i), s));
    }
    for (; i < to; ++i)
      w[i] -= (static_cast<double>(a0[i]) * c[0] + static_cast<double>(a1[i]) * c[1]) +
              (static_cast<double>(a2[i]) * c[2] + static_cast<double>(a3[i]) * c[3]);
  }
  template <class T>
  NMM_AVX static void dot4(const T* a0, const T* a1, const T* a2, const T* a3, const double* w,
                           int from, int to, double* d) {
    int i = from;
    __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0, s3 = s0;
    for (; i + 4 <= to; i += 4) {
      const __m256d wi = _mm256_loadu_pd(w + i);
      s0 = _mm256_add_pd(s0, _mm256_mul_pd(four(a0 + i), wi));
      s1 = _mm256_add_pd(s1, _mm256_mul_pd(four(a1 + i), wi));
      s2 = _mm256_add_pd(s2, _mm256_mul_pd(four(a2 + i), wi));
      s3 = _mm256_add_pd(s3, _mm256_mul_pd(four(a3 + i), wi));
    }
    double s[4][4];
    _mm256_storeu_pd(s[0], s0);
    _mm256_storeu_pd(s[1], s1);
    _mm256_storeu_pd(s[2], s2);
    _mm256_storeu_pd(s[3], s3);
    Sse2::finish(a0, a1, a2, a3, w, i, to, s, d);
  }
};
#endif

// The forward and backward passes (the file's top), with kernel set K; x = (L̃ L̃ᵀ)⁻¹ b.
// inv[k]: 1 / L_kk of column k, in double (a product instead of a division on the passes'
// dependency chains).
template <class K, class T>
inline void passes(const cholmod_factor* l, const T* x_, const double* inv, const double* b, double* yy,
                   double* ww, double* out) {
  const int n = static_cast<int>(l->n);
  const int* super = static_cast<const int*>(l->super);
  const int* pi = static_cast<const int*>(l->pi);
  const int* px = static_cast<const int*>(l->px);
  const int* ls = static_cast<const int*>(l->s);
  const int* perm = static_cast<const int*>(l->Perm);
  const auto nsuper = static_cast<int>(l->nsuper);
  for (int k = 0; k < n; ++k) yy[k] = b[perm ? perm[k] : k];
  for (int s = 0; s < nsuper; ++s) {
    const int k1 = super[s], cols = super[s + 1] - k1, rows = pi[s + 1] - pi[s];
    const int* r = ls + pi[s];
    const T* a = x_ + px[s];
    const double* iv = inv + k1;
    for (int i = 0; i < cols; ++i) ww[i] = yy[k1 + i];
    for (int i = cols; i < rows; ++i) ww[i] = 0.0;
    int j = 0;
    for (; j + 4 <= cols; j += 4) {  // four columns: their triangle, then the rows below it
      const T* c = a + static_cast<std::ptrdiff_t>(j) * rows;
      for (int q = 0; q < 4; ++q) {
        const T* cq = c + static_cast<std::ptrdiff_t>(q) * rows;
        ww[j + q] *= iv[j + q];
        for (int i = j + q + 1; i < j + 4; ++i) ww[i] -= static_cast<double>(cq[i]) * ww[j + q];
      }
      K::update4(c, c + rows, c + 2 * rows, c + 3 * rows, ww + j, ww, j + 4, rows);
    }
    for (; j < cols; ++j) {
      const T* c = a + static_cast<std::ptrdiff_t>(j) * rows;
      const double wj = ww[j] * iv[j];
      ww[j] = wj;
      for (int i = j + 1; i < rows; ++i) ww[i] -= static_cast<double>(c[i]) * wj;
    }
    for (int i = 0; i < cols; ++i) yy[k1 + i] = ww[i];
    for (int i = cols; i < rows; ++i) yy[r[i]] += ww[i];
  }
  for (int s = nsuper - 1; s >= 0; --s) {
    const int k1 = super[s], cols = super[s + 1] - k1, rows = pi[s + 1] - pi[s];
    const int* r = ls + pi[s];
    const double* iv = inv + k1;
    for (int i = 0; i < cols; ++i) ww[i] = yy[k1 + i];
    for (int i = cols; i < rows; ++i) ww[i] = yy[r[i]];
    const T* a = x_ + px[s];
    int j = cols;
    for (; j >= 4; j -= 4) {  // columns j − 4 .. j − 1: the rows below them, then their triangle
      const int j0 = j - 4;
      const T* c = a + static_cast<std::ptrdiff_t>(j0) * rows;
      double d[4];
      K::dot4(c, c + rows, c + 2 * rows, c + 3 * rows, ww, j, rows, d);
      for (int q = 3; q >= 0; --q) {
        const T* cq = c + static_cast<std::ptrdiff_t>(q) * rows;
        double v = ww[j0 + q] - d[q];
        for (int i = j0 + q + 1; i < j; ++i) v -= static_cast<double>(cq[i]) * ww[i];
        ww[j0 + q] = v * iv[j0 + q];
      }
    }
    for (--j; j >= 0; --j) {
      const T* c = a + static_cast<std::ptrdiff_t>(j) * rows;
      double v = ww[j];
      for (int i = j + 1; i < rows; ++i) v -= static_cast<double>(c[i]) * ww[i];
      ww[j] = v * iv[j];
    }
    for (int i = 0; i < cols; ++i) yy[k1 + i] = ww[i];
  }
  for (int k = 0; k < n; ++k) out[perm ? perm[k] : k] = yy[k];
}

template <class T>
void passes_sse2(const cholmod_factor* l, const T* x, const double* inv, const double* b, double* y, double* w,
                 double* out) {
  passes<Sse2, T>(l, x, inv, b, y, w, out);
}
#if defined(NMM_SINGLE_FACTOR_AVX)
// flatten: passes<Avx> and its kernels compiled into this one AVX function.
template <class T>
__attribute__((target("avx"), flatten)) void passes_avx(const cholmod_factor* l, const T* x, const double* inv,
                                                        const double* b, double* y, double* w, double* out) {
  passes<Avx, T>(l, x, inv, b, y, w, out);
}
bool cpu_has_avx() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx");
}
std::atomic<bool> g_avx{cpu_has_avx()};
#else
std::atomic<bool> g_avx{false};
#endif

// inv[k] = 1 / L_kk for every column of the supernodal factor l with values x; returns the
// tallest supernode's rows (the passes' work vector).
template <class T>
int inverse_diagonal(const cholmod_factor* l, const T* x, std::vector<double>& inv) {
  const int* pi = static_cast<const int*>(l->pi);
  const int* super = static_cast<const int*>(l->super);
  const int* px = static_cast<const int*>(l->px);
  int max_rows = 0;
  inv.resize(l->n);
  for (std::size_t s = 0; s < l->nsuper; ++s) {
    const int rows = pi[s + 1] - pi[s];
    max_rows = std::max(max_rows, rows);
    for (int j = 0; j < super[s + 1] - super[s]; ++j)
      inv[static_cast<std::size_t>(super[s] + j)] =
          1.0 / static_cast<double>(x[px[s] + static_cast<std::ptrdiff_t>(j) * (rows + 1)]);
  }
  return max_rows;
}

// x = (L Lᵀ)⁻¹ b by the passes with l's values `values`, AVX where chosen.
template <class T>
void solve_with(const cholmod_factor* l, const T* values, const std::vector<double>& inv, int max_rows,
                const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const auto n = static_cast<Eigen::Index>(l->n);
  thread_local std::vector<double> y, w;
  y.resize(static_cast<std::size_t>(n));
  w.resize(static_cast<std::size_t>(max_rows));
  x.resize(n);
#if defined(NMM_SINGLE_FACTOR_AVX)
  if (g_avx.load(std::memory_order_relaxed)) {
    passes_avx(l, values, inv.data(), b.data(), y.data(), w.data(), x.data());
    return;
  }
#endif
  passes_sse2(l, values, inv.data(), b.data(), y.data(), w.data(), x.data());
}
}  // namespace

bool SingleFactor::use_avx(bool on) {
#if defined(NMM_SINGLE_FACTOR_AVX)
  g_avx = on && cpu_has_avx();
#else
  (void)on;
#endif
  return g_avx;
}

bool SingleFactor::take(cholmod_factor* l, bool keep_spare, bool flush_subnormal) {
  clear();
  if (!l || !l->is_super || !l->is_ll || l->xtype != CHOLMOD_REAL || l->itype != CHOLMOD_INT || !l->x) return false;
  const std::size_t size = l->xsize;
  auto* bytes = static_cast<unsigned char*>(l->x);
  // In chunks, through byte copies (the array is read as double and written as float): chunk c's
  // floats (bytes 4·kChunk·c ..) go where chunk c's doubles (8·kChunk·c ..) or earlier ones were,
  // all read by then, and never on a later chunk's.
  constexpr std::size_t kChunk = 1024;
  double in[kChunk];
  float out[kChunk];
  for (std::size_t k = 0; k < size; k += kChunk) {
    const std::size_t m = std::min(kChunk, size - k);
    std::memcpy(in, bytes + k * sizeof(double), m * sizeof(double));
    if (flush_subnormal) {
      for (std::size_t i = 0; i < m; ++i)
        out[i] = std::fabs(in[i]) < static_cast<double>(std::numeric_limits<float>::min()) ? 0.0f
                                                                                           : static_cast<float>(in[i]);
    } else {
      for (std::size_t i = 0; i < m; ++i) out[i] = static_cast<float>(in[i]);
    }
    std::memcpy(bytes + k * sizeof(float), out, m * sizeof(float));
  }
  const auto* to = reinterpret_cast<const float*>(bytes);
  const auto* from = reinterpret_cast<const double*>(bytes);
#if defined(__linux__)
  // The pages wholly inside the second half go back to the system (zero-filled if touched
  // again: CHOLMOD's next factorisation writes every value first), now or at release_spare().
  // Kept, a refactorisation of the same pattern writes resident pages: on the 10,000-block
  // wall at h = 0.5 m (222,516 unknowns, 117 MB of such pages) the kernel's zeroing of them
  // was 4–7 % of a step's CPU (docs/notes/2026-11-scale.md).
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto begin = reinterpret_cast<std::uintptr_t>(to + size), end = reinterpret_cast<std::uintptr_t>(from + size);
  const std::uintptr_t first = (begin + page - 1) / page * page, last = end / page * page;
  if (last > first) {
    spare_begin_ = first;
    spare_end_ = last;
    if (!keep_spare) release_spare();
  }
  // CHOLMOD's next factorisation touches them again: in 2 MB pages, 512 times fewer faults —
  // where the spare half stays resident (keep_spare). Where it went back at once (the lean
  // runs), the refactorisation faulted its 0.9 GB in again as 2 MB pages, which the kernel
  // zeroes and, on a busy machine, first compacts: at 930k unknowns 1.8–2.4 s of the
  // kernel's page clearing per refactorisation against 1.1 s for a whole new 1.8 GB factor in
  // 4 KB pages (perf, docs/notes/2026-11-scale.md, 2026-12-01): those stay 4 KB pages.
  if (keep_spare) {
    constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
    const auto start = reinterpret_cast<std::uintptr_t>(bytes);
    const std::uintptr_t huge_first = (start + kHuge - 1) / kHuge * kHuge, huge_last = end / kHuge * kHuge;
    if (huge_last > huge_first) madvise(reinterpret_cast<void*>(huge_first), huge_last - huge_first, MADV_HUGEPAGE);
  }
#endif
  max_rows_ = inverse_diagonal(l, to, inv_);
  x_ = to;
  l_ = l;
  return true;
}

void SingleFactor::release_spare() {
#if defined(__linux__)
  if (spare_end_ > spare_begin_)
    madvise(reinterpret_cast<void*>(spare_begin_), spare_end_ - spare_begin_, MADV_DONTNEED);
#endif
  spare_begin_ = spare_end_ = 0;
}

void SingleFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  solve_with(l_, x_, inv_, max_rows_, b, x);
}

std::size_t SingleFactor::bytes() const {
  if (!l_) return 0;
  return l_->xsize * sizeof(float) + l_->ssize * sizeof(int) + (4 * l_->n + 4 * l_->nsuper) * sizeof(int) +
         inv_.size() * sizeof(double);
}

bool DoubleFactor::view(const cholmod_factor* l) {
  clear();
  if (!l || !l->is_super || !l->is_ll || l->xtype != CHOLMOD_REAL || l->itype != CHOLMOD_INT || !l->x ||
      l->minor != l->n)
    return false;
  max_rows_ = inverse_diagonal(l, static_cast<const double*>(l->x), inv_);
  l_ = l;
  return true;
}

void DoubleFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  solve_with(l_, static_cast<const double*>(l_->x), inv_, max_rows_, b, x);
}

}  // namespace nmm::solve
