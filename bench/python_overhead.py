#!/usr/bin/env python3
"""python_overhead.py [--reps N] [--steps S] [--csv FILE] [--work DIR]

The overhead of running nmm from Python against nmm-solve (docs/python.md, "Overhead"): the
jointed slope (data/jointed_slope.json, cut once by nmm-preprocess) run for S steps (default:
the scene's 500) with every output written, in three ways, each a fresh process timed from
start to exit (wall and CPU of the child):
  tool   nmm-solve slope.nmm -o OUT -q
  solve  python3 -c "import nmm; nmm.solve('slope.nmm', out=OUT)"        (one call)
  step   python3: solver = nmm.Solver(mesh, out=OUT); solver.step() S times; solver.flush()
Paired: each repetition runs the three back to back, in an order rotated from one repetition to
the next, so that a change of machine load falls on all three alike; the ratio of each Python
way to the tool is taken within a repetition, and the median over repetitions reported. Every
run's state_hash is checked equal. Writes one CSV row per run — wall_s, cpu_s: the process;
run_s: summary.json's wall_seconds (the time inside the run's advances and finish, the same
library code in all three); loop_s (step only): the Python loop of step() calls and flush(),
timed in Python — loop_s - run_s is what calling step() from Python costs, and loop_s against
the tool's run_s of the same repetition the overhead of stepping from Python. Never fails on a
timing.
Run from the source tree with the README's shell (build/bin on PATH, build/python on PYTHONPATH):
  python3 bench/python_overhead.py --reps 7 --csv bench/results/python_overhead.csv
"""
import argparse
import csv
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import time

STEP_SCRIPT = """
import sys, time, nmm
mesh = nmm.Mesh.load(sys.argv[1])
solver = nmm.Solver(mesh, out=sys.argv[2], set={'solver.steps': int(sys.argv[3])})
t0 = time.perf_counter()
for _ in range(int(sys.argv[3])):
    solver.step()
solver.flush()
print('loop_s', time.perf_counter() - t0)
"""
SOLVE_SCRIPT = """
import sys, nmm
nmm.solve(sys.argv[1], out=sys.argv[2], set={'solver.steps': int(sys.argv[3])})
"""


def same_kernels():
    """The environment with OPENBLAS_CORETYPE set to the kernel set nmm-solve runs: where OpenBLAS
    fell back to old kernels nmm-solve chooses newer ones, which the module cannot (docs/performance.md,
    *BLAS kernels*); the Python runs get the same set, so that the three ways compute the same bits."""
    out = subprocess.run(["nmm-solve", "--version"], check=True, stdout=subprocess.PIPE, text=True).stdout
    m = re.search(r"kernels (\S+) ", out)
    return dict(os.environ, OPENBLAS_CORETYPE=m.group(1)) if m else dict(os.environ)


def timed(cmd, env):
    """(wall s, CPU s of the child, its stdout) of one run."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run(cmd, check=True, stdout=subprocess.PIPE, text=True, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), p.stdout


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--steps", type=int, default=500)
    ap.add_argument("--csv", default="python_overhead.csv")
    ap.add_argument("--work", default="python_overhead_work")
    a = ap.parse_args()
    source = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    os.makedirs(a.work, exist_ok=True)
    mesh = os.path.join(a.work, "slope.nmm")
    subprocess.run(["nmm-preprocess", os.path.join(source, "data", "jointed_slope.json"), "-o", mesh, "-q"],
                   check=True)
    py = sys.executable
    ways = {
        "tool": lambda out: ["nmm-solve", mesh, "-o", out, "-q", "--set", f"solver.steps={a.steps}"],
        "solve": lambda out: [py, "-c", SOLVE_SCRIPT, mesh, out, str(a.steps)],
        "step": lambda out: [py, "-c", STEP_SCRIPT, mesh, out, str(a.steps)],
    }
    names = list(ways)
    env = same_kernels()
    rows, ratios = [], {"solve": [], "step": []}
    for rep in range(a.reps):
        order = names[rep % 3:] + names[:rep % 3]
        walls = {}
        for way in order:
            out = os.path.join(a.work, f"{way}_{rep}")
            wall, cpu, stdout = timed(ways[way](out), env)
            loop = [float(line.split()[1]) for line in stdout.splitlines() if line.startswith("loop_s ")]
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
            walls[way] = wall
            rows.append({"rep": rep, "way": way, "position": order.index(way), "steps": summary["steps_completed"],
                         "wall_s": f"{wall:.3f}", "cpu_s": f"{cpu:.3f}",
                         "run_s": f"{summary['wall_seconds']:.3f}", "loop_s": f"{loop[0]:.3f}" if loop else "",
                         "state_hash": summary["state_hash"],
                         "load_avg_1min": f"{os.getloadavg()[0]:.2f}"})
            print(f"rep {rep} {way:5s}: {wall:6.2f} s wall, {cpu:6.2f} s CPU", flush=True)
        for way in ratios:
            ratios[way].append(walls[way] / walls["tool"])
    hashes = {r["state_hash"] for r in rows}
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    steppers = [r for r in rows if r["way"] == "step"]
    per_step = statistics.median((float(r["loop_s"]) - float(r["run_s"])) / a.steps for r in steppers)
    print(f"step: the Python side of a step() call (loop_s - run_s) per step, median: {1e6 * per_step:.1f} us")
    # Stepping from Python against nmm-solve's stepping, paired: the step() loop and flush()
    # timed in Python against the tool's own time inside its run (summary.json wall_seconds).
    tool_run = {r["rep"]: float(r["run_s"]) for r in rows if r["way"] == "tool"}
    stepping = [float(r["loop_s"]) / tool_run[r["rep"]] for r in steppers]
    print(f"stepping: median paired ratio of the step() loop to nmm-solve's run {statistics.median(stepping):.4f} "
          f"({100 * (statistics.median(stepping) - 1):+.1f} %), range {min(stepping):.4f}-{max(stepping):.4f}")
    for way, r in ratios.items():
        print(f"{way}: median paired wall ratio to nmm-solve {statistics.median(r):.4f} "
              f"({100 * (statistics.median(r) - 1):+.1f} %), range {min(r):.4f}-{max(r):.4f}")
    print(f"state hashes: {'all equal' if len(hashes) == 1 else 'DIFFER: ' + ', '.join(sorted(hashes))}")
    print("wrote", a.csv)
    return 0 if len(hashes) == 1 else 1


if __name__ == "__main__":
    sys.exit(main())
