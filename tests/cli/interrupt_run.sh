#!/bin/sh
# A real SIGINT (or SIGTERM) during a solve: nmm-solve finishes the step under way, writes
# history.csv, summary.json with status "interrupted" and the checkpoint, and exits with 130.
# Usage: interrupt_run.sh SIGNAL OUTDIR -- nmm-solve MESH -o OUTDIR [args...]
sig=$1; out=$2; shift 3
rm -rf "$out"
"$@" &
pid=$!
# Wait until the run is under way (its first frame is written after the set-up), then signal.
i=0
while [ ! -e "$out/frames/frame_000000.vtu" ] && [ $i -lt 200 ]; do sleep 0.05; i=$((i + 1)); done
sleep 0.5
kill -s "$sig" $pid
wait $pid
status=$?
[ $status -eq 130 ] || { echo "exit status $status, expected 130"; exit 1; }
test -s "$out/history.csv" || { echo "no history.csv"; exit 1; }
grep -q '"status": "interrupted"' "$out/summary.json" || { echo "summary.json status is not interrupted"; exit 1; }
# The run stopped early: fewer steps than the scene asks for.
grep -q '"steps_completed": 1000,' "$out/summary.json" && { echo "the run was not interrupted"; exit 1; }
test -s "$out/checkpoint.nmmstate" || { echo "no checkpoint.nmmstate"; exit 1; }
echo "interrupted by $sig: exit 130, history.csv, summary.json and checkpoint.nmmstate written"
exit 0
