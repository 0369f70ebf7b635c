#!/usr/bin/env bash
# report_redraw.sh NMM-SOLVE NMM-REPORT MESH WORKDIR
# nmm-report redraws result.svg from a finished run's frames (result_redraw.h), and joints are
# drawn by contact state:
#  1. the block on the 30° incline with 20° friction slides: nmm-solve --pictures draws sliding
#     contacts and no sticking ones, and nmm-report's redraw from the last (binary, zlib) frame
#     is the same file byte for byte (same colour range, same polygons, same legend) — also
#     from ASCII frames (--text-frames);
#  2. with 40° friction it rests: sticking contacts, none sliding; with --contacts-every 3 a
#     frame whose contacts were sampled out says so; a step without a frame is exit status 2;
#  3. a moved mesh: a warning and the old picture kept; --mesh redraws it;
#  4. coloured by a stress component (read back from the frame's cell data): the same picture;
#  5. --contacts-gzip: contacts.csv.gz holds exactly the CSV a plain run writes, and nmm-report
#     redraws from it the picture nmm-solve drew.
set -u
solve=$1 report=$2 mesh=$3 work=$4
facts="python3 $(dirname "$0")/picture_facts.py"
rm -rf "$work" && mkdir -p "$work" || exit 1
# A copy of the mesh: step 3 moves it away, which must not disturb other tests using the fixture.
cp "$mesh" "$work/run.nmm" && mesh="$work/run.nmm" || exit 1
fail=0
check() { if ! eval "$1"; then echo "FAIL: $1"; fail=1; else echo "ok: $1"; fi; }
value() { $facts "$1" | awk -v k="$2" '$1 == k {print $2}'; }

args=(--set solver.steps=100 --set solver.output_every=10 -q --pictures)
for frames in binary text; do
  extra=()
  [ $frames = text ] && extra=(--text-frames)
  run="$work/slide_$frames"
  "$solve" "$mesh" -o "$run" "${args[@]}" "${extra[@]}" || { echo "FAIL: solve"; exit 1; }
  cp "$run/result.svg" "$work/live_$frames.svg"
  "$report" "$run" -q || { echo "FAIL: report"; exit 1; }
  check "cmp -s '$work/live_$frames.svg' '$run/result.svg'"
  $facts "$run/result.svg"
  check "[ $(value "$run/result.svg" sliding) -gt 5 ] && [ $(value "$run/result.svg" sticking) = 0 ]"
done
check "grep -q 'compressor=\"vtkZLibDataCompressor\"' '$work/slide_binary/frames/frame_000100.vtu'"

rest="$work/rest"
"$solve" "$mesh" -o "$rest" "${args[@]}" --set joint_sets.interface.friction_deg=40 --contacts-every 3 ||
  { echo "FAIL: solve rest"; exit 1; }
$facts "$rest/result.svg"
check "[ $(value "$rest/result.svg" sticking) -gt 5 ] && [ $(value "$rest/result.svg" sliding) = 0 ]"
cp "$rest/result.svg" "$work/rest_live.svg"
"$report" "$rest" -q && check "cmp -s '$work/rest_live.svg' '$rest/result.svg'"
"$report" "$rest" -q --frame 20 && check "grep -q 'contact state not recorded' '$rest/result.svg'"
"$report" "$rest" -q --frame 30 && check "[ $(value "$rest/result.svg" sticking) -gt 5 ]" &&
  check "grep -q '(step 30)' '$rest/result.svg'"
"$report" "$rest" -q --frame 31 2>"$work/err"
check "[ $? = 2 ] && grep -q 'no frame of step 31 (11 frames, steps 0 to 100)' '$work/err'"

mv "$mesh" "$work/moved.nmm"
"$report" "$rest" -q 2>"$work/err"
status=$?
mv "$work/moved.nmm" "$mesh"
check "[ $status = 0 ] && grep -q 'warning: result.svg not redrawn' '$work/err' && test -s '$rest/result.svg'"
cp "$mesh" "$work/copy.nmm"
"$report" "$rest" -q --mesh "$work/copy.nmm" && check "cmp -s '$work/rest_live.svg' '$rest/result.svg'"
syy="$work/slide_syy"
"$solve" "$mesh" -o "$syy" "${args[@]}" --picture-field syy || { echo "FAIL: solve syy"; exit 1; }
cp "$syy/result.svg" "$work/live_syy.svg"
"$report" "$syy" -q && check "grep -q 'σyy (MPa, tension +)' '$syy/result.svg' && cmp -s '$work/live_syy.svg' '$syy/result.svg'"
"$report" "$syy" -q --picture-field displacement && check "cmp -s '$work/live_binary.svg' '$syy/result.svg'"

gz="$work/slide_gzip"
"$solve" "$mesh" -o "$gz" "${args[@]}" --contacts-gzip || { echo "FAIL: solve gzip"; exit 1; }
check "[ ! -e '$gz/contacts.csv' ] && zcat '$gz/contacts.csv.gz' | cmp -s - '$work/slide_binary/contacts.csv'"
check "[ $(stat -c %s "$gz/contacts.csv.gz") -lt $(( $(stat -c %s "$work/slide_binary/contacts.csv") / 2 )) ]"
cp "$gz/result.svg" "$work/live_gzip.svg"
"$report" "$gz" -q && check "cmp -s '$work/live_gzip.svg' '$gz/result.svg'"
exit $fail
