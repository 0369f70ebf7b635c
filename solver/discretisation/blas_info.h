// The BLAS behind CHOLMOD's supernodal factorisation, as this process found it: which library,
// which of OpenBLAS's kernel sets ("core") it chose for this CPU, and how many threads it runs.
// The kernels decide how fast a factorisation runs and, in the last bits, what it computes
// (docs/performance.md "BLAS kernels"): summary.json "blas" and `nmm-solve --version` name them,
// and nmm-solve warns where OpenBLAS fell back to kernels without AVX2 on a CPU that has it.
#pragma once

#include <string>

namespace nmm::solve {

struct BlasInfo {
  std::string library;  ///< "OpenBLAS 0.3.21", or the shared object that holds dgemm_ (not OpenBLAS)
  std::string core;     ///< OpenBLAS's kernel set ("Haswell", "SkylakeX", "Prescott", ...); "" if not OpenBLAS
  std::string config;   ///< OpenBLAS's build configuration (openblas_get_config()); "" if not OpenBLAS
  int threads = 0;      ///< threads OpenBLAS runs now (the solver sets it per run); 0 if unknown
  bool cpu_avx2 = false;       ///< this CPU has AVX2 and FMA
  bool avx2_kernels = false;   ///< the kernel set uses them (Haswell and later)
  /// OpenBLAS runs kernels without AVX2 on a CPU that has it (a CPU newer than the OpenBLAS
  /// build knows falls back to Prescott's SSE3 kernels): factorisations run far slower
  bool slow_kernels() const { return !core.empty() && cpu_avx2 && !avx2_kernels; }
};

/// What this process has loaded (looked up at run time, as solver_threads.cpp does).
BlasInfo blas_info();

/// One line for `--version`: "BLAS: OpenBLAS 0.3.21, kernels Haswell (config ...)".
std::string blas_line(const BlasInfo& b);

/// The warning nmm-solve prints once where slow_kernels(): what it costs and how to choose the
/// kernels; "" otherwise.
std::string blas_warning(const BlasInfo& b);

}  // namespace nmm::solve
