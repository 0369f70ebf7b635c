#!/usr/bin/env python3
"""trace_solves.py TRACE [--below A]

Reads the contact solve's trace (NMM_TRACE_CONTACT_SOLVE=1, on stderr of nmm-solve or of
contact_bench --trace) and says why each linear solve (Newton iteration) of a step was needed.
The first solve of a solve_contact_step call is its first direction (the step starts out of
balance). Every later one follows the iterate the previous direction left, which was
  - short:     its line search stopped at alpha < A (default 0.9), by the kind of spring change
               that made the largest part of what the Newton model missed (as
               trace_line_searches.py counts them);
  - friction:  a full step that reached the force tolerance (r <= F_tol), but friction strengths
               moved with the iterate's normal forces (a round of the fixed point);
  - residual:  a full step that still left more than F_tol (contacts switched along it, or CG's
               inexact direction), with strengths moved or not ("+ friction" when they did).
Prints the solves per call (a histogram), the solves by reason, the residual the first
direction leaves (r / F_tol before its strength update) and, from the trace's "model residual"
lines, what made it up: the median over calls of |r|∞ / F_tol at the point the first line
search took — "all", the residual there; "linear", what the linear model leaves (CG's inexact
direction); and each kind of spring change along it (its contacts' departure from their linear
model; the parts may cancel, so they do not add up to "all"). Then why the factorisations were made:
"many strengths moved" (more than 5 per CG iteration of the budget since the last direction),
"CG budget spent", or "refresh" (after a CG run of more than half its budget, or a drifting one).
Last, from the trace's "accepted tol" lines, the force tolerance F_tol (N) the accepted steps
used: smallest, median, largest (F_tol is τ times the step's largest contact force).
"""
import argparse
import collections
import re
import sys

SOLVE = re.compile(r"it (\d+) r/tol (\S+) solved_cg \d alpha (\S+)")
MOVED = re.compile(r"it (\d+) strengths moved (\d+) at r/tol (\S+)")
COUNTS = re.compile(r".* cg (\d+) fac (\d+) budget (\d+)")
ACCEPTED = re.compile(r"accepted tol (\S+) N")


def short_kind(line):
    parts = re.findall(r"([a-z ]+?) \d+ (\S+?)(?: \||$)", line.split(":", 1)[1])
    return min(parts, key=lambda p: float(p[1]))[0].strip()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[1])
    ap.add_argument("trace")
    ap.add_argument("--below", type=float, default=0.9)
    a = ap.parse_args()
    try:
        lines = open(a.trace).read().split("\n")
    except OSError as e:
        print(f"trace_solves.py: {a.trace}: {e.strerror}", file=sys.stderr)
        return 2
    calls = []          # solves per solve_contact_step call
    reasons = collections.Counter()
    first_left = collections.Counter()
    last_alpha, last_kind = None, None
    moved_at = {}       # iterate -> (moved, r/tol before the update) within the current call
    first_parts = collections.defaultdict(list)  # part -> |r|inf / F_tol after each first direction
    factorised = collections.Counter()
    last_cg, last_fac = 0, 0
    tolerances = []     # N, F_tol of each accepted step
    for i, line in enumerate(lines):
        m = ACCEPTED.match(line)
        if m:
            tolerances.append(float(m.group(1)))
            continue
        m = MOVED.match(line)
        if m:
            moved_at[int(m.group(1))] = (int(m.group(2)), float(m.group(3)))
            continue
        m = SOLVE.match(line)
        if not m:
            continue
        it, rho, alpha = int(m.group(1)), float(m.group(2)), float(m.group(3))
        c = COUNTS.match(line)
        if c:
            cg, fac, budget = int(c.group(1)), int(c.group(2)), int(c.group(3))
            if fac > last_fac and "solved_cg 0" in line:
                moved_now = moved_at.get(it, (0, 0))[0]
                if last_fac == 0:
                    factorised["first"] += 1
                elif moved_now > 5 * budget:
                    factorised["many strengths moved"] += 1
                elif cg - last_cg >= budget:
                    factorised["CG budget spent"] += 1
                else:
                    factorised["refresh"] += 1
            last_cg, last_fac = cg, fac
        if it == 0:
            for j in (i + 1, i + 2):
                if j < len(lines) and "model residual over tol:" in lines[j]:
                    for name, v in re.findall(r"([a-z ]+?) (\S+?)(?: \||$)", lines[j].split(":", 1)[1]):
                        first_parts[name.strip()].append(float(v))
        if it == 0:
            calls.append(0)
            moved_at = {}
            reasons["first direction"] += 1
        else:
            moved, before = moved_at.get(it, (0, rho))
            if it == 1:
                b = "< 1" if before <= 1 else "1-2" if before < 2 else "2-5" if before < 5 else "5-20" if before < 20 else ">= 20"
                first_left[b] += 1
            if last_alpha is not None and last_alpha < a.below:
                reasons[f"short: {last_kind}"] += 1
            elif before <= 1 and moved > 0:
                reasons["friction: strengths moved at balance"] += 1
            else:
                reasons["residual: full step left > F_tol" + (" + friction" if moved > 0 else "")] += 1
        calls[-1] += 1
        last_alpha = alpha
        last_kind = short_kind(lines[i + 1]) if i + 1 < len(lines) and "model error" in lines[i + 1] else "?"
    # Calls that ended after their first direction still show their iterate-1 line only as a
    # "strengths moved" line; the residual the first direction left is counted from solves.
    n = len(calls)
    total = sum(calls)
    if n == 0:
        print("no Newton iterations in the trace")
        return 0
    hist = collections.Counter(calls)
    print(f"{n} solve calls, {total} solves, {total / n:.2f} per call; solves per call: " +
          ", ".join(f"{k}: {hist[k]}" for k in sorted(hist)))
    print("why each solve: " + ", ".join(f"{k} {v} ({v / n:.2f} per call)" for k, v in reasons.most_common()))
    print("r / F_tol after the first direction (calls that needed a second solve): " +
          ", ".join(f"{k}: {first_left[k]}" for k in ["< 1", "1-2", "2-5", "5-20", ">= 20"]))
    if first_parts:
        med = {k: sorted(v)[len(v) // 2] for k, v in first_parts.items()}
        print("after the first direction, median |r| / F_tol by part: " +
              ", ".join(f"{k} {v:.3g}" for k, v in med.items()))
    if factorised:
        print("factorisations: " + ", ".join(f"{k} {v}" for k, v in factorised.most_common()))
    if tolerances:
        t = sorted(tolerances)
        print(f"F_tol of the {len(t)} accepted steps: smallest {t[0]:.3g} N, median {t[len(t) // 2]:.3g} N, "
              f"largest {t[-1]:.3g} N")
    return 0


if __name__ == "__main__":
    sys.exit(main())
