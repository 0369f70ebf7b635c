#!/usr/bin/env bash
# expect_status.sh STATUS PATTERN OUTFILE -- COMMAND...
# Runs COMMAND and checks the contract for failures: exit status STATUS, stderr exactly one line
# containing PATTERN (grep -F), and no file left under OUTFILE (use - for none). For STATUS 0 it
# checks that OUTFILE exists instead.
set -u
want=$1 pattern=$2 out=$3
shift 4
[ "$out" != "-" ] && rm -f "$out"
err=$(mktemp)
"$@" >/dev/null 2>"$err"
got=$?
lines=$(wc -l <"$err")
fail=0
if [ "$got" != "$want" ]; then echo "exit status $got, expected $want"; fail=1; fi
if [ "$want" != 0 ]; then
  [ "$lines" = 1 ] || { echo "stderr has $lines lines, expected 1"; fail=1; }
  grep -qF -- "$pattern" "$err" || { echo "stderr lacks: $pattern"; fail=1; }
  if [ "$out" != "-" ] && ls "$out"* >/dev/null 2>&1; then echo "left behind: $(ls "$out"*)"; fail=1; fi
else
  [ "$out" = "-" ] || [ -s "$out" ] || { echo "no output $out"; fail=1; }
fi
echo "stderr: $(cat "$err")"
rm -f "$err"
exit $fail
