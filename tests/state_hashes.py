#!/usr/bin/env python3
"""The state hashes a change of layout must keep bit for bit (summary.json's state_hash).

One line per run in tests/state_hashes.txt:
  data.NAME HASH                  every scene in data/, run as CTest runs it (its "// quick:"
                                  arguments where it has them)
  reference.NAME STEPS HASH       every reference problem, a short run of its own
                                  (tests/reference_state_hashes.cpp)

Check (CTest state_hashes, reading the runs the data.NAME.solve tests made):
  python3 tests/state_hashes.py build --runs build/data
Regenerate the table (runs every scene itself, minutes), from the repository's root:
  python3 tests/state_hashes.py build --write
A change that moves results on purpose (a new contact solve, say) regenerates the table in the
same commit and says why there. The state includes the SHA-256 of the mesh's embedded scene
text, so editing a data/ scene, even a comment in it, moves its hash too: regenerate, and say so.
"""
import argparse
import json
import os
import pathlib
import shlex
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
TABLE = ROOT / "tests" / "state_hashes.txt"


def quick_args(scene):
    for line in scene.read_text().splitlines():
        if line.startswith("// quick: "):
            return shlex.split(line[len("// quick: "):])
    return []


def data_hash(bin_dir, scene, runs, work):
    name = scene.stem
    if runs is None:
        mesh = work / f"{name}.nmm"
        out = work / f"{name}_run"
        subprocess.run([bin_dir / "nmm-preprocess", scene, "-o", mesh, "-q"], check=True)
        # As data/CMakeLists.txt runs it (the pictures do not touch the state).
        subprocess.run([bin_dir / "nmm-solve", mesh, "-o", out, "--quiet"] + quick_args(scene),
                       check=False)
    else:
        out = runs / f"{name}_run"
    summary = out / "summary.json"
    if not summary.is_file():
        return f"data.{name} (no {summary})"
    return f"data.{name} {json.loads(summary.read_text())['state_hash']}"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("build", type=pathlib.Path, help="the build folder (its bin/ holds the tools)")
    p.add_argument("--runs", type=pathlib.Path,
                   help="read data/ runs from RUNS/NAME_run (CTest's build/data) instead of running them")
    p.add_argument("--write", action="store_true", help=f"write {TABLE.relative_to(ROOT)}")
    a = p.parse_args()
    bin_dir = a.build.resolve() / "bin"
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in sorted((ROOT / "data").glob("*.json")):
            lines.append(data_hash(bin_dir, scene, a.runs, pathlib.Path(tmp)))
    ref = subprocess.run([bin_dir / "reference_state_hashes", ROOT / "data"], check=True,
                         capture_output=True, text=True)
    lines += ref.stdout.splitlines()
    if a.write:
        TABLE.write_text("".join(line + "\n" for line in lines))
        print(f"wrote {len(lines)} hashes to {TABLE}")
        return 0
    want = TABLE.read_text().splitlines()
    bad = 0
    for line in sorted(set(want) | set(lines)):
        if line not in lines:
            print(f"table only: {line}")
            bad += 1
        elif line not in want:
            print(f"this build: {line}")
            bad += 1
    print(f"{len(lines)} state hashes, {bad} lines differ from {TABLE.relative_to(ROOT)}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
