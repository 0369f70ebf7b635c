#!/usr/bin/env bash
# expect_run_failure.sh PATTERN OUTDIR -- COMMAND...   (or CODE:PATTERN)
# A run that cannot go on: exit status 3, one line on stderr containing PATTERN, and
# OUTDIR/summary.json written with a status other than "ok" (the reason) and history.csv present;
# with CODE: (a stop_code of common/outcome.h) summary.json's stop_code must be CODE.
set -u
pattern=$1 out=$2 code=""
case "$pattern" in *:*) code=${pattern%%:*} pattern=${pattern#*:} ;; esac
shift 3
rm -rf "$out"
err=$(mktemp)
"$@" >/dev/null 2>"$err"
got=$?
fail=0
[ "$got" = 3 ] || { echo "exit status $got, expected 3"; fail=1; }
[ "$(wc -l <"$err")" = 1 ] || { echo "stderr is not one line"; fail=1; }
grep -qF -- "$pattern" "$err" || { echo "stderr lacks: $pattern"; fail=1; }
[ -s "$out/summary.json" ] || { echo "no summary.json"; fail=1; }
grep -q '"status": "ok"' "$out/summary.json" 2>/dev/null && { echo "summary says ok"; fail=1; }
grep -qF -- "$pattern" "$out/summary.json" 2>/dev/null || { echo "summary lacks the reason"; fail=1; }
[ -z "$code" ] || grep -q "\"stop_code\": \"$code\"" "$out/summary.json" 2>/dev/null || { echo "summary's stop_code is not $code"; fail=1; }
[ -s "$out/history.csv" ] || { echo "no history.csv"; fail=1; }
[ -s "$out/checkpoint.nmmstate" ] || { echo "no checkpoint.nmmstate (the contract: written also on exit 3)"; fail=1; }
ls "$out"/*.tmp.* >/dev/null 2>&1 && { echo "temporary files left"; fail=1; }
echo "stderr: $(cat "$err")"
rm -f "$err"
exit $fail
