#!/usr/bin/env python3
"""Checks a finished run against the outcome its scene promises.

Usage: check_expect.py SCENE.json OUTDIR [--quick]
       check_expect.py --line "EXPECTATION" OUTDIR   (one expectation given on the command line:
                                                     a check that must not change the scene's text,
                                                     which the state hashes include)

With --quick the "// expect-quick: ..." lines are checked instead (the scene's "// quick:" run).

The scene's header holds lines of the form (each a comment line of the scene file)
    // expect: summary.KEY == "text"            string equality of summary.json's KEY (KEY may
                                             name a nested one: equilibrium.verdict, or a
                                             list's entry by its index: flow.boundaries.2.KEY)
    // expect: summary.KEY >= NUMBER            also <=, >, <, == for numbers
    // expect: history travel P at end within X +- TOL   |u| of measure point P at the last row, m
    // expect: history ux P at end within X +- TOL       (also uy) a component at the last row, m
    // expect: history uy P at end < NUMBER              (also >, <=, >=)
    // expect: history uy P minus uy Q at end within X +- TOL   a difference of two points, m
    // expect: history travel P from T to end < NUMBER   |u(end) − u(T)| of point P, m: what it
                                                         moved after time T s (it has stopped)
    // expect: energy residual within PCT % of work      energy.csv: at every row |residual| <=
                                                         PCT % of the largest |work| so far, work
                                                         = load_work − gravity (the loads', the
                                                         supports' and gravity's work)
    // expect: energy residual from STEP within PCT % of work   the same for what the residual
                                                         gained since the row of step STEP
and every one of them must hold. A scene without an `expect:` line fails: every example states
what it shows. One line per check is printed; the exit status is 1 when any fails.
"""
import csv
import json
import math
import re
import sys


def energy_residual(outdir, first, pct):
    """The worst row of energy.csv from step `first` on: (|R − R(first)| / largest |work| so far
    in %, whether every row is within pct %). work = load_work − gravity."""
    rows = list(csv.DictReader(open(f"{outdir}/energy.csv", encoding="utf-8")))
    base = [r for r in rows if int(r["step"]) <= first]
    r0 = float(base[-1]["residual"]) if base else 0.0
    worst, ok, work = 0.0, True, 0.0
    for r in rows:
        work = max(work, abs(float(r["load_work"]) - float(r["gravity"])))
        if int(r["step"]) < first:
            continue
        gap = abs(float(r["residual"]) - r0)
        ok = ok and gap <= pct / 100 * work
        if work > 0:
            worst = max(worst, 100 * gap / work)
    return f"{worst:.3g} % at worst", ok


def main():
    if sys.argv[1] == "--line":
        scene, expects, outdir = "the command line", [sys.argv[2]], sys.argv[3]
    else:
        scene, outdir = sys.argv[1], sys.argv[2]
        tag = "expect-quick" if "--quick" in sys.argv[3:] else "expect"
        expects = [m.group(1).strip() for line in open(scene, encoding="utf-8")
                   for m in [re.match(r"\s*//\s*" + tag + r":\s*(.*)$", line)] if m]
    if not expects:
        print(f"{scene}: no '// expect:' line in the header")
        return 1
    summary = json.load(open(f"{outdir}/summary.json", encoding="utf-8"))
    rows = list(csv.DictReader(open(f"{outdir}/history.csv", encoding="utf-8")))
    ops = {"==": lambda a, b: a == b, ">=": lambda a, b: a >= b, "<=": lambda a, b: a <= b,
           ">": lambda a, b: a > b, "<": lambda a, b: a < b}
    failed = 0
    for e in expects:
        m = re.match(r"summary\.([\w.]+)\s*(==|>=|<=|>|<)\s*(.+)$", e)
        h = re.match(r"history\s+(travel|ux|uy)\s+(\d+)(?:\s+minus\s+(ux|uy)\s+(\d+))?\s+at end\s+(?:within\s+(\S+)\s*\+-\s*(\S+)|"
                     r"(==|>=|<=|>|<)\s*(\S+))$", e)
        f = re.match(r"history\s+travel\s+(\d+)\s+from\s+(\S+)\s+to end\s*(==|>=|<=|>|<)\s*(\S+)$", e)
        g = re.match(r"energy\s+residual\s+(?:from\s+(\d+)\s+)?within\s+(\S+)\s*%\s+of\s+work$", e)
        if g:
            got, ok = energy_residual(outdir, int(g.group(1) or 0), float(g.group(2)))
        elif f:
            point, t0, op, bound = f.groups()
            mine = [r for r in rows if int(r["point"]) == int(point)]
            start = [r for r in mine if float(r["time"]) >= float(t0) - 1e-9]
            if not start:
                print(f"FAIL {e}: no history rows for the point after t = {t0} s")
                failed += 1
                continue
            got = math.hypot(float(mine[-1]["ux"]) - float(start[0]["ux"]),
                             float(mine[-1]["uy"]) - float(start[0]["uy"]))
            ok = ops[op](got, float(bound))
        elif m:
            key, op, want = m.groups()
            want = json.loads(want)
            got = summary
            for part in key.split("."):
                if isinstance(got, list) and part.isdigit():  # a list's entry: flow.boundaries.2
                    got = got[int(part)] if int(part) < len(got) else None
                else:
                    got = got.get(part) if isinstance(got, dict) else None
            ok = got is not None and ops[op](got, want)
        elif h:
            what, point, what2, point2, x, tol, op, bound = h.groups()

            def last_value(quantity, p):
                last = [r for r in rows if int(r["point"]) == int(p)]
                if not last:
                    return None
                ux, uy = float(last[-1]["ux"]), float(last[-1]["uy"])
                return {"travel": math.hypot(ux, uy), "ux": ux, "uy": uy}[quantity]

            got = last_value(what, point)
            if got is not None and what2 is not None:
                other = last_value(what2, point2)
                got = None if other is None else got - other
            if got is None:
                print(f"FAIL {e}: no history rows for the point")
                failed += 1
                continue
            ok = abs(got - float(x)) <= float(tol) if x is not None else ops[op](got, float(bound))
        else:
            print(f"FAIL {e}: cannot read this expectation")
            failed += 1
            continue
        print(f"{'ok  ' if ok else 'FAIL'} {e}  (got {got})")
        failed += not ok
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
