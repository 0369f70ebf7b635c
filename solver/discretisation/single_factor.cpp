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
// Each value of L is read once per pass, in storage order (the passes are memory-bound).
#include "solver/discretisation/single_factor.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace nmm::solve {

namespace {
// The passes take a supernode's columns four at a time: each row's update (forward) or each
// row's term of the four sums (backward) then reads w_i once for four values of L. SSE2 (every
// x86-64) does two rows at once; the sums are split into the same partial sums either way, in a
// fixed order: the same bits on every machine of the kind.

// w_i −= Σ_k a_k[i]·c_k over rows i in [from, to), k = 0..3.
void update4(const float* a0, const float* a1, const float* a2, const float* a3, const double* c, double* w,
             int from, int to) {
  int i = from;
#if defined(__SSE2__)
  const __m128d c0 = _mm_set1_pd(c[0]), c1 = _mm_set1_pd(c[1]), c2 = _mm_set1_pd(c[2]), c3 = _mm_set1_pd(c[3]);
  const auto two = [](const float* a) {  // a[0], a[1] as doubles
    return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(a))));
  };
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

// d_k = Σ a_k[i]·w_i over rows i in [from, to), k = 0..3.
void dot4(const float* a0, const float* a1, const float* a2, const float* a3, const double* w, int from, int to,
          double* d) {
  int i = from;
  double s[4][2] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
#if defined(__SSE2__)
  __m128d s0 = _mm_setzero_pd(), s1 = s0, s2 = s0, s3 = s0;
  const auto two = [](const float* a) {
    return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(a))));
  };
  for (; i + 2 <= to; i += 2) {
    const __m128d wi = _mm_loadu_pd(w + i);
    s0 = _mm_add_pd(s0, _mm_mul_pd(two(a0 + i), wi));
    s1 = _mm_add_pd(s1, _mm_mul_pd(two(a1 + i), wi));
    s2 = _mm_add_pd(s2, _mm_mul_pd(two(a2 + i), wi));
    s3 = _mm_add_pd(s3, _mm_mul_pd(two(a3 + i), wi));
  }
  _mm_storeu_pd(s[0], s0);
  _mm_storeu_pd(s[1], s1);
  _mm_storeu_pd(s[2], s2);
  _mm_storeu_pd(s[3], s3);
#else
  for (; i + 2 <= to; i += 2) {
    const float* a[4] = {a0, a1, a2, a3};
    for (int k = 0; k < 4; ++k) {
      s[k][0] += static_cast<double>(a[k][i]) * w[i];
      s[k][1] += static_cast<double>(a[k][i + 1]) * w[i + 1];
    }
  }
#endif
  if (i < to) {
    s[0][0] += static_cast<double>(a0[i]) * w[i];
    s[1][0] += static_cast<double>(a1[i]) * w[i];
    s[2][0] += static_cast<double>(a2[i]) * w[i];
    s[3][0] += static_cast<double>(a3[i]) * w[i];
  }
  for (int k = 0; k < 4; ++k) d[k] = s[k][0] + s[k][1];
}
}  // namespace

bool SingleFactor::take(cholmod_factor* l) {
  l_ = nullptr;
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
    for (std::size_t i = 0; i < m; ++i) out[i] = static_cast<float>(in[i]);
    std::memcpy(bytes + k * sizeof(float), out, m * sizeof(float));
  }
  const auto* to = reinterpret_cast<const float*>(bytes);
  const auto* from = reinterpret_cast<const double*>(bytes);
#if defined(__linux__)
  // The pages wholly inside the second half go back to the system (zero-filled if touched
  // again: CHOLMOD's next factorisation writes every value first).
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto begin = reinterpret_cast<std::uintptr_t>(to + size), end = reinterpret_cast<std::uintptr_t>(from + size);
  const std::uintptr_t first = (begin + page - 1) / page * page, last = end / page * page;
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
  // CHOLMOD's next factorisation touches them again: in 2 MB pages, 512 times fewer faults.
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
  const auto start = reinterpret_cast<std::uintptr_t>(bytes);
  const std::uintptr_t huge_first = (start + kHuge - 1) / kHuge * kHuge, huge_last = end / kHuge * kHuge;
  if (huge_last > huge_first) madvise(reinterpret_cast<void*>(huge_first), huge_last - huge_first, MADV_HUGEPAGE);
#endif
  const int* pi = static_cast<const int*>(l->pi);
  max_rows_ = 0;
  for (std::size_t s = 0; s < l->nsuper; ++s) max_rows_ = std::max(max_rows_, pi[s + 1] - pi[s]);
  x_ = to;
  l_ = l;
  return true;
}

void SingleFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const auto n = static_cast<Eigen::Index>(l_->n);
  const int* super = static_cast<const int*>(l_->super);
  const int* pi = static_cast<const int*>(l_->pi);
  const int* px = static_cast<const int*>(l_->px);
  const int* ls = static_cast<const int*>(l_->s);
  const int* perm = static_cast<const int*>(l_->Perm);
  const auto nsuper = static_cast<int>(l_->nsuper);
  thread_local std::vector<double> y, w;
  y.resize(static_cast<std::size_t>(n));
  w.resize(static_cast<std::size_t>(max_rows_));
  for (Eigen::Index k = 0; k < n; ++k) y[static_cast<std::size_t>(k)] = b[perm ? perm[k] : k];
  double* yy = y.data();
  double* ww = w.data();
  for (int s = 0; s < nsuper; ++s) {
    const int k1 = super[s], cols = super[s + 1] - k1, rows = pi[s + 1] - pi[s];
    const int* r = ls + pi[s];
    const float* a = x_ + px[s];
    std::copy(yy + k1, yy + k1 + cols, ww);
    std::fill(ww + cols, ww + rows, 0.0);
    int j = 0;
    for (; j + 4 <= cols; j += 4) {  // four columns: their triangle, then the rows below it
      const float* c = a + static_cast<std::ptrdiff_t>(j) * rows;
      for (int q = 0; q < 4; ++q) {
        const float* cq = c + static_cast<std::ptrdiff_t>(q) * rows;
        ww[j + q] /= static_cast<double>(cq[j + q]);
        for (int i = j + q + 1; i < j + 4; ++i) ww[i] -= static_cast<double>(cq[i]) * ww[j + q];
      }
      update4(c, c + rows, c + 2 * rows, c + 3 * rows, ww + j, ww, j + 4, rows);
    }
    for (; j < cols; ++j) {
      const float* c = a + static_cast<std::ptrdiff_t>(j) * rows;
      const double wj = ww[j] / static_cast<double>(c[j]);
      ww[j] = wj;
      for (int i = j + 1; i < rows; ++i) ww[i] -= static_cast<double>(c[i]) * wj;
    }
    std::copy(ww, ww + cols, yy + k1);
    for (int i = cols; i < rows; ++i) yy[r[i]] += ww[i];
  }
  for (int s = nsuper - 1; s >= 0; --s) {
    const int k1 = super[s], cols = super[s + 1] - k1, rows = pi[s + 1] - pi[s];
    const int* r = ls + pi[s];
    std::copy(yy + k1, yy + k1 + cols, ww);
    for (int i = cols; i < rows; ++i) ww[i] = yy[r[i]];
    const float* a = x_ + px[s];
    int j = cols;
    for (; j >= 4; j -= 4) {  // columns j − 4 .. j − 1: the rows below them, then their triangle
      const int j0 = j - 4;
      const float* c = a + static_cast<std::ptrdiff_t>(j0) * rows;
      double d[4];
      dot4(c, c + rows, c + 2 * rows, c + 3 * rows, ww, j, rows, d);
      for (int q = 3; q >= 0; --q) {
        const float* cq = c + static_cast<std::ptrdiff_t>(q) * rows;
        double v = ww[j0 + q] - d[q];
        for (int i = j0 + q + 1; i < j; ++i) v -= static_cast<double>(cq[i]) * ww[i];
        ww[j0 + q] = v / static_cast<double>(cq[j0 + q]);
      }
    }
    for (--j; j >= 0; --j) {
      const float* c = a + static_cast<std::ptrdiff_t>(j) * rows;
      double v = ww[j];
      for (int i = j + 1; i < rows; ++i) v -= static_cast<double>(c[i]) * ww[i];
      ww[j] = v / static_cast<double>(c[j]);
    }
    std::copy(ww, ww + cols, yy + k1);
  }
  x.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) x[perm ? perm[k] : k] = y[static_cast<std::size_t>(k)];
}

std::size_t SingleFactor::bytes() const {
  if (!l_) return 0;
  return l_->xsize * sizeof(float) + l_->ssize * sizeof(int) + (4 * l_->n + 4 * l_->nsuper) * sizeof(int);
}

}  // namespace nmm::solve
