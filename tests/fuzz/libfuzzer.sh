#!/usr/bin/env bash
# libFuzzer on the scene parser and the mesh reader (clang, ASan + UBSan). docs/fuzzing.md.
#
#   bash tests/fuzz/libfuzzer.sh [RUNS] [BUILD_DIR]
#       Replay: the committed corpus (tests/fuzz/corpus/) plus the project's scenes and a seed
#       mesh, fixed seed, RUNS mutations per target (default 50000). The same commit executes
#       the same units and gives the same answer on every machine; this is what CI runs.
#   bash tests/fuzz/libfuzzer.sh --campaign SECONDS [BUILD_DIR]
#       A random campaign outside CI: a seed from the clock, SECONDS per target, the units it
#       finds interesting kept in BUILD_DIR/campaign/. Findings go to BUILD_DIR/findings; commit
#       each one to tests/fuzz/corpus/TARGET/ (and a unit test) once it is fixed.
#
# Findings are written as crash-*/leak-*/timeout-* files into BUILD_DIR/findings and fail the
# script. Needs clang and libclang-rt-14-dev (Debian).
set -euo pipefail
top=$(cd "$(dirname "$0")/../.." && pwd)
mode=replay
if [ "${1:-}" = "--campaign" ]; then
  mode=campaign
  shift
  seconds=${1:?usage: libfuzzer.sh --campaign SECONDS [BUILD_DIR]}
else
  runs=${1:-50000}
fi
build=${2:-$top/build-fuzz}
if ! command -v clang++ >/dev/null; then echo "libfuzzer.sh: clang++ not found, skipped"; exit 0; fi
# Warnings stay warnings here: -Werror is the main (GCC) build's job, and clang warns on other things.
# The clone's path is mapped away (__FILE__ in asserts and CGAL's messages would otherwise give
# each clone a binary of another layout, and libFuzzer's table of recent comparisons is indexed
# by code address, so the run would differ).
cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DNMM_LIBFUZZER=ON -DNMM_BUILD_BENCH=OFF -DNMM_WERROR=OFF \
  "-DCMAKE_CXX_FLAGS=-ffile-prefix-map=$top=. -ffile-prefix-map=$build=build-fuzz" >/dev/null
cmake --build "$build" -j"$(nproc)" --target fuzz_scene_parser fuzz_mesh_reader >/dev/null
# The seed mesh comes from the main build's preprocessor (bash .ci/setup builds it).
preprocess=$top/build/bin/nmm-preprocess
if [ ! -x "$preprocess" ]; then
  echo "libfuzzer.sh: $preprocess not found; build the project first (bash .ci/setup)" >&2
  exit 2
fi

# Seed inputs, by name in a fixed order (libFuzzer's directory reading follows the file system's
# order, which differs between machines; -seed_inputs keeps the order we give).
seeds=$build/seeds
rm -rf "$seeds" "$build/findings"
mkdir -p "$seeds/scene" "$seeds/mesh" "$build/findings"
cp "$top"/data/*.json "$top"/tests/fuzz/seed_scene.json "$top"/tests/cli/bad_scenes/*.json \
  "$seeds/scene/"
# Committed regression inputs (earlier findings), one folder per target's kind of input.
for kind in scene mesh; do
  if [ -d "$top/tests/fuzz/corpus/$kind" ]; then
    find "$top/tests/fuzz/corpus/$kind" -type f -exec cp {} "$seeds/$kind/" \;
  fi
done
# The seed mesh, made from a relative path so that its PROV (which names the scene file) has the
# same bytes in every clone. First byte: the harness's mode (even: as is; odd: CRCs repaired).
(cd "$top" && "$preprocess" tests/fuzz/seed_scene.json -o "$seeds/seed.nmm" -q)
{ printf '\x00'; cat "$seeds/seed.nmm"; } > "$seeds/mesh/seed-raw"
{ printf '\x01'; cat "$seeds/seed.nmm"; } > "$seeds/mesh/seed-repaired"

# Address-space randomisation off: with it on, the coverage of the first inputs differs by a
# feature now and then (something in the instrumented code depends on where the heap or the
# libraries land), and the whole run takes another path. Without it a replay repeats exactly.
# The same for the environment: clang's libFuzzer instrumentation on Linux counts stack depth
# as coverage, and the depth a frame reaches shifts with where the stack starts, which moves
# with the size of the environment (CI=true alone changed a replay's new units 1534 -> 1445).
norandom=(env -i PATH=/usr/bin:/bin setarch "$(uname -m)" -R)
if [ $mode = replay ] && ! "${norandom[@]}" true 2>/dev/null; then
  echo "libfuzzer.sh: setarch -R is not permitted here; the replay may differ between runs" >&2
  norandom=(env -i PATH=/usr/bin:/bin)
fi
[ $mode = campaign ] && norandom=()

status=0
for target in scene_parser mesh_reader; do
  kind=${target%%_*}
  # Relative paths from the build folder: every clone passes the same arguments.
  list=$(cd "$build" && find "seeds/$kind" -type f | LC_ALL=C sort | paste -sd, -)
  # A fresh, empty working corpus each time: what libFuzzer adds to it must not carry over.
  work=$build/work/$kind
  rm -rf "$work"
  mkdir -p "$work"
  if [ $mode = replay ]; then
    how=(-seed=20261125 -runs="$runs" -reload=0)
    echo "libFuzzer fuzz_$target: replay, seed 20261125, $runs runs, $(echo "$list" | tr , '\n' | wc -l) seed inputs"
  else
    mkdir -p "$build/campaign/$kind"
    work=$build/campaign/$kind
    how=(-max_total_time="$seconds")
    echo "libFuzzer fuzz_$target: campaign, ${seconds} s"
  fi
  (cd "$build" && "${norandom[@]}" "bin/fuzz_$target" "${work#"$build"/}" -seed_inputs="$list" \
    "${how[@]}" -max_len=65536 -rss_limit_mb=2048 -artifact_prefix="findings/$target-" \
    -print_final_stats=1 2>"$target.log") || status=1
  grep -E "^stat::number_of_executed_units|^stat::new_units_added|ERROR|SUMMARY" "$build/$target.log" || true
done
[ $status = 0 ] && echo "libFuzzer: no findings" || echo "libFuzzer: FINDINGS in $build/findings"
exit $status
