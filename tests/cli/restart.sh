#!/usr/bin/env bash
# restart.sh SOLVE PREPROCESS SCENE OTHER_SCENE WORKDIR N
# The restart contract (docs/interface.md "Rock-engineering set-ups and restart"):
# - a run of 2N steps and a run of N steps + a restart of N steps end in bitwise equal states
#   (summary.json "state_hash", the SHA-256 of the whole run state and contact history), and the
#   restart's step numbers and times continue from the checkpoint;
# - a checkpoint with a flipped byte (header, table, each part of the data, the last byte), one
#   cut short, one of another mesh, and a missing one are refused with exit status 2, one line
#   on stderr, and no output folder.
set -u
solve=$1 pre=$2 scene=$3 other=$4 dir=$5 n=$6
here=$(dirname "$0")
rm -rf "$dir" && mkdir -p "$dir"
"$pre" "$scene" -o "$dir/m.nmm" -q || { echo "preprocess failed"; exit 1; }
"$pre" "$other" -o "$dir/other.nmm" -q || { echo "preprocess failed"; exit 1; }
fail=0
"$solve" "$dir/m.nmm" -o "$dir/straight" -q --set solver.steps=$((2 * n)) || { echo "straight run failed"; exit 1; }
"$solve" "$dir/m.nmm" -o "$dir/first" -q --set solver.steps=$n || { echo "first run failed"; exit 1; }
# Not quiet: its last line (the progress line's) must count steps as history.csv does.
"$solve" "$dir/m.nmm" -o "$dir/second" --set solver.steps=$n --restart "$dir/first/checkpoint.nmmstate" \
  2> "$dir/second.log" || { echo "restart failed"; cat "$dir/second.log"; exit 1; }
field() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }
h1=$(field "$dir/straight/summary.json" state_hash)
h2=$(field "$dir/second/summary.json" state_hash)
h0=$(field "$dir/first/summary.json" state_hash)
echo "straight $h1"; echo "restart  $h2"; echo "half     $h0"
[ "$h1" = "$h2" ] || { echo "restarted state differs from the straight run"; fail=1; }
[ "$h0" != "$h2" ] || { echo "the state did not move in the second half"; fail=1; }
[ "$(field "$dir/second/summary.json" step)" = $((2 * n)) ] || { echo "step numbers do not continue"; fail=1; }
# The progress line, run_history.csv and history.csv count on from the checkpoint alike.
last=$(tail -n 1 "$dir/second.log")
echo "restart's last line: $last"
case "$last" in *" step $((2 * n)) "*) ;; *) echo "the progress line does not end at step $((2 * n))"; fail=1 ;; esac
case "$last" in *"ok, moving"*|*"ok, at_rest"*) ;; *) echo "no status and verdict on the last line"; fail=1 ;; esac
[ "$(awk -F, 'NR == 2 {print $1}' "$dir/second/run_history.csv")" = $((n + 1)) ] &&
  [ "$(tail -n 1 "$dir/second/run_history.csv" | cut -d, -f1)" = $((2 * n)) ] ||
  { echo "run_history.csv steps do not go on from the checkpoint"; fail=1; }
# Row for row as the straight run's second half: per-step iterations and cuts too (the restart
# counts on from the checkpoint's totals, not from zero).
if ! diff <(tail -n +$((n + 2)) "$dir/straight/run_history.csv") <(tail -n +2 "$dir/second/run_history.csv") > /dev/null; then
  echo "run_history.csv of the restart differs from the straight run's rows $((n + 1))-$((2 * n)):"
  diff <(tail -n +$((n + 2)) "$dir/straight/run_history.csv") <(tail -n +2 "$dir/second/run_history.csv") | head -4
  fail=1
fi
# The equilibrium indicators carry no state: the restart's last step measures as the straight run's.
e1=$(field "$dir/straight/summary.json" equilibrium)
e2=$(field "$dir/second/summary.json" equilibrium)
[ "$e1" = "$e2" ] || { echo "equilibrium differs: straight $e1, restart $e2"; fail=1; }
# The checkpoint must catch contacts sliding (state 2 in contacts.csv), or the test proves less.
sliding=$(awk -F, -v s=$n 'NR > 1 && $1 == s && $6 == 2' "$dir/first/contacts.csv" | wc -l)
echo "contacts sliding at the checkpoint (step $n): $sliding"
[ "$sliding" -gt 0 ] || { echo "no contact slides at the checkpoint"; fail=1; }
cmp -s "$dir/straight/checkpoint.nmmstate" "$dir/second/checkpoint.nmmstate" ||
  echo "note: checkpoint files differ (diagnostic counters only, if the hashes agree)"

good="$dir/first/checkpoint.nmmstate"
size=$(stat -c %s "$good")
for off in 0 9 13 20 26 40 70 $((size / 5)) $((size / 3)) $((size / 2)) $((2 * size / 3)) $((size - 1)); do
  bad="$dir/flip_$off.nmmstate"
  cp "$good" "$bad"
  byte=$(od -An -tu1 -j "$off" -N1 "$bad" | tr -d ' ')
  printf "$(printf '\\%03o' $(( (byte ^ 0x04) & 0xff )))" | dd of="$bad" bs=1 seek="$off" conv=notrunc status=none
  "$here/expect_status.sh" 2 "flip_$off.nmmstate" "$dir/out_flip_$off" -- \
    "$solve" "$dir/m.nmm" -o "$dir/out_flip_$off" -q --restart "$bad" || { echo "flip at $off accepted"; fail=1; }
done
head -c $((size - 7)) "$good" > "$dir/short.nmmstate"
"$here/expect_status.sh" 2 "short.nmmstate" "$dir/out_short" -- \
  "$solve" "$dir/m.nmm" -o "$dir/out_short" -q --restart "$dir/short.nmmstate" || fail=1
"$here/expect_status.sh" 2 "another mesh" "$dir/out_other" -- \
  "$solve" "$dir/other.nmm" -o "$dir/out_other" -q --restart "$good" || fail=1
"$here/expect_status.sh" 2 "missing.nmmstate" "$dir/out_missing" -- \
  "$solve" "$dir/m.nmm" -o "$dir/out_missing" -q --restart "$dir/missing.nmmstate" || fail=1
"$here/expect_status.sh" 2 "geometry cannot change" "$dir/out_geo" -- \
  "$solve" "$dir/m.nmm" -o "$dir/out_geo" -q --restart "$good" --set mesh.size=1 || fail=1
exit $fail
