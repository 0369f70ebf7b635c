#!/usr/bin/env python3
"""check_stop_at_ratio.py OUTDIR STEPS THRESHOLD

A static run with solver.stop_at_ratio = THRESHOLD and solver.steps = STEPS (docs/solver.md,
"Equilibrium indicators"): it must end early, with status "ok", stopped_by "stop_at_ratio", the
verdict "at_rest", the maximum unbalanced force ratio of its last step below THRESHOLD and that
of every step before at or above it (it stops at the first step below), run_history.csv and
history.csv ending at that step, and a frame of it.
"""
import csv
import json
import os
import sys


def main():
    outdir, steps, threshold = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    s = json.load(open(os.path.join(outdir, "summary.json"), encoding="utf-8"))
    rows = list(csv.DictReader(open(os.path.join(outdir, "run_history.csv"), encoding="utf-8")))
    hist = list(csv.DictReader(open(os.path.join(outdir, "history.csv"), encoding="utf-8")))
    eq = s["equilibrium"]
    ratios = [float(r["max_unbalanced_ratio"]) for r in rows]
    done = s["steps_completed"]
    print(f"stopped after {done} of {steps} steps: {s['stopped_by']}, {eq['verdict']}, "
          f"max ratio {eq['max_unbalanced_ratio']:.3g} (threshold {threshold:g}), "
          f"mean {eq['mean_unbalanced_ratio']:.3g}; ratios of the last steps {ratios[-3:]}")
    checks = [
        (s["status"] == "ok", "status ok"),
        (s["stopped_by"] == "stop_at_ratio", "stopped_by stop_at_ratio"),
        (0 < done < steps, "ended early"),
        (eq["verdict"] == "at_rest", "verdict at_rest"),
        (eq["max_unbalanced_ratio"] < threshold, "last ratio below the threshold"),
        (len(rows) == done and abs(ratios[-1] - eq["max_unbalanced_ratio"]) <= 1e-6 * threshold,
         "run_history.csv has every step, its last ratio the summary's"),
        (all(r >= threshold for r in ratios[:-1]), "no earlier step below the threshold"),
        (int(hist[-1]["step"]) == s["step"], "history.csv ends at the last step"),
        (os.path.exists(os.path.join(outdir, "frames", "frame_%06d.vtu" % s["step"])),
         "a frame of the last step"),
    ]
    failed = [name for ok, name in checks if not ok]
    for name in failed:
        print("FAIL", name)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
