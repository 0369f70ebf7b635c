#!/usr/bin/env python3
"""The folders are layers (docs/code-layout.md); an #include may only point down:

  common/                  -> (nothing)
  reference/               -> common/
  preprocess/              -> common/
  solver/discretisation/   -> common/
  solver/contact/          -> common/, solver/discretisation/
  solver/fracture/         -> common/, preprocess/, solver/discretisation/, solver/contact/
  solver/reinforcement/    -> the same and solver/fracture/
  solver/flow/             -> the same and solver/reinforcement/
  solver/stepping/         -> common/, preprocess/, solver/discretisation/, solver/contact/,
                              solver/fracture/, solver/reinforcement/, solver/flow/
  solver/output/           -> the same and solver/stepping/
  report/                  -> common/, solver/...
  studies/                 -> common/, reference/, preprocess/, solver/..., report/
  tools/                   -> anything (the command-line tools' mains)
  python/                  -> common/, preprocess/, solver/..., report/ (the Python module's
                              bindings: the library the tools call, no studies/)
  tests/, bench/: anything
No exceptions.

Every project header is included by its path from the repository root ("solver/contact/contact_set.h"),
the one include directory, so an #include says which layer it reaches into. Resolves each
#include to the folder holding the header and prints every include that points elsewhere or
names a project header by another path; likewise every library a folder's CMakeLists.txt links (target_link_libraries of
its nmm_* targets) that belongs to a folder above. Exit status 1 if there is one.
Usage: check_layers.py [SOURCE_DIR]
"""
import pathlib
import re
import sys

SOLVER = ["solver/discretisation", "solver/contact", "solver/fracture", "solver/reinforcement", "solver/flow",
          "solver/stepping", "solver/output"]
ALLOWED = {
    "common": set(),
    "reference": {"common"},
    "preprocess": {"common"},
    # From the fracture wing on, the solver re-cuts covers with the preprocessor's cutting code
    # (one cutting code: preprocess/recut.h).
    **{w: {"common", *SOLVER[:i]} | ({"preprocess"} if i >= 2 else set()) for i, w in enumerate(SOLVER)},
    "report": {"common", *SOLVER},
    "studies": {"common", "reference", "preprocess", *SOLVER, "report"},
    "tools": {"common", "reference", "preprocess", *SOLVER, "report", "studies"},
    "python": {"common", "preprocess", *SOLVER, "report"},
}


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    where = {}
    for folder in ALLOWED:
        for f in (root / folder).rglob("*.h"):
            where.setdefault(f.relative_to(root).as_posix(), folder)
    include = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
    bad = 0
    for folder, allowed in ALLOWED.items():
        for f in sorted((root / folder).rglob("*")):
            if f.suffix not in (".h", ".cpp"):
                continue
            # A file belongs to the deepest folder of ALLOWED that holds it (solver/contact/, not solver/).
            if max((k for k in ALLOWED if f.relative_to(root).as_posix().startswith(k + "/")), key=len) != folder:
                continue
            rel = f.relative_to(root).as_posix()
            for n, line in enumerate(f.read_text(errors="replace").splitlines(), 1):
                m = include.match(line)
                if not m:
                    continue
                target = where.get(m.group(1))
                named = [h for h in where if pathlib.Path(h).name == pathlib.Path(m.group(1)).name]
                if not target and named:
                    print(f"{rel}:{n}: includes {m.group(1)}: not by its path from the root")
                    bad += 1
                if target and target != folder and target not in allowed:
                    print(f"{rel}:{n}: includes {m.group(1)} from {target}/, above {folder}/")
                    bad += 1
    library = {"nmm_common": "common", "nmm_reference": "reference", "nmm_preprocess": "preprocess",
               "nmm_joint_network": "preprocess", "nmm_solver": "solver/discretisation", "nmm_report": "report",
               "nmm_studies": "studies"}
    link = re.compile(r"target_link_libraries\((\w+)([^)]*)\)", re.S)
    for folder, allowed in ALLOWED.items():
        cmake = root / folder / "CMakeLists.txt"
        if not cmake.is_file():
            continue  # a wing of solver/: its sources are in solver/CMakeLists.txt
        for m in link.finditer(cmake.read_text()):
            if library.get(m.group(1)) != folder:
                continue  # not a library of this folder
            for dep in re.findall(r"nmm_\w+", m.group(2)):
                target = library.get(dep)
                if target and target != folder and target not in allowed:
                    print(f"{folder}/CMakeLists.txt: {m.group(1)} links {dep} from {target}/, above {folder}/")
                    bad += 1
    print(f"{bad} includes and links against the layers")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
