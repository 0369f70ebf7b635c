// Which of OpenBLAS's kernel sets a program of nmm runs: the set OpenBLAS picked, unless it fell
// back to an old one on a CPU that runs a newer one.
//
// Debian's OpenBLAS (DYNAMIC_ARCH) picks its kernel set ("core") once, when the library loads,
// from the CPU's model number; a CPU newer than the build knows (OpenBLAS 0.3.21 on a Sapphire
// Rapids Xeon) gets Prescott's SSE3 kernels, and CHOLMOD's supernodal factorisation then takes
// 1.3–1.5 times as long (docs/performance.md "BLAS kernels"). OpenBLAS reads OPENBLAS_CORETYPE
// only while it loads, so the choice is made by running the program again:
//
//   choose = SkylakeX  if core ∈ old and the CPU has AVX-512 F, BW, VL and DQ
//            Haswell   if core ∈ old and the CPU has AVX2 and FMA
//            none      otherwise, or if OPENBLAS_CORETYPE is set (the user chose),
//                      NMM_BLAS_KERNELS=keep (opt-out), or this process was already re-run
//   old    = kernel sets older than AVX2 (Prescott, Core2, Penryn, Nehalem, Sandybridge, ...)
//
// and where choose ≠ none, main() sets OPENBLAS_CORETYPE=choose and NMM_BLAS_KERNELS_CHOSEN=choose
// and execs /proc/self/exe with the same arguments, before any BLAS call. The marker both stops
// a second re-run and tells summary.json ("blas" "chosen") that nmm, not the user, chose. The
// kernel set changes the last bits of the factorisations (tests/state_hashes.txt has one section
// per set); the results a run gets are then those of the CPUs OpenBLAS knows with these kernels.
// The Python module runs inside CPython and cannot re-run it: set OPENBLAS_CORETYPE before
// `import nmm` (docs/python.md).
#pragma once

#include <string>

namespace nmm::solve {

/// The instruction sets of a CPU that OpenBLAS's newer kernel sets need (cpuid).
struct CpuFeatures {
  bool avx2 = false, fma = false;                                      ///< Haswell's kernels
  bool avx512f = false, avx512bw = false, avx512vl = false, avx512dq = false;  ///< SkylakeX's
};

/// This CPU's (cpuid through __builtin_cpu_supports; none off x86-64).
CpuFeatures cpu_features();

/// The kernel set to ask OpenBLAS for where it picked `core` on a CPU with `cpu`: "SkylakeX",
/// "Haswell", or "" to keep `core` (already AVX2 or newer, a family not in the old list, a CPU
/// without the instructions, or no OpenBLAS: `core` empty).
std::string better_kernels(const std::string& core, const CpuFeatures& cpu);

/// The whole rule with the environment given (null = variable unset): `coretype` is
/// OPENBLAS_CORETYPE, `opt` NMM_BLAS_KERNELS ("keep", or unset/"auto"), `marker`
/// NMM_BLAS_KERNELS_CHOSEN. The kernel set to re-run with, or "" to run on.
std::string kernels_to_choose(const char* coretype, const char* opt, const char* marker,
                              const std::string& core, const CpuFeatures& cpu);

/// True when `opt` (NMM_BLAS_KERNELS) is a value the rule knows: unset, "", "auto" or "keep".
bool kernels_option_valid(const char* opt);

/// Called first in main() of every program that factorises: applies the rule to this process's
/// environment and OpenBLAS and, where it chooses, re-runs the program with the chosen set (does
/// not return then). An unknown NMM_BLAS_KERNELS is bad input: one line, exit status 2. If the
/// re-run fails, the program runs on with the kernels it has.
void choose_blas_kernels(char** argv);

/// The kernel set nmm chose for this process (NMM_BLAS_KERNELS_CHOSEN), "" if it did not.
std::string chosen_blas_kernels();

}  // namespace nmm::solve
