#include "solver/discretisation/blas_info.h"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstring>

#include "solver/discretisation/loaded_symbol.h"

namespace nmm::solve {

namespace {
// OpenBLAS's kernel sets (DYNAMIC_ARCH, x86-64) whose level-3 kernels use AVX2 and FMA.
constexpr const char* kAvx2Cores[] = {"haswell", "zen", "skylakex", "cooperlake", "sapphirerapids"};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool cpu_has_avx2() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}
}  // namespace

BlasInfo blas_info() {
  BlasInfo b;
  using Text = char* (*)();
  using Count = int (*)();
  const auto corename = reinterpret_cast<Text>(loaded_symbol("openblas_get_corename"));
  const auto config = reinterpret_cast<Text>(loaded_symbol("openblas_get_config"));
  const auto threads = reinterpret_cast<Count>(loaded_symbol("openblas_get_num_threads"));
  b.cpu_avx2 = cpu_has_avx2();
  if (corename && config) {
    b.core = corename();
    b.config = config();
    if (threads) b.threads = threads();
    // "OpenBLAS 0.3.21 NO_LAPACKE DYNAMIC_ARCH ...": the library is its first two words.
    const std::size_t first = b.config.find(' ');
    const std::size_t second = first == std::string::npos ? first : b.config.find(' ', first + 1);
    b.library = b.config.substr(0, second);
    const std::string core = lower(b.core);
    for (const char* c : kAvx2Cores) b.avx2_kernels |= core == c;
    return b;
  }
  // Another BLAS: name the shared object that holds dgemm_.
  Dl_info where{};
  void* dgemm = loaded_symbol("dgemm_");
  b.library = dgemm && dladdr(dgemm, &where) && where.dli_fname ? where.dli_fname : "unknown";
  return b;
}

std::string blas_line(const BlasInfo& b) {
  if (b.core.empty()) return "BLAS: " + b.library;
  return "BLAS: " + b.library + ", kernels " + b.core + " (" + b.config + ")";
}

std::string blas_warning(const BlasInfo& b) {
  if (!b.slow_kernels()) return "";
  // Measured: docs/performance.md "BLAS kernels".
  return "OpenBLAS runs its " + b.core +
         " kernels on a CPU with AVX2: factorisations take about 1.5 times as long as with its "
         "Haswell kernels (docs/performance.md \"BLAS kernels\"); nmm's programs choose those "
         "themselves unless OPENBLAS_CORETYPE or NMM_BLAS_KERNELS=keep is set (OPENBLAS_CORETYPE="
         "SkylakeX where the CPU has AVX-512, Haswell where it has AVX2)";
}

}  // namespace nmm::solve
