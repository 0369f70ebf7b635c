#!/usr/bin/env python3
"""Copies the rows of freshly made tables (docs/figures/*_tables.md) into the doc pages that
carry them (docs/accuracy.md, docs/joint-studies.md): every row of a page's table whose key (the
setting cells, as tests/cli/compare_tables.py matches them) is in the fresh table of the same
section — found by heading, else by header row — is replaced by the fresh row. Rows the fresh
run does not have are left alone and listed.

Usage: python3 docs/sync_tables.py FRESH_TABLES.md PAGE.md...   (docs/regenerate.sh runs it)
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "cli"))
import compare_tables as ct  # noqa: E402


def main():
    fresh = ct.tables(sys.argv[1])
    for page in sys.argv[2:]:
        lines = open(page, encoding="utf-8").read().split("\n")
        section, header, replaced, missing = None, None, 0, []
        for i, line in enumerate(lines):
            if line.startswith("#"):
                section, header = line.lstrip("#").strip(), None
                continue
            if not line.startswith("|"):
                header = None
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if all(ct.re.fullmatch(r":?-+:?", c) for c in cells):
                continue
            if header is None:
                header = cells
                continue
            table = fresh.get(section) or next((t for t in fresh.values() if t[0] == header), None)
            if table is None or table[0] != header:
                continue
            k = ct.key(cells, header)
            row = next((r for r in table[1] if ct.key(r, header) == k), None)
            if row is None:
                missing.append(f"{section}: {' | '.join(k)}")
                continue
            new = "| " + " | ".join(row) + " |"
            if new != line:
                lines[i] = new
                replaced += 1
        open(page, "w", encoding="utf-8").write("\n".join(lines))
        print(f"{page}: {replaced} rows replaced" + (f"; not in the fresh run: {missing}" if missing else ""))


if __name__ == "__main__":
    main()
