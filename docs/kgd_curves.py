#!/usr/bin/env python3
"""The KGD hydraulic fracture in both regimes against their closed forms (docs/flow.md
"Hydraulic fracturing").

    python3 docs/kgd_curves.py BIN_DIR OUT_DIR [--figure docs/figures/kgd_curves.svg]

Runs the two KGD tests of tests/test_kgd.cpp (BIN_DIR/test_kgd, the scenes of reference/kgd.h)
with KGD_TRACE=1, which prints every accepted step's half-length, wellbore pressure and
wellbore opening next to the closed form's at that time: toughness-dominated (the K-vertex,
Griffith's crack under a uniform pressure) and viscosity-dominated (the M-vertex, Adachi &
Detournay 2002). Writes OUT_DIR/kgd_curves.csv (regime, time_s, half_length_m, closed_half_length_m,
pressure_pa, closed_pressure_pa, opening_m, closed_opening_m) and the figure: one row per regime,
columns half-length, wellbore pressure and wellbore opening against time, the run's steps as
dots, the closed form as a line. Prints each test's summary line (its errors at the growths).
"""
import os
import re
import subprocess

from figure_page import arguments, figure_path, page, write

TESTS = [("toughness", "Kgd.ToughnessDominatedLengthAndPressure", "K-vertex (K_m = 29)"),
         ("viscosity", "Kgd.ViscosityDominatedLengthOpeningAndPressure", "M-vertex (K_m = 0.046)")]
STEP = re.compile(r"t +([\d.]+) s: half-length ([\d.e+-]+) m \(closed form ([\d.e+-]+)\), wellbore p ([\d.e+-]+) Pa "
                  r"\(([\d.e+-]+)\), opening ([\d.e+-]+) m \(([\d.e+-]+)\)")


def run(bin_dir, name):
    env = dict(os.environ, KGD_TRACE="1")
    out = subprocess.run([f"{bin_dir}/test_kgd", f"--gtest_filter={name}"], env=env, capture_output=True, text=True)
    rows = [tuple(float(v) for v in m.groups()) for m in STEP.finditer(out.stdout)]
    summary = [line for line in out.stdout.splitlines() if line.startswith("kgd,")]
    return rows, summary


def panel(parts, x0, y0, w, h, rows, col, scale, label, title):
    """One panel: the run's column col (dots) and the closed form's col + 1 (line), times scale."""
    xs = [r[0] for r in rows]
    ys = [v for r in rows for v in (r[col] * scale, r[col + 1] * scale)]
    xmax, ymax = max(xs) * 1.05, max(ys) * 1.1
    sx = lambda x: x0 + w * x / xmax
    sy = lambda y: y0 + h - h * max(y, 0) / ymax
    parts.append(f'<line x1="{x0}" y1="{y0 + h}" x2="{x0 + w}" y2="{y0 + h}" stroke="black"/>')
    parts.append(f'<line x1="{x0}" y1="{y0}" x2="{x0}" y2="{y0 + h}" stroke="black"/>')
    parts.append(f'<text x="{x0 + w / 2}" y="{y0 - 8}" text-anchor="middle">{title}</text>')
    parts.append(f'<text x="{x0 + w / 2}" y="{y0 + h + 30}" text-anchor="middle">time (s)</text>')
    parts.append(f'<text x="{x0 - 42}" y="{y0 + h / 2}" transform="rotate(-90 {x0 - 42} {y0 + h / 2})" '
                 f'text-anchor="middle">{label}</text>')
    for k in range(5):
        x, y = xmax * k / 4, ymax * k / 4
        parts.append(f'<text x="{sx(x):.1f}" y="{y0 + h + 14}" text-anchor="middle">{x:.3g}</text>')
        parts.append(f'<text x="{x0 - 4}" y="{sy(y) + 4:.1f}" text-anchor="end">{y:.3g}</text>')
    line = " ".join(f"{sx(r[0]):.1f},{sy(r[col + 1] * scale):.1f}" for r in rows)
    parts.append(f'<polyline points="{line}" fill="none" stroke="#d62728" stroke-width="1.5"/>')
    for r in rows:
        parts.append(f'<circle cx="{sx(r[0]):.1f}" cy="{sy(r[col] * scale):.1f}" r="2" fill="#1f77b4"/>')


def svg(results, path):
    pw, ph, mx, my = 230, 170, 70, 60
    w, h = 3 * (pw + mx) + 20, len(results) * (ph + my + 30) + 50
    parts = page(w, h, 11) + [
             f'<circle cx="{mx}" cy="16" r="3" fill="#1f77b4"/><text x="{mx + 8}" y="20">nmm (each accepted step)</text>',
             f'<line x1="{mx + 200}" y1="16" x2="{mx + 230}" y2="16" stroke="#d62728" stroke-width="1.5"/>'
             f'<text x="{mx + 236}" y="20">closed form</text>']
    for i, (title, rows) in enumerate(results):
        y0 = 50 + i * (ph + my + 30)
        panel(parts, mx, y0, pw, ph, rows, 1, 1.0, "half-length (m)", f"{title}: half-length")
        panel(parts, mx + pw + mx, y0, pw, ph, rows, 3, 1e-6, "wellbore pressure (MPa)", f"{title}: pressure")
        panel(parts, mx + 2 * (pw + mx), y0, pw, ph, rows, 5, 1e3, "wellbore opening (mm)", f"{title}: opening")
    write(parts, path)


def main():
    a, out = arguments()
    results = []
    with open(out / "kgd_curves.csv", "w") as f:
        f.write("regime,time_s,half_length_m,closed_half_length_m,pressure_pa,closed_pressure_pa,opening_m,"
                "closed_opening_m\n")
        for regime, name, title in TESTS:
            rows, summary = run(a.bin_dir, name)
            for r in rows:
                f.write(regime + "," + ",".join(f"{v:.6g}" for v in r) + "\n")
            print("\n".join(summary) if summary else f"{name}: no summary line")
            results.append((title, rows))
    svg(results, figure_path(a, out, "kgd_curves.svg"))


if __name__ == "__main__":
    main()
