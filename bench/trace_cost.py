#!/usr/bin/env python3
"""trace_cost.py STEPS.csv [--from K]

Where a long run's CPU time goes, from the per-step lines of `contact_bench --trace` (its
stdout: cpu_ms and the counts of each step). Fits each step's thread CPU time, by least squares
over the steps from K on (default 2: the first step's first analysis and factorisations of a
fresh pattern are not typical), to

    cpu = c0 + c1 * solves + c2 * CG iterations + c3 * factorisations + c4 * analyses

c0: what a step costs whatever it does (detection, assembly, the contacts' rows, the pattern,
the state update); c1 a Newton iteration's own work (residual, friction strengths, line
search); c2 a CG iteration (a solve pair with the kept factor, a product with H); c3 a numeric
factorisation (with restoring the matrix and adding the springs); c4 a symbolic analysis. Prints
the coefficients (ms), R², the mean counts per step, and each part's ms per step and share.
Parts whose counts are the same in every fitted step cannot be told apart and are fitted as one
(at 930k unknowns every factorisation after the first step analyses a grown pattern: "per
factorisation + per analysis"); a part no fitted step has is left out.
The counts are exact; the CPU times are the machine's (a loaded machine's steps scatter more).
"""
import sys


def rows_of(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("step"):
                continue
            v = line.strip().split(",")
            if len(v) < 14:
                continue
            # step, newton, friction_updates, cg, factorisations, ..., cpu_ms (12), analyses (13)
            rows.append((int(v[0]), float(v[1]), float(v[3]), float(v[4]), float(v[13]), float(v[12])))
    return rows


def solve(a, b):
    n = len(b)
    m = [a[i][:] + [b[i]] for i in range(n)]
    for i in range(n):
        p = max(range(i, n), key=lambda r: abs(m[r][i]))
        m[i], m[p] = m[p], m[i]
        if m[i][i] == 0:
            raise SystemExit("trace_cost.py: the counts do not vary enough to separate the parts")
        for r in range(n):
            if r != i:
                f = m[r][i] / m[i][i]
                m[r] = [x - f * y for x, y in zip(m[r], m[i])]
    return [m[i][n] / m[i][i] for i in range(n)]


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    first = 2
    if "--from" in sys.argv:
        first = int(sys.argv[sys.argv.index("--from") + 1])
    rows = [r for r in rows_of(sys.argv[1]) if r[0] >= first]
    if len(rows) < 6:
        raise SystemExit("trace_cost.py: fewer than 6 steps to fit")
    names = ["fixed part", "per solve", "per CG iteration", "per factorisation", "per analysis"]
    cols = [[1.0] * len(rows)] + [[r[j] for r in rows] for j in range(1, 5)]
    # Columns that are all zero, or equal to an earlier one, carry no part of their own.
    kept, kept_names = [], []
    for col, name in zip(cols, names):
        if not any(col):
            continue
        same = next((i for i, c in enumerate(kept) if c == col), None)
        if same is None:
            kept.append(col)
            kept_names.append(name)
        else:
            kept_names[same] += " + " + name
    x = [[c[i] for c in kept] for i in range(len(rows))]
    y = [r[5] for r in rows]
    k = len(kept)
    a = [[sum(xi[i] * xi[j] for xi in x) for j in range(k)] for i in range(k)]
    b = [sum(xi[i] * yi for xi, yi in zip(x, y)) for i in range(k)]
    c = solve(a, b)
    n = len(rows)
    mean = [sum(xi[i] for xi in x) / n for i in range(k)]
    ym = sum(y) / n
    pred = [sum(ci * xij for ci, xij in zip(c, xi)) for xi in x]
    r2 = 1 - sum((yi - pi) ** 2 for yi, pi in zip(y, pred)) / sum((yi - ym) ** 2 for yi in y)
    print(f"steps {rows[0][0]}-{rows[-1][0]} ({n}), {ym:.1f} ms CPU per step, fit R^2 = {r2:.3f}")
    print("part,ms_each,count_per_step,ms_per_step,share")
    for name, ci, mi in zip(kept_names, c, mean):
        print(f"{name},{ci:.1f},{mi:.3f},{ci * mi:.1f},{100 * ci * mi / ym:.1f} %")


if __name__ == "__main__":
    main()
