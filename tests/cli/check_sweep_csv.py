#!/usr/bin/env python3
"""Checks an nmm-sweep result against its sweep file, expanded independently of studies/sweep.cpp.

    check_sweep_csv.py SWEEP.json OUT/sweep.csv STEPS

The runs are variants (or one unnamed) x product x preprocess product (docs/fos-and-sweeps.md): the
CSV must hold exactly one row per combination (the varied values read back from their columns),
every run ended with exit 0 and run_status "ok" after STEPS steps of the scene's time step (its
summary.simulated_time), every requested summary key is a column, and every requested history
column has a finite value for each measure point of the scene. Exit 0 pass, 1 fail.
"""
import csv
import itertools
import json
import math
import os
import re
import sys


def load_jsonc(path):
    text = open(path).read()
    text = re.sub(r"(?m)^\s*//.*$", "", text)          # whole-line comments
    text = re.sub(r"(?m)([,\[\]{}\"\d])\s*//.*$", r"\1", text)  # trailing comments
    return json.loads(text)


def same(a, b):
    try:
        return math.isclose(float(a), float(b), rel_tol=1e-12, abs_tol=0)
    except (TypeError, ValueError):
        return str(a) == str(b)


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    sweep_path, csv_path, steps = sys.argv[1], sys.argv[2], int(sys.argv[3])
    sweep = load_jsonc(sweep_path)
    base = os.path.dirname(os.path.abspath(sweep_path))
    scene = load_jsonc(os.path.join(base, sweep["scene"])) if "scene" in sweep else {}
    points = len(scene.get("measure_points", []))
    dt = scene.get("solver", {}).get("time_step", 1e-3)
    for s in sweep.get("set", []):
        if s.startswith("solver.time_step="):
            dt = float(s.split("=", 1)[1])

    variants = [v["name"] for v in sweep.get("variants", [])] or [None]
    product = sweep.get("product", {})
    pre = sweep.get("preprocess_product", {})
    axes = [("variant", variants)] if variants != [None] else []
    axes += [(k, v) for k, v in product.items()]
    axes += [("preprocess:" + k, v) for k, v in pre.items()]
    expected = [dict(zip([a for a, _ in axes], combo)) for combo in itertools.product(*[v for _, v in axes])]

    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    problems = []
    if len(rows) != len(expected):
        problems.append(f"{len(rows)} rows, the sweep file expands to {len(expected)}")
    unmatched = list(rows)
    for want in expected:
        hit = [r for r in unmatched if all(same(r.get(k), v) for k, v in want.items())]
        if len(hit) != 1:
            problems.append(f"{len(hit)} rows for {want}")
            continue
        unmatched.remove(hit[0])
    for r in rows:
        rid = r.get("run", "?")
        if r.get("exit") != "0" or r.get("run_status") != "ok":
            problems.append(f"{rid}: exit {r.get('exit')}, run_status {r.get('run_status')}")
        t = r.get("summary.simulated_time")
        if t is not None and not math.isclose(float(t), steps * dt, rel_tol=1e-9):
            problems.append(f"{rid}: simulated_time {t}, expected {steps} x {dt} s")
        for key in sweep.get("outputs", {}).get("summary", []):
            if r.get("summary." + key, "") == "":
                problems.append(f"{rid}: summary.{key} missing")
        for col in sweep.get("outputs", {}).get("history", []):
            for p in range(points):
                v = r.get(f"history.{col}.p{p}", "")
                try:
                    ok = math.isfinite(float(v))
                except ValueError:
                    ok = False
                if not ok:
                    problems.append(f"{rid}: history.{col}.p{p} = {v!r}")
    for p in problems:
        print("FAIL:", p)
    if not problems:
        print(f"{csv_path}: {len(rows)} rows = {' x '.join(str(len(v)) for _, v in axes) or '1'} "
              f"combinations, all exit 0 / ok, {points} measure points: PASS")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
