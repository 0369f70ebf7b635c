#!/usr/bin/env python3
"""The Brazilian discs of the fracturing matrix, elastic: the centre's tension against the load
(docs/fracture.md "Robustness matrix").

    python3 docs/disc_centre_stress.py BUILD_DIR [--sizes 12 16 20 32 48]

Takes each disc cell's scene (`fracture_matrix CASE --scene FILE`), removes its strength and its
fracture block, sets h = D/n, and runs it elastic (the nmm module from BUILD_DIR/python) to
0.8 of the time at which the closed form expects the first crack. Prints, per mesh size, the
load P = |sum A_e sigma_yy,e| / H over the disc (N/m; exact for the discrete equilibrium, the
matrix's own reading) and sigma_xx of the element at the centre against
  - Hondros (uniform radial pressure over the flats): 2P/(pi D) (sin 2a - a)/sin a,
  - a rigid flat (flat punch over the flats, reference/rock_tests.h): 2P/(pi D) pi cos 2a / (2 E(sin a)),
and the largest sigma_1 of any element of the disc (the one that cracks first) against the
rigid flat's centre value: its inverse is the first crack's load against the closed form.
Three set-ups: disc_flats (flats held by supports), disc_platens (steel platens, frictionless
as in the matrix) and disc_platens with 10 degrees of friction at the platens.
"""
import argparse
import json
import math
import pathlib
import subprocess
import sys
import tempfile
import warnings


def run(build, case, n, friction_deg):
    import nmm
    import numpy as np
    with tempfile.TemporaryDirectory() as tmp:
        scene = pathlib.Path(tmp) / "scene.json"
        subprocess.run([str(build / "bin" / "fracture_matrix"), case, "--scene", str(scene)], check=True)
        d = json.loads(scene.read_text())
    d.pop("fracture", None)
    d["materials"]["rock"].pop("strength", None)
    platens = "platens" in case
    D = 0.2 if platens else 1.0
    R, a = D / 2, math.radians(10)
    H = D * math.cos(a)
    d["mesh"]["size"] = D / n
    if friction_deg is not None:
        d["joint_sets"]["platen"]["friction_deg"] = friction_deg
    t_crack = d["solver"]["steps"] * d["solver"]["time_step"] / 1.2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the platens are thinner than a few elements at D/12
        mesh = nmm.preprocess(nmm.Scene(d))
    solver = nmm.Solver(mesh)
    out = solver.run_until(0.8 * t_crack)
    s = solver.element_stress
    disc = mesh.element_body == 0
    P = abs((mesh.element_areas()[disc] * s[disc, 1]).sum()) / H
    centre = [e for e in range(mesh.element_count) if disc[e] and inside(mesh.element_polygon(e), R, R)]
    sxx = s[centre, 0].mean()
    s1 = 0.5 * (s[:, 0] + s[:, 1]) + np.sqrt((0.5 * (s[:, 0] - s[:, 1])) ** 2 + s[:, 2] ** 2)
    s1_max = s1[disc].max()
    line = 2 * P / (math.pi * D)
    hondros = line * (math.sin(2 * a) - a) / math.sin(a)
    rigid = line * math.pi * math.cos(2 * a) / (2 * ellipe(math.sin(a)))
    return out.ok, P, sxx / hondros, sxx / rigid, s1_max / rigid


def ellipe(k, n=2000):
    """The complete elliptic integral of the second kind, modulus k (Simpson, n intervals)."""
    h = math.pi / 2 / n
    f = [math.sqrt(1 - (k * math.sin(i * h)) ** 2) for i in range(n + 1)]
    return h / 3 * (f[0] + f[-1] + 4 * sum(f[1:-1:2]) + 2 * sum(f[2:-1:2]))


def inside(poly, x, y):
    c = False
    for i in range(len(poly)):
        (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % len(poly)]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            c = not c
    return c


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("build", type=pathlib.Path)
    ap.add_argument("--sizes", type=int, nargs="+", default=[12, 16, 20, 32, 48], help="D/h")
    args = ap.parse_args()
    sys.path.insert(0, str(args.build / "python"))
    print(f"{'set-up':28} {'D/h':>4} {'P (N/m)':>11} {'sxx/Hondros':>12} {'sxx/rigid':>10} {'s1max/rigid':>12}")
    for label, case, friction in (("flats (supports)", "disc_flats.h1.static.slow", None),
                                  ("platens, frictionless", "disc_platens.h1.static.slow", None),
                                  ("platens, friction 10 deg", "disc_platens.h1.static.slow", 10)):
        for n in args.sizes:
            ok, P, rh, rr, r1 = run(args.build, case, n, friction)
            print(f"{label:28} {n:>4} {P:>11.5g} {rh:>12.4f} {rr:>10.4f} {r1:>12.4f}{'' if ok else '  (stopped)'}")


if __name__ == "__main__":
    main()
