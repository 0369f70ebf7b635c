#!/usr/bin/env python3
"""The fracturing robustness matrix's read-offs (docs/fracture.md, "Robustness matrix").

  fracture_matrix.py compare A.csv B.csv   one cell under two OpenBLAS kernel families: the peak
                                           loads (the slope: the wedge's travel) within 1 %
  fracture_matrix.py energy A.csv B.csv    one cell under both families: energy.csv's residual at
                                           worst within 1 % of the work done (docs/energy.md)
  fracture_matrix.py table DIR OUT.csv     every run's row (DIR/*.csv, written by
                                           tests/fracture_matrix.cpp) into OUT.csv, one line per
                                           run, and the totals: how many of how many reached
                                           their end, passed, and agree across the families
                                           (R %: energy.csv's residual at worst, in % of the work)

compare exits 1 when the peaks differ by more than 1 % (or a row is missing); energy when a
row's residual is over 1 % of the work (or a row is missing); table exits 1
unless every run of the matrix is there and passed (so a stop anywhere fails the label).
"""
import csv
import glob
import os
import sys
from collections import Counter, defaultdict

PEAK_TOLERANCE = 0.01  # –, of the larger peak
ENERGY_TOLERANCE = 1.0  # %, energy.csv's residual at worst, of the largest work done so far


def read_row(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return rows[0] if rows else None


def relative_difference(a, b):
    a, b = float(a), float(b)
    top = max(abs(a), abs(b))
    return 0.0 if top == 0 else abs(a - b) / top


def compare(paths):
    rows = []
    for p in paths:
        if not os.path.exists(p):
            print(f"{p}: no row (the run did not write one)")
            return 1
        rows.append(read_row(p))
    a, b = rows
    d = relative_difference(a["peak_load"], b["peak_load"])
    print(f"{a['case']}: peak {a['peak_load']} {a['load_unit']} ({a['kernel']}) vs {b['peak_load']} "
          f"({b['kernel']}): {100 * d:.3f} % apart (tolerance {100 * PEAK_TOLERANCE:.0f} %)")
    return 0 if d <= PEAK_TOLERANCE else 1


def energy(paths):
    ok = True
    for p in paths:
        row = read_row(p) if os.path.exists(p) else None
        if not row or not row.get("residual_worst_pct"):
            print(f"{p}: no energy figures (the run did not write them)")
            return 1
        worst = float(row["residual_worst_pct"])
        before = row.get("residual_without_damped_worst_pct") or "-"
        print(f"{row['case']} ({row['kernel']}): residual {row['residual_j']} J/m, {worst:.3g} % of the work at worst "
              f"(step {row['residual_worst_step']}; work {row['work_j']} J/m, fracture {row['fracture_j']} J/m, "
              f"damped {row.get('damped_j') or '-'} J/m; without damped {before} %; tolerance {ENERGY_TOLERANCE:g} %)")
        ok = ok and worst <= ENERGY_TOLERANCE
    return 0 if ok else 1


def table(folder, out):
    paths = sorted(glob.glob(os.path.join(folder, "*.csv")))
    rows = [r for r in (read_row(p) for p in paths) if r]
    if not rows:
        print(f"{folder}: no rows")
        return 1
    fields = list(rows[0].keys()) + ["kernel_peak_difference_pct"]
    by_case = defaultdict(dict)
    for r in rows:
        by_case[r["case"]][r["kernel"]] = r
    for r in rows:
        others = [o for k, o in by_case[r["case"]].items() if k != r["kernel"]]
        r["kernel_peak_difference_pct"] = (
            f"{100 * relative_difference(r['peak_load'], others[0]['peak_load']):.3f}"
            if others and r["peak_load"] and others[0]["peak_load"] else "")
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)

    print(f"{'case':34} {'h':>7} {'kernel':8} {'status':13} {'steps':>5} {'1st crack':>10} {'closed':>10} "
          f"{'err %':>7} {'peak':>10} {'Δkern %':>7} {'R %':>6}")
    for r in rows:
        print(f"{r['case']:34} {r['h_m']:>7} {r['kernel']:8} {r['status']:13} {r['steps']:>5} "
              f"{r['first_crack_load']:>10} {r['closed_form'] or '-':>10} {r['first_crack_error_pct'] or '-':>7} "
              f"{r['peak_load']:>10} {r['kernel_peak_difference_pct'] or '-':>7} {r.get('residual_worst_pct') or '-':>6}")
    n = len(rows)
    ran = sum(r["status"] == "ok" for r in rows)
    passed = sum(r["pass"] == "1" for r in rows)
    cases = [c for c, k in by_case.items() if len(k) == 2]
    agree = sum(all(r["kernel_peak_difference_pct"] and float(r["kernel_peak_difference_pct"]) <= 100 * PEAK_TOLERANCE
                    for r in by_case[c].values()) for c in cases)
    within = [r for r in rows if r["first_crack_error_pct"]]
    close = sum(abs(float(r["first_crack_error_pct"])) <= 5 for r in within)
    print(f"reached their end: {ran}/{n}; passed every check: {passed}/{n}; first crack within 5 % of the closed "
          f"form: {close}/{len(within)} (of the runs with one that cracked); peak within 1 % across the kernel "
          f"families: {agree}/{len(cases)} cells")
    stops = Counter(r["status"] for r in rows if r["status"] != "ok")
    for code, k in stops.most_common():
        print(f"stopped: {k} × {code}")
    for test in sorted({r["test"] for r in rows}):
        sub = [r for r in by_case.values() for r in sub_rows(r) if r["test"] == test]
        print(f"  {test:16} {sum(r['status'] == 'ok' for r in sub)}/{len(sub)} reached their end, "
              f"{sum(r['pass'] == '1' for r in sub)}/{len(sub)} passed")
    expected = 7 * 3 * 2 * 2 * 2
    print(f"rows: {n} of the matrix's {expected}; table: {out}")
    return 0 if n == expected and passed == n else 1


def sub_rows(kernels):
    return list(kernels.values())


def main(argv):
    if len(argv) == 4 and argv[1] == "compare":
        return compare(argv[2:])
    if len(argv) == 4 and argv[1] == "energy":
        return energy(argv[2:])
    if len(argv) == 4 and argv[1] == "table":
        return table(argv[2], argv[3])
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
