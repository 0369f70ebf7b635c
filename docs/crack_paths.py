#!/usr/bin/env python3
"""Crack paths grown by toughness against published ones (docs/crack-tips.md "A curved path",
"Wings from a closed flaw").

    python3 docs/crack_paths.py BIN_DIR OUT_DIR [--figure docs/figures/crack_paths.svg] [--no-wings] [--quick]

(--quick: the SCB specimen at R/25 alone, no wings: a check that the script runs, in seconds.)

1. The semi-circular bend specimen of Ayatollahi, Aliha & Hassani (2006, Mater. Sci. Eng. A 417):
   PMMA (E 3 GPa, nu 0.4, plane stress), radius R = 50 mm, an edge crack a = 0.3R from the middle
   of the flat side at beta = 30 deg to the load line, supports at x = -+0.43R (pinned left,
   roller right), the top pushed down 0.1 mm a static step; K_Ic 1 MPa.m^0.5 (the path does not
   depend on it), tip_step = h, at h = R/25, R/50, R/100:

                 | load
             .-''=''-.
           /     /     \\       the crack from (0, 0) at 30 deg to the vertical,
          |     /       |      a = 15 mm; it kinks away from the load line and
          '----+--------'      curves back to the loading point
           ^   0    ^
         -21.5 mm  21.5 mm

   Their tested path and their GMTS computation (x at heights y, read off their figure; the
   digitisation of Loiseau's gcrack reference files interpolated at these heights) are drawn
   with the runs' paths (the crack segments as cut, cracks.csv).
2. (unless --no-wings) Wing cracks from a closed flaw 2a = 0.5 m at 45 deg in a 5 m x 5 m plate
   (E 10 GPa, nu 0.25, plane strain), faces of friction 30 deg, under a uniaxial compression that
   grows 0.03 MPa a step from 1.8 MPa; K_Ic 0.5 MPa.m^0.5 (closed form of the first growth:
   sigma_c = K_Ic / ((2/sqrt 3) sqrt(pi a) (sin b cos b - tan phi cos^2 b)) = 2.31 MPa), h = 0.025 m,
   tip_step = 4h.

Writes OUT_DIR/crack_paths.csv (case, mesh_m, step, x0_m, y0_m, x1_m, y1_m: every segment as
cut, read from the run's checkpoint) and the figure, and prints per run its status, wall time, the x of the SCB path at the
heights of the published points and its largest distance from them, and the wings' first growth
(step, load, angle from the flaw).
"""
import json
import math
import pathlib
import struct
import subprocess

from figure_page import arguments, figure_path, page, write

R = 0.05
SCB_SIZES = [R / 25, R / 50, R / 100]
Y_MM = [15, 17.5, 20, 22.5, 25, 27.5, 30, 32.5, 35, 37.5, 40, 42.5, 45]
TEST_MM = [6.20, 4.51, 3.14, 1.90, 1.27, 0.83, 0.50, 0.33, 0.13, -0.07, -0.20, -0.26, -0.39]
GMTS_MM = [6.29, 5.04, 4.13, 3.38, 2.74, 2.27, 1.97, 1.62, 1.27, 1.11, 0.97, 0.84, 0.68]


def scb(h):
    s, a, beta = 0.43 * R, 0.3 * R, math.radians(30)
    w = 0.5 * h
    top = math.sqrt(R * R - 0.25 * w * w)
    outer = [[-R, 0], [-s - h / 2, 0], [-s + h / 2, 0], [0, 0], [s - h / 2, 0], [s + h / 2, 0], [R, 0]]
    n = max(48, int(math.pi * R / h))
    for i in range(1, n):
        t = i * math.pi / n
        x = R * math.cos(t)
        if abs(t - math.pi / 2) < 1.5 * math.asin(w / (2 * R)):
            continue
        if x < -w / 2 and outer[-1][0] > w / 2:
            outer += [[w / 2, top], [-w / 2, top]]
        outer.append([x, R * math.sin(t)])
    return {
        "plane": "stress",
        "materials": {"pmma": {"density": 1180, "young": 3e9, "poisson": 0.4,
                               "strength": {"tensile": 1e9, "cohesion": 1e9, "friction_deg": 30, "toughness": 1e6}}},
        "joint_sets": {"crack": {"friction_deg": 30, "normal": {"model": "constant", "kn": 1e13},
                                 "shear": {"model": "constant", "ks": 4e12}}},
        "bodies": [{"material": "pmma", "outer": outer}],
        "joints": [{"set": "crack", "points": [[0, 0], [a * math.sin(beta), a * math.cos(beta)]]}],
        "mesh": {"size": h},
        "fracture": {"crack_set": "crack", "tip_step": h},
        "supports": [{"points": [[-s - h / 2, 0], [-s + h / 2, 0]], "fix": "xy"},
                     {"points": [[s - h / 2, 0], [s + h / 2, 0]], "fix": "y"},
                     {"points": [[w / 2, top], [-w / 2, top]], "fix": "y", "velocity": [0, -1e-4]}],
        "solver": {"time_step": 1, "steps": 8, "dynamic": False, "static_mode": "equilibrium"},
    }


def wings(h):
    half, a, b = 2.5, 0.25, math.pi / 4
    load = [[0, 1.8], [100, 4.8]]  # x 1 MPa: 0.03 MPa a step
    return {
        "plane": "strain",
        "materials": {"rock": {"density": 2500, "young": 1e10, "poisson": 0.25,
                               "strength": {"tensile": 1e9, "cohesion": 1e9, "friction_deg": 30, "toughness": 0.5e6}}},
        "joint_sets": {"crack": {"friction_deg": 30, "normal": {"model": "constant", "kn": 1e12},
                                 "shear": {"model": "constant", "ks": 4e11}}},
        "bodies": [{"material": "rock", "outer": [[-half, -half], [half, -half], [half, half], [-half, half]]}],
        "joints": [{"set": "crack", "points": [[-a * math.cos(b), -a * math.sin(b)], [a * math.cos(b), a * math.sin(b)]]}],
        "mesh": {"size": h},
        "fracture": {"crack_set": "crack", "tip_step": 4 * h},
        "tractions": [{"points": [[-half, half], [half, half]], "normal": -1e6, "shear": 0, "table": load},
                      {"points": [[-half, -half], [half, -half]], "normal": -1e6, "shear": 0, "table": load}],
        "fixed_points": [[0, -half + 0.01 * h]],
        "supports": [{"points": [[half - 0.5 * h, -half], [half, -half]], "fix": "y"}],
        "solver": {"time_step": 1, "steps": 30, "dynamic": False, "static_mode": "equilibrium"},
    }


def segments_as_cut(checkpoint):
    """(step, x0, y0, x1, y1) of every crack segment as cut (the reference configuration, as a
    broken specimen's path is measured), from the checkpoint's FRACTURE section
    (docs/checkpoint-format.md); cracks.csv has the ends where they were when they formed, moved
    by the run's displacement (0.1-0.6 mm in x along the specimen's path)."""
    b = pathlib.Path(checkpoint).read_bytes()
    (count,) = struct.unpack_from("<I", b, 16)
    for i in range(count):
        tag, offset, size = struct.unpack_from("<8sQQ", b, 32 + 32 * i)
        if tag.rstrip(b"\0") == b"FRACTURE":
            break
    else:
        return []
    at = offset + 1 + 4  # u8 tips started, i32 cracks
    (n,) = struct.unpack_from("<Q", b, at)
    at += 8 + n * (4 * 8 + 4 + 1)  # tips
    for _ in range(2):  # armed, debris: u8 per element
        (n,) = struct.unpack_from("<Q", b, at)
        at += 8 + n
    at += 4 + 8  # debris blocks, debris area
    (n,) = struct.unpack_from("<Q", b, at)
    at += 8
    segs = []
    for _ in range(n):
        ax, ay, bx, by = struct.unpack_from("<4d", b, at)
        (step,) = struct.unpack_from("<q", b, at + 8 * 8 + 1 + 4)
        segs.append((step, ax, ay, bx, by))
        at += 8 * 8 + 1 + 4 + 8 + 8
    return segs


def run(bin_dir, out, name, doc):
    (out / f"{name}.json").write_text(json.dumps(doc))
    subprocess.run([f"{bin_dir}/nmm-preprocess", out / f"{name}.json", "-o", out / f"{name}.nmm"], check=True,
                   capture_output=True)
    subprocess.run([f"{bin_dir}/nmm-solve", out / f"{name}.nmm", "-o", out / name, "-q"], capture_output=True)
    summary = json.load(open(out / name / "summary.json"))
    return summary, segments_as_cut(out / name / "checkpoint.nmmstate")


def x_at(segs, y):
    for _, x0, y0, x1, y1 in segs:
        if y1 != y0 and (y - y0) * (y - y1) <= 0:
            return x0 + (x1 - x0) * (y - y0) / (y1 - y0)
    return float("nan")


def svg(scb_paths, wing_paths, path):
    width, height = 840 if wing_paths else 420, 440
    colours = ["#1f77b4", "#d62728", "#2ca02c"]
    parts = page(width, height, 12)
    # Left: the SCB specimen about the crack, 1 mm = 7 px (x -20..32 mm, y 0..53 mm).
    ox, oy, k = 160, 410, 7.0
    px = lambda x: ox + k * 1e3 * x
    py = lambda y: oy - k * 1e3 * y
    arc = " ".join(f"{px(R * math.cos(t * math.pi / 180)):.1f},{py(R * math.sin(t * math.pi / 180)):.1f}"
                   for t in range(50, 115))
    parts.append(f'<polyline points="{px(-0.02):.1f},{py(0):.1f} {px(0.032):.1f},{py(0):.1f}" stroke="#888" fill="none"/>')
    parts.append(f'<polyline points="{arc}" stroke="#888" fill="none"/>')
    parts.append(f'<line x1="{px(0)}" y1="{py(0)}" x2="{px(0.015 * math.sin(math.pi / 6)):.1f}" '
                 f'y2="{py(0.015 * math.cos(math.pi / 6)):.1f}" stroke="black" stroke-width="2"/>')
    for name, xs, style in (("test (Ayatollahi et al. 2006)", TEST_MM, 'stroke="black" stroke-dasharray="5,3"'),
                            ("their GMTS computation", GMTS_MM, 'stroke="#777" stroke-dasharray="2,2"')):
        pts = " ".join(f"{px(1e-3 * x):.1f},{py(1e-3 * y):.1f}" for x, y in zip(xs, Y_MM))
        parts.append(f'<polyline points="{pts}" fill="none" {style} stroke-width="1.5"/>')
    for i, (h, segs) in enumerate(scb_paths.items()):
        pts = " ".join([f"{px(segs[0][1]):.1f},{py(segs[0][2]):.1f}"] + [f"{px(s[3]):.1f},{py(s[4]):.1f}" for s in segs])
        parts.append(f'<polyline points="{pts}" fill="none" stroke="{colours[i]}" stroke-width="1.2"/>')
    legend = [("test (Ayatollahi et al. 2006), dashed", "black"), ("their GMTS computation, dotted", "#777")]
    legend += [(f"nmm, h = R/{round(R / h)} = {1e3 * h:.1f} mm", colours[i]) for i, h in enumerate(scb_paths)]
    for i, (text, colour) in enumerate(legend):
        parts.append(f'<text x="{px(0.0105):.0f}" y="{py(0.016) + 16 * i:.0f}" fill="{colour}">{text}</text>')
    parts.append(f'<text x="210" y="18" text-anchor="middle">semi-circular bend, beta 30 deg (R 50 mm): the path</text>')
    parts.append(f'<text x="{px(0.0):.0f}" y="{py(0) + 18:.0f}" text-anchor="middle">crack mouth (0, 0)</text>')
    if wing_paths:
        # Right: the flaw and its wings, 1 m = 300 px about the plate's centre.
        cx, cy, kw = 630, 225, 300.0
        qx = lambda x: cx + kw * x
        qy = lambda y: cy - kw * y
        a = 0.25 / math.sqrt(2)
        parts.append(f'<line x1="{qx(-a):.1f}" y1="{qy(-a):.1f}" x2="{qx(a):.1f}" y2="{qy(a):.1f}" stroke="black" '
                     'stroke-width="2"/>')
        for _, x0, y0, x1, y1 in wing_paths:
            parts.append(f'<line x1="{qx(x0):.1f}" y1="{qy(y0):.1f}" x2="{qx(x1):.1f}" y2="{qy(y1):.1f}" '
                         f'stroke="{colours[0]}" stroke-width="1.5"/>')
        for y in (0.58, -0.6):
            parts.append(f'<text x="{cx}" y="{qy(y) + 4:.0f}" text-anchor="middle">compression (along y)</text>')
        parts.append(f'<text x="{cx}" y="18" text-anchor="middle">wings from a closed flaw (2a 0.5 m, 45 deg, friction 30 deg)</text>')
    write(parts, path)


def main():
    a, out = arguments([("--no-wings", {"action": "store_true"}), ("--quick", {"action": "store_true"})])
    scb_paths, wing_paths = {}, []
    with open(out / "crack_paths.csv", "w") as f:
        f.write("case,mesh_m,step,x0_m,y0_m,x1_m,y1_m\n")
        for h in SCB_SIZES[:1] if a.quick else SCB_SIZES:
            s, segs = run(a.bin_dir, out, f"scb_{h:.5f}", scb(h))
            scb_paths[h] = segs
            for seg in segs:
                f.write(f"scb,{h:.6g},{seg[0]}," + ",".join(f"{v:.6g}" for v in seg[1:]) + "\n")
            xs = [1e3 * x_at(segs, 1e-3 * y) for y in Y_MM]
            d_test = max(abs(x - t) for x, t in zip(xs, TEST_MM))
            d_gmts = max(abs(x - g) for x, g in zip(xs, GMTS_MM))
            first = math.degrees(math.atan2(segs[0][4] - segs[0][2], segs[0][3] - segs[0][1]))
            print(f"SCB h {1e3 * h:.1f} mm: {s['status']} ({s['wall_seconds']:.1f} s), {len(segs)} segments, first at "
                  f"{first:.1f} deg from +x; x (mm) at y {Y_MM[0]}..{Y_MM[-1]} mm: {' '.join(f'{x:.2f}' for x in xs)}; "
                  f"largest distance from the test {d_test:.2f} mm, from GMTS {d_gmts:.2f} mm")
        if not a.no_wings and not a.quick:
            h = 0.025
            s, segs = run(a.bin_dir, out, "wings", wings(h))
            wing_paths = segs
            for seg in segs:
                f.write(f"wings,{h:.6g},{seg[0]}," + ",".join(f"{v:.6g}" for v in seg[1:]) + "\n")
            if segs:
                step = segs[0][0]
                sigma = 1.8 + 0.03 * step
                first = math.degrees(math.atan2(segs[0][4] - segs[0][2], segs[0][3] - segs[0][1]))
                print(f"wings h {h} m: {s['status']} ({s['wall_seconds']:.1f} s), {len(segs)} segments; first growth at "
                      f"step {step}, sigma {sigma:.3f} MPa ({100 * (sigma / 2.3125 - 1):+.1f} % of sigma_c 2.31 MPa), "
                      f"first segment at {first:.1f} deg from +x")
    svg(scb_paths, wing_paths, figure_path(a, out, "crack_paths.svg"))


if __name__ == "__main__":
    main()
