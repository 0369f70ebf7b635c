#include "solver/discretisation/blas_kernels.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "solver/discretisation/loaded_symbol.h"

namespace nmm::solve {

namespace {
constexpr const char* kMarker = "NMM_BLAS_KERNELS_CHOSEN";

// OpenBLAS 0.3.21's x86 kernel sets without AVX2, which it falls back to for a CPU it does not
// know (Prescott for an unknown Intel). The AMD Bulldozer line (Bulldozer ... Excavator) is not
// here: those are the sets OpenBLAS picks for those CPUs on purpose.
constexpr const char* kOldCores[] = {"prescott", "core2",  "penryn",   "dunnington", "nehalem",
                                     "sandybridge", "atom", "nano",    "barcelona",  "bobcat",
                                     "opteron", "opteron_sse3", "katmai", "coppermine", "northwood",
                                     "banias"};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}
}  // namespace

CpuFeatures cpu_features() {
  CpuFeatures f;
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  f.avx2 = __builtin_cpu_supports("avx2");
  f.fma = __builtin_cpu_supports("fma");
  f.avx512f = __builtin_cpu_supports("avx512f");
  f.avx512bw = __builtin_cpu_supports("avx512bw");
  f.avx512vl = __builtin_cpu_supports("avx512vl");
  f.avx512dq = __builtin_cpu_supports("avx512dq");
#endif
  return f;
}

std::string better_kernels(const std::string& core, const CpuFeatures& cpu) {
  const std::string c = lower(core);
  const bool old = std::any_of(std::begin(kOldCores), std::end(kOldCores), [&](const char* o) { return c == o; });
  if (!old) return "";
  // OpenBLAS's SkylakeX kernels use AVX-512 F/BW/VL/DQ (its own check in dynamic.c).
  if (cpu.avx512f && cpu.avx512bw && cpu.avx512vl && cpu.avx512dq && cpu.avx2 && cpu.fma) return "SkylakeX";
  if (cpu.avx2 && cpu.fma) return "Haswell";
  return "";
}

bool kernels_option_valid(const char* opt) {
  return opt == nullptr || *opt == '\0' || std::strcmp(opt, "auto") == 0 || std::strcmp(opt, "keep") == 0;
}

std::string kernels_to_choose(const char* coretype, const char* opt, const char* marker,
                              const std::string& core, const CpuFeatures& cpu) {
  if (coretype != nullptr && *coretype != '\0') return "";  // the user chose
  if (opt != nullptr && std::strcmp(opt, "keep") == 0) return "";
  if (marker != nullptr && *marker != '\0') return "";  // already re-run once: never loop
  return better_kernels(core, cpu);
}

void choose_blas_kernels(char** argv) {
  const char* opt = std::getenv("NMM_BLAS_KERNELS");
  if (!kernels_option_valid(opt)) {
    std::fprintf(stderr, "error: NMM_BLAS_KERNELS=%s: expected keep or auto\n", opt);
    std::exit(2);
  }
  using Text = char* (*)();
  const auto corename = reinterpret_cast<Text>(loaded_symbol("openblas_get_corename"));
  if (corename == nullptr) return;  // not OpenBLAS
  const std::string chosen = kernels_to_choose(std::getenv("OPENBLAS_CORETYPE"), opt, std::getenv(kMarker),
                                               corename(), cpu_features());
  if (chosen.empty()) return;
  setenv("OPENBLAS_CORETYPE", chosen.c_str(), 1);
  setenv(kMarker, chosen.c_str(), 1);
  std::fflush(nullptr);
  execv("/proc/self/exe", argv);
  // Not re-run (no /proc, say): run on with OpenBLAS's kernels; children get no stale choice.
  unsetenv("OPENBLAS_CORETYPE");
  unsetenv(kMarker);
}

std::string chosen_blas_kernels() {
  // Only while OPENBLAS_CORETYPE still says so: a child run with the user's own set inherits the marker.
  const char* m = std::getenv(kMarker);
  const char* c = std::getenv("OPENBLAS_CORETYPE");
  return m && c && std::strcmp(m, c) == 0 ? m : "";
}

}  // namespace nmm::solve
