#!/bin/sh
# A run that stops (exit status 3) draws its reason under result.svg, wrapped, with the likely
# cause (a mesh coarser than the body), keeps the title short, says the same on its one stderr
# line and in index.html; nmm-report redraws the same picture and takes --exaggerate.
# Usage: failed_run_picture.sh NMM-PREPROCESS NMM-SOLVE NMM-REPORT SCENE WORKDIR
pre=$1 solve=$2 report=$3 scene=$4 work=$5
rm -rf "$work"; mkdir -p "$work"
fail=0
check() { if ! sh -c "$1"; then echo "FAILED: $1"; fail=1; fi; }
"$pre" "$scene" -o "$work/coarse.nmm" -q 2>"$work/pre.err"
check "grep -q 'mesh size 10 m is larger than body' '$work/pre.err'"
"$solve" "$work/coarse.nmm" -o "$work/run" -q --pictures 2>"$work/err"
status=$?
cat "$work/err"
check "[ $status = 3 ]"
check "[ \$(wc -l < '$work/err') = 1 ]"
check "grep -q 'time step cut below its floor (1e-05 s) at t = .* s because one step moved a cover by .* m, more than the 6e-07 m a step may move (2 × max_displacement_ratio 1e-07 × w0 3 m, w0 being half the model size as in DDA); likely cause: mesh size 10 m against body 0, 6 m wide and 1 m high: the mesh is coarser than the body' '$work/err'"
svg="$work/run/result.svg"
check "grep -q '>coarse-block  t = .* s  (stopped, reason below)  displacement ×[0-9]*<' '$svg'"
check "grep -q '>stopped: time step cut below its floor' '$svg'"
check "grep -q '>likely cause: mesh size 10 m against body 0' '$svg'"
# Wrapped: the reason takes two lines or more, none wider than the picture's estimate.
python3 - "$svg" <<'PY' || fail=1
import re, sys
svg = open(sys.argv[1], encoding="utf-8").read()
texts = re.findall(r"<text[^>]*>([^<]*)</text>", svg)
start = next(i for i, t in enumerate(texts) if t.startswith("stopped: "))
end = next(i for i, t in enumerate(texts) if t.startswith("likely cause: "))
lines = texts[start:end]
print(f"reason in {len(lines)} lines, longest {max(map(len, lines))} characters")
sys.exit(0 if len(lines) >= 2 and max(map(len, lines)) < 140 else 1)
PY
check "grep -q 'class=\"bad\">time step cut below its floor' '$work/run/index.html'"
check "grep -q '<p>likely cause: mesh size 10 m against body 0' '$work/run/index.html'"
if command -v rsvg-convert >/dev/null 2>&1; then check "test -s '$work/run/result.png'"; fi
# nmm-report: the same picture by default, and the factor asked for.
cp "$svg" "$work/live.svg"
"$report" "$work/run" -q && check "cmp -s '$work/live.svg' '$svg'"
"$report" "$work/run" -q --exaggerate 50 && check "grep -q 'displacement ×50<' '$svg'"
"$report" "$work/run" -q --exaggerate 1 && check "grep -q 'deformation true scale<' '$svg'"
exit $fail
