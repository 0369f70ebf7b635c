#!/usr/bin/env bash
# blas_kernels.sh NMM_SOLVE: the kernel set nmm's programs run (solver/discretisation/blas_kernels.h).
# Unset: where the CPU has AVX2 and FMA, the set is one with AVX2 (OpenBLAS's own pick, or the one
# nmm re-ran with after a fallback), and the program's output comes once. The user's
# OPENBLAS_CORETYPE is kept, even an old set; so is OpenBLAS's pick under NMM_BLAS_KERNELS=keep.
set -u
solve=$1
fail=0
blas() { "$solve" --version | grep '^BLAS:'; }
plain=$(env -u OPENBLAS_CORETYPE -u NMM_BLAS_KERNELS -u NMM_BLAS_KERNELS_CHOSEN "$solve" --version)
echo "unset: $(echo "$plain" | grep '^BLAS:')"
[ "$(echo "$plain" | grep -c '^BLAS:')" = 1 ] || { echo "--version printed $(echo "$plain" | grep -c '^BLAS:') BLAS lines"; fail=1; }
flags=$(grep -m1 '^flags' /proc/cpuinfo)
if [[ " $flags " == *" avx2 "* && " $flags " == *" fma "* ]]; then
  echo "$plain" | grep -qE 'kernels (Haswell|Zen|SkylakeX|Cooperlake|SapphireRapids) ' ||
    { echo "a CPU with AVX2 runs an older kernel set"; fail=1; }
  if [[ " $flags " == *" avx512f "* && " $flags " == *" avx512bw "* && " $flags " == *" avx512vl "* &&
        " $flags " == *" avx512dq "* ]]; then
    echo "$plain" | grep -qE 'kernels (SkylakeX|Cooperlake|SapphireRapids) ' ||
      { echo "a CPU with AVX-512 runs a set without it"; fail=1; }
  fi
fi
user=$(env -u NMM_BLAS_KERNELS_CHOSEN OPENBLAS_CORETYPE=Prescott "$solve" --version | grep '^BLAS:')
echo "OPENBLAS_CORETYPE=Prescott: $user"
[[ "$user" == *"kernels Prescott "* ]] || { echo "the user's OPENBLAS_CORETYPE was not kept"; fail=1; }
keep=$(env -u OPENBLAS_CORETYPE -u NMM_BLAS_KERNELS_CHOSEN NMM_BLAS_KERNELS=keep "$solve" --version | grep '^BLAS:')
echo "NMM_BLAS_KERNELS=keep: $keep"
[ -n "$keep" ] || fail=1
exit $fail
