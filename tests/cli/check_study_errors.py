#!/usr/bin/env python3
"""Checks rows of nmm-study's accuracy_time.csv against error limits.

Usage: check_study_errors.py ACCURACY_TIME.csv CASE:SETTING:VALUE:MAX_ERROR...

Each CASE:SETTING:VALUE:MAX_ERROR names one run (the CSV's case, setting and value columns, the
value compared within 1e-9 relative) whose relative error (the error column: |computed − exact| /
|exact|) must be at most MAX_ERROR (a fraction: 0.01 is 1 %). A run missing from the CSV — the
study leaves out runs that did not complete — fails. One line per check; exit status 1 if any
fails.
"""
import csv
import sys


def main():
    rows = list(csv.DictReader(open(sys.argv[1], encoding="utf-8")))
    failed = 0
    for spec in sys.argv[2:]:
        case, setting, value, limit = spec.split(":")
        found = [r for r in rows if r["case"] == case and r["setting"] == setting
                 and abs(float(r["value"]) - float(value)) <= 1e-9 * abs(float(value))]
        if not found:
            print(f"FAIL  {case} {setting} {value}: not in the CSV (the run did not complete or was not run)")
            failed += 1
            continue
        error = float(found[0]["error"])
        ok = error <= float(limit)
        failed += not ok
        print(f"{'ok   ' if ok else 'FAIL '} {case} {setting} {value}: error {100 * error:.3f} % "
              f"(limit {100 * float(limit):.3g} %), {float(found[0]['wall_seconds']):.3f} s")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
