#!/usr/bin/env python3
"""Checks a run's energy.csv (solver/output/energy.h) against a known answer.

Usage: check_energy.py CASE OUTDIR
  free_fall  a 2 m x 1 m block (2650 kg/m3) falling from rest: K = 1/2 m g^2 t^2 within 0.1 %,
             K + V = 0 within 1e-6 K (a wrong sign of V gives 2 K), strain ~ 0
  hanging_column  an elastic column released under gravity from fixed points: it stretches
             (strain energy above 100 J/m at its largest) and K + U + V + S + damped stays put:
             |residual| < 0.2 % of the largest strain energy (measured 0.057 %; 0.3 % before the
             damped column metered the scheme's damping; a missing 1/2 in U would leave half of it
             unaccounted)
  hanging_support  the same column held by a soft support along its top instead: the support
             springs store > 50 J/m, and the balance holds within 0.2 % (measured 0.066 %)
  point_load the column without gravity, pulled by a 200 kN/m point load at its bottom: the
             load's work W > 1000 J/m goes into K + U + S + damped, |residual| < 0.5 % of W
             (measured 0.086 %; 2.8 % before the damped column: the scheme damps the local
             vibration under the point; a wrong sign of W would leave 2 W)
  traction   the same with a 200 kPa traction pulling its bottom edge: the same balance
             (measured 0.085 %; 1.8 % before the damped column)
  shaking    the free block without gravity, its base accelerated at 3 m/s^2 in x (a ramp over
             0.1 s): the body force -m a_base does work W, all of it kinetic: K = W within 0.1 %
  slide      the block on the 30 deg incline with 20 deg friction: friction work = tan 20 deg
             * m g cos 30 deg * travel and gravity V = -m g sin 30 deg * travel within 2 %,
             K = 1/2 m v^2 with v from the last two rows of history.csv within 3 %
  rest       the same block held by 40 deg friction: K < 1e-9 J/m, no friction work after the
             first output step
One line per check; exit status 1 if any fails.
"""
import csv
import math
import sys

G = 9.81


def rows(path):
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(path, encoding="utf-8"))]


def main():
    case, out = sys.argv[1], sys.argv[2]
    e = rows(f"{out}/energy.csv")
    last = e[-1]
    checks = []
    if case == "free_fall":
        m = 2650 * 2.0
        t = last["time"]
        k_exact = 0.5 * m * (G * t) ** 2
        checks.append(("K = 1/2 m g^2 t^2", last["kinetic"], abs(last["kinetic"] - k_exact) <= 1e-3 * k_exact))
        checks.append(("K + V = 0", last["kinetic"] + last["gravity"],
                       abs(last["kinetic"] + last["gravity"]) <= 1e-6 * last["kinetic"]))
        checks.append(("strain ~ 0", last["strain"], abs(last["strain"]) <= 1e-9 * last["kinetic"]))
    elif case in ("hanging_column", "hanging_support"):
        umax = max(r["strain"] for r in e)
        rmax = max(abs(r["residual"]) for r in e)
        checks.append(("largest strain energy > 100 J/m", umax, umax > 100))
        checks.append(("|residual| < 0.2 % of it", rmax, rmax < 0.002 * umax))
        if case == "hanging_support":
            smax = max(r["springs"] for r in e)
            checks.append(("the soft support stores > 50 J/m", smax, smax > 50))
    elif case == "shaking":
        w = last["load_work"]
        checks.append(("work of the base shaking > 100 J/m", w, w > 100))
        checks.append(("K = W (a free block)", last["kinetic"], abs(last["kinetic"] - w) <= 1e-3 * w))
    elif case in ("point_load", "traction"):
        w = last["load_work"]
        rmax = max(abs(r["residual"]) for r in e)
        checks.append((f"work of the {case.replace('_', ' ')} > 1000 J/m", w, w > 1000))
        checks.append(("|residual| < 0.5 % of it", rmax, rmax < 0.005 * w))
    elif case in ("slide", "rest"):
        m = 2650 * 2.0
        h = [r for r in rows(f"{out}/history.csv") if r["point"] == 0]
        travel = math.hypot(h[-1]["ux"], h[-1]["uy"])
        if case == "slide":
            want_f = math.tan(math.radians(20)) * m * G * math.cos(math.radians(30)) * travel
            want_v = -m * G * math.sin(math.radians(30)) * travel
            checks.append(("friction work = mu N s", last["friction"], abs(last["friction"] - want_f) <= 0.02 * want_f))
            checks.append(("V = -m g sin30 s", last["gravity"], abs(last["gravity"] - want_v) <= 0.02 * abs(want_v)))
            dt = h[-1]["time"] - h[-2]["time"]
            v = math.hypot(h[-1]["ux"] - h[-2]["ux"], h[-1]["uy"] - h[-2]["uy"]) / dt
            # the mean velocity over the last interval is the velocity at its middle: shift by a*dt/2
            a = G * (math.sin(math.radians(30)) - math.cos(math.radians(30)) * math.tan(math.radians(20)))
            want_k = 0.5 * m * (v + 0.5 * a * dt) ** 2
            checks.append(("K = 1/2 m v^2", last["kinetic"], abs(last["kinetic"] - want_k) <= 0.03 * want_k))
        else:
            checks.append(("K ~ 0 at rest", last["kinetic"], last["kinetic"] < 1e-9))
            checks.append(("no friction work after the first output", last["friction"] - e[1]["friction"],
                           abs(last["friction"] - e[1]["friction"]) < 1e-9))
    else:
        print(f"unknown case {case}")
        return 2
    failed = 0
    for name, got, ok in checks:
        print(f"{'ok  ' if ok else 'FAIL'} {case}: {name} (got {got:.6g})")
        failed += not ok
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
