#!/usr/bin/env python3
"""Copies the rows of freshly made tables (docs/figures/*_tables.md) into the doc pages that
carry them (docs/accuracy.md, docs/joint-studies.md): every row of a page's table whose key (the
setting cells, as tests/cli/compare_tables.py matches them) is in the fresh table of the same
section — found by heading, else by header row — is replaced by the fresh row. Rows the fresh
run does not have are left alone and listed. The read-off lines under a table ("- penalty:
costliest run ...", made with the table) follow the fresh ones of the same section too.

Usage: python3 docs/sync_tables.py FRESH_TABLES.md PAGE.md...   (docs/regenerate.sh runs it)
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "cli"))
import compare_tables as ct  # noqa: E402


READ_OFF = ": costliest run"


def read_offs(path):
    """{(section, setting): line} of the "- setting: costliest run ..." lines of a tables file."""
    found, section = {}, None
    for line in open(path, encoding="utf-8").read().split("\n"):
        if line.startswith("#"):
            section = line.lstrip("#").strip()
        elif line.startswith("- ") and READ_OFF in line:
            found[(section, line.split(READ_OFF)[0])] = line
    return found


def main():
    fresh = ct.tables(sys.argv[1])
    fresh_read_offs = read_offs(sys.argv[1])
    for page in sys.argv[2:]:
        lines = open(page, encoding="utf-8").read().split("\n")
        section, header, replaced, missing = None, None, 0, []
        table_section = None  # the fresh section of the page's last table
        for i, line in enumerate(lines):
            if line.startswith("#"):
                section, header = line.lstrip("#").strip(), None
                continue
            if not line.startswith("|"):
                header = None
                new = fresh_read_offs.get((table_section, line.split(READ_OFF)[0])) if READ_OFF in line else None
                if new is not None and new != line:
                    lines[i] = new
                    replaced += 1
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if all(ct.re.fullmatch(r":?-+:?", c) for c in cells):
                continue
            if header is None:
                header = cells
                continue
            name = section if section in fresh else next((n for n, t in fresh.items() if t[0] == header), None)
            table = fresh.get(name)
            if table is None or table[0] != header:
                continue
            table_section = name
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
        print(f"{page}: {replaced} rows and read-off lines replaced" + (f"; not in the fresh run: {missing}" if missing else ""))


if __name__ == "__main__":
    main()
