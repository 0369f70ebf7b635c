// The choice of OpenBLAS's kernel set (solver/discretisation/blas_kernels.h): which set a fallen-back
// OpenBLAS is sent to on which CPU, and when nmm leaves the choice alone. The re-run itself is
// checked through nmm-solve --version (tests/CMakeLists.txt, cli.blas_kernels_*).
#include <gtest/gtest.h>

#include "solver/discretisation/blas_kernels.h"

namespace {

using nmm::solve::better_kernels;
using nmm::solve::CpuFeatures;
using nmm::solve::kernels_option_valid;
using nmm::solve::kernels_to_choose;

CpuFeatures sse3_only() { return {}; }
CpuFeatures avx2_fma() {
  CpuFeatures c;
  c.avx2 = c.fma = true;
  return c;
}
CpuFeatures avx512() {  // a Skylake-SP or later Xeon: F, BW, VL and DQ
  CpuFeatures c = avx2_fma();
  c.avx512f = c.avx512bw = c.avx512vl = c.avx512dq = true;
  return c;
}

TEST(BlasKernels, FallenBackSetGoesToTheNewestTheCpuRuns) {
  EXPECT_EQ(better_kernels("Prescott", avx512()), "SkylakeX");
  EXPECT_EQ(better_kernels("Prescott", avx2_fma()), "Haswell");
  EXPECT_EQ(better_kernels("Nehalem", avx2_fma()), "Haswell");
  EXPECT_EQ(better_kernels("Sandybridge", avx512()), "SkylakeX");  // AVX without AVX2
  EXPECT_EQ(better_kernels("prescott", avx512()), "SkylakeX");     // OpenBLAS's spelling varies
}

TEST(BlasKernels, AvxFiveTwelveNeedsAllFourParts) {
  CpuFeatures c = avx512();
  c.avx512bw = false;  // Knights Landing: F without BW/VL/DQ, not SkylakeX's
  EXPECT_EQ(better_kernels("Prescott", c), "Haswell");
  c = avx512();
  c.avx512dq = false;
  EXPECT_EQ(better_kernels("Prescott", c), "Haswell");
}

TEST(BlasKernels, KeepsWhatTheCpuCannotImproveOn) {
  EXPECT_EQ(better_kernels("Prescott", sse3_only()), "");  // an old CPU: Prescott is its set
  CpuFeatures fma_only;
  fma_only.fma = true;  // FMA without AVX2 (no such Intel; Haswell's kernels need both)
  EXPECT_EQ(better_kernels("Prescott", fma_only), "");
  EXPECT_EQ(better_kernels("Haswell", avx512()), "");      // already AVX2: OpenBLAS knew the CPU
  EXPECT_EQ(better_kernels("SkylakeX", avx512()), "");
  EXPECT_EQ(better_kernels("Cooperlake", avx512()), "");
  EXPECT_EQ(better_kernels("Zen", avx2_fma()), "");
  EXPECT_EQ(better_kernels("Excavator", avx2_fma()), "");  // AMD's own line, picked on purpose
  EXPECT_EQ(better_kernels("", avx512()), "");             // not OpenBLAS
}

TEST(BlasKernels, UserChoiceOptOutAndMarkerStopIt) {
  // Nothing set: the rule applies.
  EXPECT_EQ(kernels_to_choose(nullptr, nullptr, nullptr, "Prescott", avx512()), "SkylakeX");
  EXPECT_EQ(kernels_to_choose("", "auto", "", "Prescott", avx2_fma()), "Haswell");
  // The user's OPENBLAS_CORETYPE, even Prescott's, is never overridden.
  EXPECT_EQ(kernels_to_choose("Prescott", nullptr, nullptr, "Prescott", avx512()), "");
  // NMM_BLAS_KERNELS=keep.
  EXPECT_EQ(kernels_to_choose(nullptr, "keep", nullptr, "Prescott", avx512()), "");
  // Re-run once already (OpenBLAS ignored the set asked for): no second re-run, no loop.
  EXPECT_EQ(kernels_to_choose(nullptr, nullptr, "SkylakeX", "Prescott", avx512()), "");
}

TEST(BlasKernels, OptionWords) {
  EXPECT_TRUE(kernels_option_valid(nullptr));
  EXPECT_TRUE(kernels_option_valid(""));
  EXPECT_TRUE(kernels_option_valid("keep"));
  EXPECT_TRUE(kernels_option_valid("auto"));
  EXPECT_FALSE(kernels_option_valid("Haswell"));
  EXPECT_FALSE(kernels_option_valid("KEEP"));
}

}  // namespace
