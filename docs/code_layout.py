#!/usr/bin/env python3
"""Writes docs/code-layout.md: the source tree measured before and after a change of layout.

  python3 docs/code_layout.py BEFORE_REV > docs/code-layout.md

BEFORE_REV is a git revision (the tree before); "after" is the working tree. Measured for each
with Universal Ctags (function extents, public methods) and the #include lines: files and lines
per folder, the largest functions, the public methods of the main types, and the include graph
between folders (an arrow A -> B: a file in A includes a header that lives in B).
"""
import collections
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
FOLDERS = ["common", "preprocess", "solver", "report", "reference", "studies", "tests", "bench"]
MAIN_TYPES = ["TimeStepper", "Model", "Configuration", "StepControl", "RunDriver", "Form", "ContactSet",
              "EnergyMeter", "CoverSpace", "OutputWriter", "SystemMatrix"]
# Types whose public methods are listed by name (the rest by count).
LISTED_TYPES = ["TimeStepper", "Model"]


def sources(tree):
    for folder in FOLDERS:
        d = tree / folder
        if d.is_dir():
            for f in sorted(d.rglob("*")):
                if f.suffix in (".h", ".cpp") and f.is_file():
                    yield folder, f


def ctags(tree, files, kinds):
    out = subprocess.run(["ctags", "-o", "-", "--c++-kinds=" + kinds, "--fields=+neaK",
                          "--language-force=C++"] + [str(f.relative_to(tree)) for f in files],
                         cwd=tree, capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        parts = line.split("\t")
        fields = dict(p.split(":", 1) for p in parts[3:] if ":" in p)
        yield parts[0], parts[1], fields


INTRO = """Where the code lives, layer by layer (an arrow only ever points down this list):

- `common/`: the data model, scene and mesh files, writers; no CGAL, no solver.
- `reference/`: the reference problems, each a scene and its closed form (sliding block,
  cantilever, Kirsch, joint specimen, wave bar, brick wall, block on a plane, planar slide);
  needs `common/` only, and is used by the tests, the benches, the studies and the data/ checks.
- `preprocess/`: cover cutting with CGAL, nmm-preprocess and nmm-inspect.
- `solver/`: the kernel (time stepping, contact, joint laws, frames, checkpoints; the library
  nmm_solver, which includes nothing but `common/`) and nmm-solve, whose main
  (tools/nmm_solve.cpp) is the one file here that reaches up, into `report/`, for `--pictures`
  and the run's report; no CGAL, nothing from `preprocess/`.
- `report/`: what is drawn and written about a run (result picture, likely cause of a stop, the
  run's report, redraw), nmm-report and nmm-history-plot.
- `studies/`: nmm-study and nmm-joint-study (reference problems run in process, with their
  read-offs) and nmm-fos and nmm-sweep (the tools driven as programs).
- `tests/`, `bench/`: on top of everything.

Every header is included by its path from the repository root (`#include "solver/discretisation/model.h"`;
the root is the one include directory), so each #include names the layer it reaches into.
CTest `layers` (tests/check_layers.py) fails on an #include or a library link that points up
this list, or on a project header included by another path.

Inside `solver/`, a run of nmm-solve is a short pipeline, one file per stage:

1. `model.*` (`Model`): what is derived once from the mesh and the scene: element materials and
   their D matrices, the penalty defaults (100·E fixed points and supports, 20·E/h default
   interface, each named with its reason), the contact laws, the boundary edge sets, the water
   and w0. Shared by const reference by the stepping, the contacts and the energy meter.
2. `configuration.*` (`Configuration`): the cover space placed on the covers' current nodes,
   each element's frame and basis: what assembly, contact linearisation and the energy meter
   evaluate shape functions with.
3. `form.*` (`Form`): the integrators the scene calls for, built once from the model and walked
   per step to assemble the system; `integrators.*` holds one kernel per term (elasticity,
   initial stress, body force, inertia with `newmark.h`'s coefficients, fixed points, point
   loads, supports, tractions, water, in-situ traction), each with its order-0 fast path.
4. `time_stepper.*` (`TimeStepper`): the run's phases only: build, start from a checkpoint
   (`restart_from`, `restore`: `restart.*`), take steps (`attempt`: frames, contacts, assembly,
   solve, accept or reject, `state_update.*`; `step`; `run_until`, the attempts under
   `step_control.*`, `StepControl`: Shi's displacement-ratio rule, cuts and growth, constants
   named with their reasons), and `view()`.
5. `run_driver.*` (`RunDriver`): the run, calling observers after each accepted step (frames,
   histories and contacts, checkpoint, and nmm-solve's run history, energy and progress line),
   each reading the run's `RunView` (`run_view.h`: state, model, space, contacts, system,
   costs), then writing summary.json (`run_summary.*`).

Beside them: `initial_state.*` (step 0's state), `state_update.*` (the state moved on by a
solved increment), `newmark.h` (the time integration and its β rule), `static_support.*`
(whether a static system is held), `run_effects.*` (summary.json's effects), `stress_field.*`
(the state's stress polynomials, their means and point values for frames and pictures) and
`energy.*` (the energy meter, one of nmm-solve's observers). Test and bench hooks into assembly
and update are `TimeStepperProbe`'s (`time_stepper_probe.h`), off `TimeStepper`'s surface.

A move between folders must not change a result. CTest `state_hashes` compares summary.json's
`state_hash` (SHA-256 of the run state, the contact history and the mesh, which includes the
scene file's text) of every data/ scene, run as CTest runs it, and of 15 short reference-problem
runs against the table tests/state_hashes.txt, bit for bit. A change that moves results on
purpose regenerates the table in the same commit and says why (a minute of runs):
```
python3 tests/state_hashes.py build --write
```

"""


def measure(tree):
    files = list(sources(tree))
    per_folder = collections.OrderedDict((f, [0, 0]) for f in FOLDERS)
    where = {}
    solver_files = {}
    for folder, f in files:
        lines = len(f.read_text(errors="replace").splitlines())
        per_folder[folder][0] += 1
        per_folder[folder][1] += lines
        where.setdefault(f.name, folder)
        if folder == "solver":
            solver_files[f.name] = lines
    functions = []
    for name, path, fields in ctags(tree, [f for _, f in files if f.suffix == ".cpp"], "f"):
        if "line" in fields and "end" in fields:
            scope = fields.get("class", fields.get("struct", "")).split("::")[-1]
            scope = scope + "::" if scope else ""
            functions.append((int(fields["end"]) - int(fields["line"]) + 1, path, scope + name))
    functions.sort(key=lambda t: (-t[0], t[1], t[2]))
    methods = collections.defaultdict(set)
    for name, path, fields in ctags(tree, [f for _, f in files if f.suffix == ".h"], "pf"):
        cls = fields.get("class", "").split("::")[-1]
        if cls in MAIN_TYPES and fields.get("access") == "public" and not name.startswith("operator"):
            methods[cls].add(name)
    edges = collections.Counter()
    inc = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
    for folder, f in files:
        for line in f.read_text(errors="replace").splitlines():
            m = inc.match(line)
            if m:
                target = where.get(pathlib.Path(m.group(1)).name)
                if target and target != folder:
                    edges[(folder, target)] += 1
    return per_folder, functions, methods, edges, solver_files


def tree_of(rev, tmp):
    subprocess.run(f"git -C {ROOT} archive {rev} | tar -x -C {tmp}", shell=True, check=True)
    return pathlib.Path(tmp)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    rev = sys.argv[1]
    short = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", rev],
                           capture_output=True, text=True, check=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        before = measure(tree_of(rev, tmp))
    after = measure(ROOT)
    w = sys.stdout.write
    w("# Code layout, before and after\n\n")
    w(INTRO)
    w(f"The source tree measured at {short} (before) and now (after). Regenerate from the "
      f"repository's root (needs Universal Ctags and the git history):\n```\npython3 docs/code_layout.py {short} > docs/code-layout.md\n```\n\n")
    w("## Files and lines per folder\n\n| folder | files before | lines before | files after | lines after |\n|---|---|---|---|---|\n")
    for folder in FOLDERS:
        b, a = before[0][folder], after[0][folder]
        w(f"| {folder}/ | {b[0]} | {b[1]:,} | {a[0]} | {a[1]:,} |\n")
    tb = [sum(v[i] for v in before[0].values()) for i in (0, 1)]
    ta = [sum(v[i] for v in after[0].values()) for i in (0, 1)]
    w(f"| all | {tb[0]} | {tb[1]:,} | {ta[0]} | {ta[1]:,} |\n\n")
    for label, m in (("before", before), ("after", after)):
        fns = m[1]
        w(f"## The largest functions, {label}\n\n{len(fns)} functions in .cpp files, "
          f"{sum(1 for n, _, _ in fns if n > 150)} over 150 lines.\n\n| lines | function | file |\n|---|---|---|\n")
        for n, path, name in fns[:10]:
            w(f"| {n} | `{name}` | {path} |\n")
        w("\n")
    w("## Public methods of the main types\n\n| type | before | after |\n|---|---|---|\n")
    for t in MAIN_TYPES:
        b = len(before[2][t]) if t in before[2] else "—"
        w(f"| `{t}` | {b} | {len(after[2][t])} |\n")
    for t in LISTED_TYPES:
        w(f"\n`{t}`'s public methods after: " + ", ".join(f"`{m}`" for m in sorted(after[2][t])) + ".\n")
    w("\n## Files of solver/ that changed\n\nLines per file (— : not there); the stepping core is "
      "time_stepper.cpp.\n\n| file | lines before | lines after |\n|---|---|---|\n")
    for name in sorted(set(before[4]) | set(after[4])):
        b, a = before[4].get(name), after[4].get(name)
        if b != a:
            w(f"| {name} | {'—' if b is None else f'{b:,}'} | {'—' if a is None else f'{a:,}'} |\n")
    w("\n## Include graph between folders\n\nAn arrow A → B: files in A include headers that "
      "live in B (count of #include lines).\n\n| arrow | before | after |\n|---|---|---|\n")
    for e in sorted(set(before[3]) | set(after[3]), key=lambda e: (FOLDERS.index(e[0]), FOLDERS.index(e[1]))):
        w(f"| {e[0]}/ → {e[1]}/ | {before[3].get(e, 0)} | {after[3].get(e, 0)} |\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
