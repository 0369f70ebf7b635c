#!/usr/bin/env python3
"""Petersson's notched beam with cohesive softening at three mesh sizes (docs/fracture.md
"Cohesive softening").

    python3 docs/cohesive_beam.py BIN_DIR OUT_DIR [--figure docs/figures/cohesive_beam.svg]
    python3 docs/cohesive_beam.py BIN_DIR OUT_DIR --stiffness   # the beam before it cracks
    python3 docs/cohesive_beam.py BIN_DIR OUT_DIR --to-zero     # h 0.025 m on to 6 mm, the load about zero
    ... --to-zero --sizes 0.025,0.0167,0.0125   # the three meshes so, and their curves in one figure
    ... --split-gap-ends   # either, with the slot's end carried on for the covers (docs/preprocess.md)

The beam of Petersson (1981, Lund TVBM-1006; docs/physics.md §6): span 2.0 m between roller
supports, depth 0.2 m, a notch 0.1 m deep and 10 mm wide at mid-span, E 30 GPa, nu 0.2, plane
stress, sigma_t 3.33 MPa, G_f 124 N/m (w_c = 74.5 um); crack faces kn 1e14 Pa/m; cover order 1
(docs/higher-order-covers.md). The test rested on rollers and was loaded through one, which let
the beam turn on them: each support and the load hold a strip 0.4 mm long (SUPPORT), the outline
having vertices at the strips' ends, the left support in x too (a pin). A strip held in y holds
the beam's end straight and takes a moment that grows with its length: the unnotched beam at cover
order 1, h 0.025 m, is 135.9 kN/m per mm on 2 cm strips, 118.4 on 4 mm and 116.4 on 2 mm against
116.6 simply supported, and after the peak, as the beam turns, the 4 mm strips (the scene until
2026-12-01, with a fixed point at (0.1, 0.01) that took most of the left reaction) pulled their
outer ends down and cracked the bottom skin over them at h 0.0125 m. The load strip (top, mid-span) moves down 1 um a static step
(dt 1 ms), 1000 equilibrium steps (static_mode "equilibrium", K d = F: DDA's static steps keep the
inertia term 2M/dt^2, a drag of about 0.7 kN/m at 1 um a step that the load work would pay):

        load v 1 mm/s
          ==
    +-----------------+---------------------------+      0.2 m
    |                 | notch 0.1 m               |
    +-----------------+---------------------------+
      ==                                        ==
   0.098-0.102 m         span 2.0 m      2.098-2.102 m

--stiffness runs the beam without cracks (tensile strength 1000x) to 0.1 mm at cover orders 0
and 1, and the same beam without its notch (closed form 116.6 kN/m per mm), and prints its stiffness, the slope of P against h between 0.05 and 0.1 mm (in DDA's static
steps their inertia adds a constant to P), against the closed form: a simply supported beam with shear,
S^3/(48EI) + S/(4 kappa G W), plus the notch's compliance 2/E * int_0^a (K/P)^2 da with K of a
three-point bend bar of S/W = 4 (Srawley 1976), 61.4 kN/m per mm.

Each run's load P (N per m of thickness) is the moving support's work per travel (energy.csv
load_work: dW/dh), its deflection h the support's travel. Writes OUT_DIR/cohesive_beam.csv
(h_mm, mesh, deflection_mm, load_kn_per_m) and the figure, and prints per mesh the peak, the
load work at the end (1 mm) and energy.csv's `fracture` there, each against the same beam's
converged answer (docs/cohesive_beam_reference.py, its curve docs/figures/cohesive_beam_reference.csv,
drawn dashed), the run's status and wall time. At 1 mm the crack has not parted the ligament: the
converged beam has taken 10.02 J/m of load work there, of the G_f x ligament = 12.4 J/m it takes
to full separation.
"""
import csv
import json
import pathlib
import resource
import subprocess

from figure_page import arguments, figure_path, page, write

SIZES = [0.025, 0.0167, 0.0125]
GF_LIGAMENT = 124.0 * 0.1  # J/m
REFERENCE = pathlib.Path(__file__).parent / "figures" / "cohesive_beam_reference.csv"
SUPPORT = 0.0004  # m, the length of each support strip and of the load strip
_s = SUPPORT / 2
OUTLINE = [[0, 0], [0.1 - _s, 0], [0.1 + _s, 0], [1.095, 0], [1.095, 0.1], [1.105, 0.1], [1.105, 0],
           [2.1 - _s, 0], [2.1 + _s, 0], [2.2, 0], [2.2, 0.2], [1.1 + _s, 0.2], [1.1 - _s, 0.2], [0, 0.2]]


def scene(h, split=False):
    return {
        "plane": "stress",
        "materials": {"concrete": {"density": 2400, "young": 3e10, "poisson": 0.2,
                                   "strength": {"tensile": 3.33e6, "cohesion": 10e6, "friction_deg": 35,
                                                "fracture_energy": 124}}},
        "joint_sets": {"crack": {"friction_deg": 30, "normal": {"model": "constant", "kn": 1e14},
                                 "shear": {"model": "constant", "ks": 4e13}}},
        "bodies": [{"material": "concrete", "outer": OUTLINE}],
        "fracture": {"crack_set": "crack"},
        "mesh": {"size": h, **({"split_gap_ends": True} if split else {})},
        "supports": [{"points": [[0.1 - SUPPORT / 2, 0], [0.1 + SUPPORT / 2, 0]], "fix": "xy"},
                     {"points": [[2.1 - SUPPORT / 2, 0], [2.1 + SUPPORT / 2, 0]], "fix": "y"},
                     {"points": [[1.1 - SUPPORT / 2, 0.2], [1.1 + SUPPORT / 2, 0.2]], "fix": "y",
                      "velocity": [0, -1e-3]}],
        "solver": {"time_step": 1e-3, "steps": 1000, "dynamic": False, "static_mode": "equilibrium",
                   "output_every": 2, "cover_order": 1},
    }


def curve(run):
    rows = list(csv.DictReader(open(run / "energy.csv")))
    out = []
    for a, b in zip(rows, rows[1:]):
        dh = 1e-3 * (float(b["time"]) - float(a["time"]))
        if dh > 0:
            out.append((1e3 * 1e-3 * 0.5 * (float(a["time"]) + float(b["time"])),
                        (float(b["load_work"]) - float(a["load_work"])) / dh / 1e3))
    return out, float(rows[-1]["load_work"])


def reference():
    """The converged curve [(deflection_mm, load_kn_per_m)] from the origin, the load work at 1 mm
    (J/m) and the dissipation there (J/m), of docs/cohesive_beam_reference.py."""
    rows = list(csv.DictReader(open(REFERENCE)))
    pts = [(0.0, 0.0)] + [(float(r["deflection_mm"]), float(r["load_kn_per_m"])) for r in rows]
    work, n = 0.0, 4000
    for i in range(n):  # the trapezoidal rule on the curve as drawn, straight between its points
        x0, x1 = i / n, (i + 1) / n
        work += 0.5 * (at(pts, x0) + at(pts, x1)) * (x1 - x0)
    diss = at([(float(r["deflection_mm"]), float(r["dissipated_j_per_m"])) for r in rows], 1.0)
    return pts, work, diss


def at(pts, x):
    """y of the polyline pts (ascending x) at x."""
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if x0 <= x <= x1:
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    return pts[-1][1]


def svg(curves, path, ref=None):
    w, ht, m = 640, 400, 60
    xmax = max(max(p[0] for p in c) for c in curves.values()) * 1.05
    ymax = max(max(p[1] for p in c) for c in curves.values()) * 1.1
    sx = lambda x: m + (w - 2 * m) * x / xmax
    sy = lambda y: ht - m - (ht - 2 * m) * max(y, 0) / ymax
    colours = ["#1f77b4", "#d62728", "#2ca02c"]
    parts = page(w, ht, 12) + [
             f'<line x1="{m}" y1="{ht - m}" x2="{w - m}" y2="{ht - m}" stroke="black"/>',
             f'<line x1="{m}" y1="{m}" x2="{m}" y2="{ht - m}" stroke="black"/>',
             f'<text x="{w / 2}" y="{ht - 20}" text-anchor="middle">load point deflection (mm)</text>',
             f'<text x="18" y="{ht / 2}" transform="rotate(-90 18 {ht / 2})" text-anchor="middle">load (kN per m)</text>']
    for k in range(6):
        x, y = xmax * k / 5, ymax * k / 5
        parts.append(f'<text x="{sx(x)}" y="{ht - m + 16}" text-anchor="middle">{x:.2f}</text>')
        parts.append(f'<text x="{m - 6}" y="{sy(y) + 4}" text-anchor="end">{y:.0f}</text>')
    for i, (h, c) in enumerate(curves.items()):
        pts = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y in c)
        parts.append(f'<polyline points="{pts}" fill="none" stroke="{colours[i]}" stroke-width="1.5"/>')
        parts.append(f'<text x="{w - m - 150}" y="{m + 16 * (i + 1)}" fill="{colours[i]}">h = {h} m</text>')
    if ref:
        pts = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y in ref if x <= xmax)
        parts.append(f'<polyline points="{pts}" fill="none" stroke="black" stroke-dasharray="5,4" stroke-width="1.2"/>')
        parts.append(f'<text x="{w - m - 150}" y="{m + 16 * (len(curves) + 1)}">converged (reference)</text>')
    write(parts, path)


def closed_form_stiffness(a=0.1):
    """N/m per m, P/h of the beam with a notch a deep (the docstring's compliance)."""
    e, w, span, nu = 3e10, 0.2, 2.0, 0.2

    def k_per_p(x):  # 1/m^(3/2): K/P per unit thickness, Srawley's S/W = 4 formula
        r = x / w
        f = 3 * r ** 0.5 * (1.99 - r * (1 - r) * (2.15 - 3.93 * r + 2.7 * r * r)) / (2 * (1 + 2 * r) * (1 - r) ** 1.5)
        return span / w ** 1.5 * f
    n = 4000
    crack = sum(2 / e * k_per_p((i + 0.5) * a / n) ** 2 * a / n for i in range(n))
    beam = span ** 3 / (48 * e * w ** 3 / 12) + span / (4 * 5 / 6 * e / (2 * (1 + nu)) * w)
    return 1 / (beam + crack)


def stiffness(a, out):
    split = a.split_gap_ends
    for notch in (True, False):
        exact = closed_form_stiffness(0.1 if notch else 0.0)
        for h in SIZES:
            for order in (0, 1):
                s = scene(h, split)
                if not notch:  # the notch's four outline vertices taken out
                    s["bodies"][0]["outer"] = OUTLINE[:3] + OUTLINE[7:]
                s["materials"]["concrete"]["strength"]["tensile"] *= 1000
                s["solver"].update({"steps": 100, "cover_order": order})
                tag = f"{h}_{order}" + ("" if notch else "_unnotched")
                name = out / f"elastic_{tag}"
                scene_file, mesh_file = out / f"elastic_{tag}.json", out / f"elastic_{tag}.nmm"
                scene_file.write_text(json.dumps(s))
                subprocess.run([f"{a.bin_dir}/nmm-preprocess", scene_file, "-o", mesh_file], check=True,
                               capture_output=True)
                subprocess.run([f"{a.bin_dir}/nmm-solve", mesh_file, "-o", name, "-q"], check=True, capture_output=True)
                pts = [p for p in curve(name)[0] if 0.05 <= p[0] <= 0.1]
                mx, my = sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts)
                k = sum((p[0] - mx) * (p[1] - my) for p in pts) / sum((p[0] - mx) ** 2 for p in pts)
                print(f"{'notched' if notch else 'unnotched'} h {h} m, cover order {order}: {k:.1f} kN/m per mm "
                      f"({100 * (k / (exact / 1e6) - 1):+.0f} % of the closed form {exact / 1e6:.1f})")


def to_zero(a, out):
    """The beam at each of --sizes (h 0.025 m unless told) on to 6 mm (--dt, one for all or one per
    size, 2 ms unless told: 2 um a step), where its load has fallen to about 1 % of its peak: per
    mm the load, energy.csv's load work, fracture, strain, springs and residual, against the
    converged beam run on to full separation (its load, load work and dissipation); the deflection
    where the load falls under 1 % of the peak, the load work there and the run's CPU time. Writes OUT_DIR/cohesive_beam_to_zero.csv and, with --figure or more than one size,
    the curves to 6 mm (cohesive_beam_to_zero.svg). --reuse reads OUT_DIR's runs of an earlier
    --to-zero instead of running them again."""
    if len(a.dt) not in (1, len(a.sizes)):
        raise SystemExit("--dt: one step for all sizes or one per size")
    rows = list(csv.DictReader(open(REFERENCE)))
    ref = list(zip([0.0] + [float(r["deflection_mm"]) for r in rows], [0.0] + [float(r["load_kn_per_m"]) for r in rows]))
    ref_diss = list(zip([0.0] + [float(r["deflection_mm"]) for r in rows], [0.0] + [float(r["dissipated_j_per_m"]) for r in rows]))
    curves = {}
    with open(out / "cohesive_beam_to_zero.csv", "w") as f:
        f.write("mesh_m,deflection_mm,load_kn_per_m\n")
        for h, dt in zip(a.sizes, a.dt * len(a.sizes) if len(a.dt) == 1 else a.dt):
            run, cpu = out / f"run_to_zero_{h}", None
            if not a.reuse:
                s = scene(h, a.split_gap_ends)
                s["solver"].update({"time_step": dt, "steps": round(6 / dt), "output_every": round(1e-2 / dt)})
                (out / f"beam_to_zero_{h}.json").write_text(json.dumps(s))
                subprocess.run([f"{a.bin_dir}/nmm-preprocess", out / f"beam_to_zero_{h}.json", "-o",
                                out / f"beam_to_zero_{h}.nmm"], check=True, capture_output=True)
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                with open(out / f"solve_to_zero_{h}.log", "w") as log:  # its messages (traces too)
                    subprocess.run([f"{a.bin_dir}/nmm-solve", out / f"beam_to_zero_{h}.nmm", "-o", run, "-q"],
                                   stdout=log, stderr=subprocess.STDOUT)
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
            c = curve(run)[0]
            curves[h] = c
            for x, y in c:
                f.write(f"{h},{x:.6g},{y:.6g}\n")
            to_zero_table(h, run, c, ref, ref_diss, cpu)
    if a.figure or len(a.sizes) > 1:
        svg(curves, figure_path(a, out, "cohesive_beam_to_zero.svg"), ref)


def work_at(energy, mm):
    """energy.csv's load work (J/m) at deflection mm, straight between its rows."""
    return at([(float(r["time"]), float(r["load_work"])) for r in energy], mm)


def to_zero_table(h, run, c, ref, ref_diss, cpu):
    """Prints one run of to_zero against the converged beam (ref: its load, ref_diss: its dissipation)."""
    energy = list(csv.DictReader(open(run / "energy.csv")))
    peak = max(p[1] for p in c)
    print(f"h {h} m\nmm | load kN/m (converged) | load work J/m (converged) | fracture J/m (converged) | strain | "
          f"springs | residual")
    for mm in (m for m in (1, 2, 3, 4, 5, 6) if m <= float(energy[-1]["time"]) + 1e-9):  # those the run reached
        e = min(energy, key=lambda r: abs(float(r["time"]) - mm))
        load = min(c, key=lambda p: abs(p[0] - mm))[1]
        n = 4000  # the converged curve's work to mm, straight between its points
        ref_work = sum(0.5 * (at(ref, mm * i / n) + at(ref, mm * (i + 1) / n)) * mm / n for i in range(n))
        print(f"{mm} | {load:.3f} ({at(ref, mm):.3f}) | {float(e['load_work']):.3f} ({ref_work:.3f}) | "
              f"{float(e['fracture']):.3f} ({at(ref_diss, mm):.3f}) | {float(e['strain']):.3f} | "
              f"{float(e['springs']):.3f} | {float(e['residual']):.4f}")
    low = next((p for p in c if p[0] > 1 and p[1] < 0.01 * peak), None)
    s = json.load(open(run / "summary.json"))
    work = float(energy[-1]["load_work"])
    print(f"{s['status']} after {s['steps_completed']} steps; peak {peak:.4g} kN/m; "
          + (f"under 1 % of it from {low[0]:.2f} mm (load work {work_at(energy, low[0]):.4g} J/m)" if low
             else "never under 1 % of it")
          + f"; at the end {c[-1][1]:.3g} kN/m ({100 * c[-1][1] / peak:.2f} %), load work {work:.4g} J/m "
          f"({100 * (work / GF_LIGAMENT - 1):+.1f} % of G_f x ligament {GF_LIGAMENT} J/m), fracture "
          f"{float(energy[-1]['fracture']):.4g} J/m, residual {float(energy[-1]['residual']):.4f} J/m; "
          f"{s['fracture']['cracks']} cracks" + (f"; {cpu:.1f} s CPU" if cpu is not None else ""))


def main():
    a, out = arguments([("--stiffness", {"action": "store_true"}), ("--split-gap-ends", {"action": "store_true"}),
                        ("--to-zero", {"action": "store_true"}), ("--reuse", {"action": "store_true"}),
                        ("--sizes", {"type": lambda t: [float(x) for x in t.split(",")], "default": [0.025]}),
                        ("--dt", {"type": lambda t: [float(x) for x in t.split(",")], "default": [2e-3]})])
    if a.stiffness:
        stiffness(a, out)
        return
    if a.to_zero:
        to_zero(a, out)
        return
    curves = {}
    ref, ref_work, ref_diss = reference()
    ref_peak = max(ref, key=lambda p: p[1])
    print(f"converged: peak {ref_peak[1]:.4g} kN/m at {ref_peak[0]:.3f} mm; load work at 1 mm {ref_work:.4g} J/m, "
          f"dissipated {ref_diss:.4g} J/m")
    with open(out / "cohesive_beam.csv", "w") as f:
        f.write("mesh_m,deflection_mm,load_kn_per_m\n")
        for h in SIZES:
            (out / f"beam_{h}.json").write_text(json.dumps(scene(h, a.split_gap_ends)))
            subprocess.run([f"{a.bin_dir}/nmm-preprocess", out / f"beam_{h}.json", "-o", out / f"beam_{h}.nmm"],
                           check=True, capture_output=True)
            run = out / f"run_{h}"
            subprocess.run([f"{a.bin_dir}/nmm-solve", out / f"beam_{h}.nmm", "-o", run, "-q"], capture_output=True)
            c, work = curve(run)
            curves[h] = c
            for x, y in c:
                f.write(f"{h},{x:.6g},{y:.6g}\n")
            s = json.load(open(run / "summary.json"))
            peak = max(c, key=lambda p: p[1])
            fracture = float(list(csv.DictReader(open(run / "energy.csv")))[-1]["fracture"])
            print(f"h {h} m: {s['status']} after {s['steps_completed']} steps ({s['wall_seconds']:.1f} s); peak "
                  f"{peak[1]:.4g} kN/m at {peak[0]:.3f} mm ({100 * (peak[1] / ref_peak[1] - 1):+.1f} %); load work "
                  f"{work:.4g} J/m ({100 * (work / ref_work - 1):+.1f} %; {100 * (work / GF_LIGAMENT - 1):+.1f} % of "
                  f"G_f x ligament {GF_LIGAMENT} J/m); fracture {fracture:.4g} J/m ({100 * (fracture / ref_diss - 1):+.1f} %); "
                  f"{s['fracture']['cracks']} cracks")
    svg(curves, figure_path(a, out, "cohesive_beam.svg"), ref)


if __name__ == "__main__":
    main()
