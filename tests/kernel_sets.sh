#!/usr/bin/env bash
# The whole test suite under several of OpenBLAS's kernel sets in turn, as on CPUs of other
# families (OpenBLAS picks its kernels by the CPU it finds; OPENBLAS_CORETYPE forces a set):
# the test command's answer must not depend on the CPU (tests/state_hashes.py).
# Usage, after the build (bash .ci/setup): bash tests/kernel_sets.sh [CORE...]
#   default cores: Prescott Haswell SkylakeX Zen (about 4 minutes each on 2 cores)
set -uo pipefail
cd "$(dirname "$0")/.."
cores=("$@")
[ ${#cores[@]} -gt 0 ] || cores=(Prescott Haswell SkylakeX Zen)
failed=()
for core in "${cores[@]}"; do
  echo "== OPENBLAS_CORETYPE=$core"
  # OpenBLAS takes a forced set without asking the CPU: AVX-512 kernels die on a CPU without it.
  if [[ $core == SkylakeX || $core == Cooperlake ]] && ! grep -qw avx512f /proc/cpuinfo; then
    echo "$core: this CPU has no AVX-512, skipped"
    continue
  fi
  if OPENBLAS_CORETYPE=$core ctest --test-dir build -j"$(nproc)" --output-on-failure > "build/kernel_sets_$core.log" 2>&1; then
    tail -n 1 "build/kernel_sets_$core.log" | grep -q . && grep -E "tests passed" "build/kernel_sets_$core.log"
  else
    grep -E "tests passed|Failed|\*\*\*" "build/kernel_sets_$core.log" | tail -n 20
    failed+=("$core")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "failing kernel sets: ${failed[*]} (logs: build/kernel_sets_CORE.log)"
  exit 1
fi
echo "every kernel set passes: ${cores[*]}"
