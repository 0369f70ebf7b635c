#!/usr/bin/env bash
# libfuzzer.sh SECONDS [BUILD_DIR]: builds the libFuzzer targets with clang (ASan + UBSan) and
# runs each for SECONDS from a seed corpus made of the project's scenes and a mesh file.
# Findings are written as crash-* files into BUILD_DIR/findings and fail the script.
# Needs clang and libclang-rt-14-dev (Debian). docs/fuzzing.md.
set -euo pipefail
seconds=${1:-10}
top=$(cd "$(dirname "$0")/../.." && pwd)
build=${2:-$top/build-fuzz}
if ! command -v clang++ >/dev/null; then echo "libfuzzer.sh: clang++ not found, skipped"; exit 0; fi
# Warnings stay warnings here: -Werror is the main (GCC) build's job, and clang warns on other things.
cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DNMM_LIBFUZZER=ON -DNMM_BUILD_BENCH=OFF -DNMM_WERROR=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target fuzz_scene_parser fuzz_mesh_reader >/dev/null
corpus=$build/corpus
mkdir -p "$corpus/scene" "$corpus/mesh" "$build/findings"
cp "$top"/data/*.json "$top"/tests/fuzz/seed_scene.json "$top"/tests/cli/bad_scenes/*.json "$corpus/scene/"
if [ -x "$top/build/bin/nmm-preprocess" ]; then
  "$top/build/bin/nmm-preprocess" "$top/tests/fuzz/seed_scene.json" -o "$build/seed.nmm" -q
  { printf '\x00'; cat "$build/seed.nmm"; } > "$corpus/mesh/raw"
  { printf '\x01'; cat "$build/seed.nmm"; } > "$corpus/mesh/repaired"
fi
status=0
for target in scene_parser mesh_reader; do
  dir=$corpus/${target%%_*}
  echo "libFuzzer fuzz_$target: ${seconds} s"
  "$build/bin/fuzz_$target" "$dir" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 \
    -artifact_prefix="$build/findings/$target-" -print_final_stats=1 2>"$build/$target.log" || status=1
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|ERROR|SUMMARY" "$build/$target.log" || true
done
[ $status = 0 ] && echo "libFuzzer: no findings" || echo "libFuzzer: FINDINGS in $build/findings"
exit $status
