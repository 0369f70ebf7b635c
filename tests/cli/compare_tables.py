#!/usr/bin/env python3
"""Checks that the committed doc tables (docs/figures/*_tables.md, made by docs/regenerate.sh)
still match a fresh run of the same tool.

Usage: compare_tables.py COMMITTED.md FRESH.md [--skip SECTION_TEXT]... [--min-rows N]
                         [--keys HEADER,HEADER,...]

The fresh file may come from the tool's --quick mode: it runs a subset of the same settings, so
each of its table rows is looked up in the committed table of the same section (heading, or
the same header row when the committed page names its sections differently) by
its key — the cells under the setting headers (--keys; default: test, load, τ/τf, setting, run,
model) — and compared there (a quick-only setting absent from the committed table is listed and
left out):
  - cells without numbers must be equal;
  - numbers are compared one by one with a tolerance of 0.5 % of the value plus 1.5 units of
    the last digit printed (rounding of a 4-significant-digit table), so a changed model fails
    while the last digit may move;
  - columns whose header mentions "wall" (wall-clock seconds) are ignored: they differ run to run.
Sections named in --skip are left out (the reason belongs to the caller, e.g. the quick run uses
fewer steps than the committed one). Fails when fewer than N rows (default 3) were compared, so
a renamed heading cannot make the check vacuous. One line per mismatch; exit status 1 if any.
"""
import re
import sys

NUM = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def tables(path):
    """{section: (header cells, [row cells])} of the Markdown tables in the file."""
    out, section, header = {}, None, None
    for line in open(path, encoding="utf-8"):
        line = line.rstrip("\n")
        if line.startswith("#"):
            section, header = line.lstrip("#").strip(), None
            continue
        if not line.startswith("|") or section is None:
            header = None if not line.startswith("|") else header
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if all(re.fullmatch(r":?-+:?", c) for c in cells):
            continue
        if header is None:
            header = cells
            out.setdefault(section, (header, []))
        else:
            out[section][1].append(cells)
    return out


KEYS = ["test", "load", "τ/τf", "setting", "run", "model"]


def key(cells, header):
    return tuple(c for h, c in zip(header, cells) if h in KEYS) or (cells[0],)


def unit(text):
    """Value of one unit in the last printed digit of a number."""
    mant = re.split(r"[eE]", text)[0]
    exp = int(re.split(r"[eE]", text)[1]) if re.search(r"[eE]", text) else 0
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return 10.0 ** (exp - decimals)


def main():
    committed, fresh = sys.argv[1], sys.argv[2]
    skips = [sys.argv[i + 1] for i, a in enumerate(sys.argv) if a == "--skip"]
    min_rows = int(sys.argv[sys.argv.index("--min-rows") + 1]) if "--min-rows" in sys.argv else 3
    if "--keys" in sys.argv:
        KEYS[:] = sys.argv[sys.argv.index("--keys") + 1].split(",")
    old, new = tables(committed), tables(fresh)
    compared, failed = 0, 0
    for section, (header, rows) in new.items():
        if any(s in section for s in skips):
            print(f"skip  {section}")
            continue
        # The doc pages (docs/accuracy.md, docs/joint-studies.md) carry the same tables under
        # headings of their own: a table is found by its heading, else by its header row.
        found = old.get(section) or next((t for t in old.values() if t[0] == header), None)
        if found is None:
            print(f"FAIL  section '{section}' (header {header}) is not in {committed}")
            failed += 1
            continue
        oheader, orows = found
        if oheader != header:
            print(f"FAIL  {section}: header {header} != committed {oheader}")
            failed += 1
            continue
        index = {key(r, header): r for r in orows}
        for r in rows:
            o = index.get(key(r, header))
            if o is None:
                print(f"note  {section}: {key(r, header)} is not in the committed table (not compared)")
                continue
            compared += 1
            for h, a, b in zip(header, r, o):
                if "wall" in h.lower():
                    continue
                na, nb = NUM.findall(a), NUM.findall(b)
                if not na and a == b:
                    continue
                if len(na) != len(nb) or NUM.sub("#", a) != NUM.sub("#", b):
                    print(f"FAIL  {section} | {r[0]} | {h}: '{a}' (fresh) vs '{b}' (committed)")
                    failed += 1
                    continue
                for x, y in zip(na, nb):
                    fx, fy = float(x), float(y)
                    tol = 0.005 * max(abs(fx), abs(fy)) + 1.5 * max(unit(x), unit(y))
                    if abs(fx - fy) > tol:
                        print(f"FAIL  {section} | {r[0]} | {h}: {x} (fresh) vs {y} (committed), tolerance {tol:.3g}")
                        failed += 1
    print(f"{compared} rows compared, {failed} mismatches ({committed} against {fresh})")
    if compared < min_rows:
        print(f"FAIL  fewer than {min_rows} rows compared")
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
