#!/usr/bin/env python3
"""trace_line_searches.py TRACE [--below A]

Reads the contact solve's trace (NMM_TRACE_CONTACT_SOLVE=1 nmm-solve ... 2> TRACE) and counts
the line searches that ended at α below A (default 0.9), each by the kind of spring change that
made the largest part of what the Newton model missed along its direction (the trace line after
the iteration: "model error over psi0: closing N E | opening N E | ..."; the most negative E
stopped the step short). Prints the Newton iterations, the short line searches and the counts.
"""
import argparse
import collections
import re
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[1])
    ap.add_argument("trace")
    ap.add_argument("--below", type=float, default=0.9)
    a = ap.parse_args()
    try:
        lines = open(a.trace).read().split("\n")
    except OSError as e:
        print(f"trace_line_searches.py: {a.trace}: {e.strerror}", file=sys.stderr)
        return 2
    iterations, short, kinds = 0, 0, collections.Counter()
    for i, line in enumerate(lines):
        m = re.match(r"it \d+ r/tol \S+ solved_cg \d alpha (\S+)", line)
        if not m:
            continue
        iterations += 1
        if float(m.group(1)) >= a.below or i + 1 >= len(lines) or "model error" not in lines[i + 1]:
            continue
        short += 1
        parts = re.findall(r"([a-z ]+?) \d+ (\S+?)(?: \||$)", lines[i + 1].split(":", 1)[1])
        kinds[min(parts, key=lambda p: float(p[1]))[0].strip()] += 1
    print(f"{iterations} Newton iterations, {short} line searches ending at alpha < {a.below}; "
          f"the largest part missed: " + ", ".join(f"{k} {n}" for k, n in kinds.most_common()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
