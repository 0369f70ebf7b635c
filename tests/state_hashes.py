#!/usr/bin/env python3
"""The state hashes a change of layout must keep bit for bit (summary.json's state_hash), per
platform, and the physical figures every platform must reproduce within round-off.

The last bits of a run's results depend on the BLAS kernels behind CHOLMOD's factorisation
(OpenBLAS picks its kernel set, its "core", by the CPU it finds: Haswell, Zen, SkylakeX, ...)
and on the compiler. So tests/state_hashes.txt holds one section of hashes per platform,
    platform LIBRARY | CORE CORE ... | COMPILER
(the cores that give the same bits share a section), and one line of figures per run,
    figures NAME rtol=R V V ...   (the measure points' final displacements ux, uy, m)
One line per run in a section:
  data.NAME HASH                  every scene in data/, run as CTest runs it (its "// quick:"
                                  arguments where it has them)
  reference.NAME STEPS HASH       every reference problem, a short run of its own
                                  (tests/reference_state_hashes.cpp)

Check (CTest state_hashes, reading the runs the data.NAME.solve tests made):
  python3 tests/state_hashes.py build --runs build/data
On a platform the table has, every hash must match bit for bit. On any other (another BLAS
version, a core not yet recorded, another compiler), and always with --elsewhere (CTest
state_hashes.elsewhere): the reference problems run twice must give the same hashes (a run is
deterministic), and every figure must match the table's within round-off:
  |a − b| ≤ rtol · (largest |value| of that run's figures) + ATOL
with each run's rtol in the table: the largest spread --write measured between OpenBLAS's kernel
sets, times a margin (SPREAD_MARGIN below).

Regenerate the table (runs every scene once per OpenBLAS core this CPU can run, many minutes),
from the repository's root:
  python3 tests/state_hashes.py build --write
With --cores CORE,... only those kernel sets are run and written (minutes, not an hour); the
others' sections are kept as below. A section this CPU cannot regenerate (SkylakeX on a CPU without AVX-512, an L2-sized set recorded
for another L2 size) is kept; its line of each run whose hash moved on a platform this CPU did
regenerate becomes `NAME ?`: on that platform the run is checked by its figures within round-off
until a CPU that runs it writes the table again. Every other run there stays bitwise.
A change that moves results on purpose (a new contact solve, say) regenerates the table in the
same commit and says why there. The state includes the SHA-256 of the mesh's embedded scene
text, so editing a data/ scene, even a comment in it, moves its hash too: regenerate, and say so.
"""
import argparse
import json
import os
import pathlib
import shlex
import signal
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
TABLE = ROOT / "tests" / "state_hashes.txt"

# OpenBLAS's kernel sets (DYNAMIC_ARCH, x86-64) that --write tries through OPENBLAS_CORETYPE;
# those this CPU cannot run (their instructions missing) are skipped.
CORES = ["Prescott", "Core2", "Penryn", "Dunnington", "Nehalem", "Atom", "Nano", "Opteron",
         "Opteron_SSE3", "Barcelona", "Bobcat", "Bulldozer", "Piledriver", "Steamroller",
         "Excavator", "Sandybridge", "Haswell", "Zen", "SkylakeX", "Cooperlake"]

# Kernel sets whose blocking OpenBLAS sizes by the CPU's L2 cache (kernel/setparam-ref.c): their
# bits are recorded for the L2 size of the machine that wrote the table, as CORE/L2=SIZE.
L2_SIZED = {"Prescott", "Core2", "Penryn", "Dunnington", "Opteron", "Opteron_SSE3"}


def l2_size():
    try:
        return pathlib.Path("/sys/devices/system/cpu/cpu0/cache/index2/size").read_text().strip()
    except OSError:
        pass
    # A virtual machine may not have that folder: glibc reads the size from CPUID, as OpenBLAS does.
    try:
        n = int(subprocess.run(["getconf", "LEVEL2_CACHE_SIZE"], capture_output=True, text=True,
                               check=True).stdout.strip())
        return f"{n // 1024}K" if n > 0 else "unknown"
    except (OSError, ValueError, subprocess.CalledProcessError):
        return "unknown"


def core_key(core):
    """The core as the table keys it: with the L2 size where the blocking depends on it."""
    return f"{core}/L2={l2_size()}" if core in L2_SIZED else core


# Round-off tolerance of the figures on a platform the table lacks, per run: relative to the
# largest |value| of the run's figures, SPREAD_MARGIN times the largest spread --write measured
# between the kernel sets it recorded, at least RTOL_FLOOR; plus ATOL (m). Measured 2026-11-28:
# the jointed slopes spread most (dfn_slope 4.0e-3, jointed_slope 8.6e-4: contacts near a state
# change decided differently in the last bits), every other run within 5e-9.
SPREAD_MARGIN = 3
RTOL_FLOOR = 1e-6
ATOL = 1e-12


def quick_args(scene):
    for line in scene.read_text().splitlines():
        if line.startswith("// quick: "):
            return shlex.split(line[len("// quick: "):])
    return []


def data_run(bin_dir, scene, runs, work, env=None):
    """The scene's run folder: CTest's (runs) or a run made here."""
    name = scene.stem
    if runs is not None:
        return runs / f"{name}_run"
    mesh = work / f"{name}.nmm"
    out = work / f"{name}_run"
    subprocess.run([bin_dir / "nmm-preprocess", scene, "-o", mesh, "-q"], check=True, env=env)
    # As data/CMakeLists.txt runs it (the pictures do not touch the state).
    subprocess.run([bin_dir / "nmm-solve", mesh, "-o", out, "--quiet"] + quick_args(scene),
                   check=False, env=env)
    return out


def data_lines(out):
    """(hash line, figures line) of a data/ run folder."""
    name = out.name[:-len("_run")]
    summary = out / "summary.json"
    if not summary.is_file():
        return f"data.{name} (no {summary})", None
    hash_line = f"data.{name} {json.loads(summary.read_text())['state_hash']}"
    rows = [line.split(",") for line in (out / "history.csv").read_text().splitlines()]
    head, rows = rows[0], rows[1:]
    ux, uy, step = head.index("ux"), head.index("uy"), head.index("step")
    last = [r for r in rows if r[step] == rows[-1][step]] if rows else []
    values = " ".join(f"{float(r[ux]):.17g} {float(r[uy]):.17g}" for r in last)
    return hash_line, f"figures data.{name} {values}".rstrip()


def run_all(bin_dir, runs, env=None):
    """(platform, hash lines, figures lines) of this build: every data/ scene and reference problem."""
    hashes, figures = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in sorted((ROOT / "data").glob("*.json")):
            h, f = data_lines(data_run(bin_dir, scene, runs, pathlib.Path(tmp), env))
            hashes.append(h)
            if f:
                figures.append(f)
    platform, ref_hashes, ref_figures = reference(bin_dir, env)
    return platform, hashes + ref_hashes, figures + ref_figures


def reference(bin_dir, env=None):
    out = subprocess.run([bin_dir / "reference_state_hashes", ROOT / "data"], check=True,
                         capture_output=True, text=True, env=env).stdout.splitlines()
    platform = out[0][len("platform "):]
    hashes = [l for l in out[1:] if not l.startswith("figures ")]
    figures = [l for l in out[1:] if l.startswith("figures ")]
    return platform, hashes, figures


def split_platform(p):
    """'LIB | CORE ... | COMPILER' -> (LIB, {CORE, ...}, COMPILER), each core as core_key() keys it."""
    lib, cores, compiler = (x.strip() for x in p.split("|"))
    return lib, {c if "/" in c else core_key(c) for c in cores.split()}, compiler


def read_table():
    sections, figures, platform = {}, {}, None
    for line in TABLE.read_text().splitlines():
        if not line or line.startswith("#"):
            continue
        if line.startswith("platform "):
            platform = line[len("platform "):]
            sections[platform] = []
        elif line.startswith("figures "):
            name, rtol, *values = line[len("figures "):].split()
            figures[name] = (float(rtol[len("rtol="):]), [float(v) for v in values])
        else:
            sections[platform].append(line)
    return sections, figures


def write(bin_dir, cores=None):
    classes = []  # [(hash lines, [cores], figures, lib, compiler)]
    for core in cores or CORES:
        env = dict(os.environ, OPENBLAS_CORETYPE=core)
        try:
            platform, hashes, figures = run_all(bin_dir, None, env)
        except subprocess.CalledProcessError:
            print(f"{core}: not runnable on this CPU, skipped")
            continue
        lib, got, compiler = split_platform(platform)
        if got != {core_key(core)}:
            print(f"{core}: OpenBLAS ran {' '.join(got)} instead, skipped")
            continue
        for c in classes:
            if c[0] == hashes:
                c[1].append(core_key(core))
                break
        else:
            classes.append((hashes, [core_key(core)], figures, lib, compiler))
        print(f"{core}: {len(classes)} distinct result sets so far")
    out = ["# State hashes per platform (BLAS | kernel sets giving the same bits | compiler), then",
           "# every run's figures (measure points' final ux uy, m). Written by, and read by:",
           "#   python3 tests/state_hashes.py build --write   (its docstring says what is checked)"]
    for hashes, cores, _, lib, compiler in classes:
        out.append(f"platform {lib} | {' '.join(cores)} | {compiler}")
        out += hashes
    out += kept_sections(classes)
    # The spread of the figures between the kernel sets, relative to the first set's largest
    # |value|: each run's tolerance elsewhere.
    first = {l.split()[1]: [float(v) for v in l.split()[2:]] for l in classes[0][2]}
    worst = {name: 0.0 for name in first}
    for c in classes[1:]:
        for l in c[2]:
            name, values = l.split()[1], [float(v) for v in l.split()[2:]]
            scale = max([abs(v) for v in first[name]] + [1e-300])
            d = max([abs(a - b) for a, b in zip(first[name], values)] + [0.0]) / scale
            worst[name] = max(worst[name], d)
    # Written from some kernel sets only, a run's spread is at least what the table had.
    old_rtol = {n: r for n, (r, _) in read_table()[1].items()} if cores and TABLE.exists() else {}
    for name, values in first.items():
        rtol = max(RTOL_FLOOR, SPREAD_MARGIN * worst[name], old_rtol.get(name, 0.0))
        out.append(f"figures {name} rtol={rtol:.1e} " + " ".join(f"{v:.17g}" for v in values))
    TABLE.write_text("".join(line + "\n" for line in out))
    print(f"wrote {len(classes)} platforms to {TABLE}")
    for name, d in sorted(worst.items(), key=lambda x: -x[1])[:5]:
        print(f"largest relative spread of the figures between kernel sets: {name} {d:.2e}")
    return 0


def run_name(line):
    return line.split()[0]


def kept_sections(classes):
    """The old table's sections this CPU wrote none of the kernel sets of (same BLAS and compiler),
    as lines, each run whose hash moved on a section written now marked `NAME ?`."""
    if not TABLE.exists():
        return []
    old, _ = read_table()
    written = set()
    for _, cores, _, lib, compiler in classes:
        written |= {(lib, c, compiler) for c in cores}
    moved, compared = set(), False
    for platform, lines in old.items():
        lib, cores, compiler = split_platform(platform)
        for hashes, new_cores, _, new_lib, new_compiler in classes:
            if (lib, compiler) == (new_lib, new_compiler) and cores & set(new_cores):
                compared = True
                was = {run_name(l): l for l in lines}
                moved |= {run_name(l) for l in hashes if was.get(run_name(l)) != l}
    out = []
    for platform, lines in old.items():
        lib, cores, compiler = split_platform(platform)
        if any((lib, c, compiler) in written for c in cores):
            continue
        out.append(f"platform {platform}")
        # Nothing to compare with (a table from other CPUs only): no line can be vouched for.
        out += [f"{run_name(l)} ?" if not compared or run_name(l) in moved else l for l in lines]
        print(f"kept {platform}: not written now; {sum(l.endswith(' ?') for l in out)} runs marked unverified so far")
    return out


def compare_figures(want, got):
    """Lines of figures outside the tolerance (empty: all within)."""
    bad = []
    got = {l.split()[1]: [float(v) for v in l.split()[2:]] for l in got}
    for name, (rtol, values) in sorted(want.items()):
        if name not in got:
            bad.append(f"{name}: no figures from this build")
            continue
        mine = got[name]
        if len(mine) != len(values):
            bad.append(f"{name}: {len(mine)} figures, the table has {len(values)}")
            continue
        scale = max([abs(v) for v in values] + [0.0])
        worst = max([abs(a - b) for a, b in zip(values, mine)] + [0.0])
        limit = rtol * scale + ATOL
        print(f"  {name}: largest difference {worst:.3e} (tolerance {limit:.3e})")
        if worst > limit:
            bad.append(f"{name}: figures differ by {worst:.3e}, more than {limit:.3e}: {mine} against {values}")
    return bad


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("build", type=pathlib.Path, help="the build folder (its bin/ holds the tools)")
    p.add_argument("--runs", type=pathlib.Path,
                   help="read data/ runs from RUNS/NAME_run (CTest's build/data) instead of running them")
    p.add_argument("--write", action="store_true", help=f"write {TABLE.relative_to(ROOT)}")
    p.add_argument("--elsewhere", action="store_true",
                   help="check as on a platform the table lacks: determinism and figures within round-off")
    p.add_argument("--cores", help="CORE,CORE,...: run every scene under each of these OpenBLAS kernel "
                                   "sets in turn (OPENBLAS_CORETYPE) and check each; with --write, "
                                   "write only their sections and keep the others")
    a = p.parse_args()
    bin_dir = a.build.resolve() / "bin"
    if a.write:
        return write(bin_dir, a.cores.split(",") if a.cores else None)
    if a.cores:
        failed, skipped, cores = [], [], a.cores.split(",")
        for core in cores:
            print(f"== OPENBLAS_CORETYPE={core}")
            try:
                if check(bin_dir, None, a.elsewhere, dict(os.environ, OPENBLAS_CORETYPE=core)):
                    failed.append(core)
            except subprocess.CalledProcessError as e:
                # OpenBLAS takes a forced kernel set without asking the CPU: SkylakeX's on a CPU
                # without AVX-512 (an AMD EPYC, say) die at their first instruction. Such a set
                # is not this CPU's to check; any other death is a failure.
                if e.returncode != -signal.SIGILL:
                    raise
                print(f"{core}: not runnable on this CPU (illegal instruction), skipped")
                skipped.append(core)
        checked = len(cores) - len(skipped)
        print(f"kernel sets failing: {', '.join(failed) if failed else 'none'}"
              + (f"; skipped: {', '.join(skipped)}" if skipped else ""))
        # The check compares kernel families: it must have run two of them at least.
        return 1 if failed or checked < min(2, len(cores)) else 0
    return check(bin_dir, a.runs, a.elsewhere)


def check(bin_dir, runs, elsewhere, env=None):
    """0 when this build's runs (under env) pass: bitwise on a platform the table has, else
    deterministic and within round-off."""
    platform, lines, figures = run_all(bin_dir, runs, env)
    sections, want_figures = read_table()
    lib, cores, compiler = split_platform(platform)
    match = None
    for p_, hashes in sections.items():
        l, cs, c = split_platform(p_)
        if l == lib and c == compiler and cores <= cs:
            match = hashes
    if match is not None and not elsewhere:
        # Runs marked `NAME ?` (kept_sections): their figures within round-off, not their bits.
        unverified = {run_name(l) for l in match if l.split()[-1] == "?"}
        bad = 0
        for line in sorted({l for l in match if run_name(l) not in unverified} |
                           {l for l in lines if run_name(l) not in unverified}):
            if line not in lines:
                print(f"table only: {line}")
                bad += 1
            elif line not in match:
                print(f"this build: {line}")
                bad += 1
        ran = {run_name(l) for l in lines if "(no " not in l}  # a run that wrote its summary
        problems = [f"{n}: no run" for n in sorted(unverified - ran)]
        problems += compare_figures({n: v for n, v in want_figures.items() if n in unverified},
                                    [f for f in figures if f.split()[1] in unverified])
        for b in problems:
            print(b)
        print(f"platform {platform}: {len(lines)} state hashes, {bad} lines differ from "
              f"{TABLE.relative_to(ROOT)}" + (f"; {len(unverified)} runs by their figures "
                                              f"({len(problems)} problems)" if unverified else ""))
        return 1 if bad or problems else 0
    why = "as asked (--elsewhere)" if elsewhere else "a platform the table lacks"
    print(f"platform {platform}: {why}; checking determinism and the figures within round-off "
          f"(each run's rtol in the table, ATOL {ATOL:g} m)")
    _, again, _ = reference(bin_dir, env)
    first = [l for l in lines if l.startswith("reference.")]
    bad = [f"not deterministic: {x} then {y}" for x, y in zip(first, again) if x != y]
    bad += compare_figures(want_figures, figures)
    for b in bad:
        print(b)
    print(f"{len(want_figures)} runs' figures, {len(bad)} problems")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
