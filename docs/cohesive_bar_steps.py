#!/usr/bin/env python3
"""The cohesive bar of reference/cohesive_bar.h at three meshes and three steps (docs/fracture.md
"Where a cohesive crack may start"): cracks, dissipated energy against G_f x 0.19 m = 19 J/m, and
the worst post-peak departure from Hillerborg's u = P*C + w_c(1 - sigma/sigma_t) (C the taper's
compliance; the read-off of tests/test_cohesive.cpp bar_curve).

    python3 docs/cohesive_bar_steps.py build/bin OUT
"""
import csv
import json
import math
import subprocess
import sys
from pathlib import Path

E, ST, WC, GF_AREA = 1e10, 1e6, 2e-4, 19.0  # Pa, Pa, m, J/m
C = 2 / (E * 0.02) * math.log(0.2 / 0.19)  # m per N/m, the taper's compliance


def scene(h, dt, length=1.0):
    return {"plane": "stress",
            "materials": {"rock": {"density": 2500, "young": E, "poisson": 0.2,
                                   "strength": {"tensile": ST, "cohesion": 4e6, "friction_deg": 35,
                                                "fracture_energy": 100}}},
            "joint_sets": {"crack": {"friction_deg": 30, "normal": {"model": "constant", "kn": 1e13},
                                     "shear": {"model": "constant", "ks": 4e12}}},
            "bodies": [{"material": "rock", "outer": [[0, 0], [length / 2, 0.005], [length, 0], [length, 0.2],
                                                      [length / 2, 0.195], [0, 0.2]]}],
            "fracture": {"crack_set": "crack"}, "mesh": {"size": h},
            "supports": [{"points": [[0, 0], [0, 0.2]], "fix": "x"},
                         {"points": [[length, 0], [length, 0.2]], "fix": "x", "velocity": [1e-3, 0]}],
            "fixed_points": [[0, 0.1]], "measure_points": [[length - 0.001, 0.1], [0.001, 0.1]],
            "solver": {"time_step": dt, "steps": int(round(0.26 / dt)), "dynamic": False, "output_every": 1}}


def read_off(run):
    energy = list(csv.DictReader(open(run / "energy.csv")))
    ux = {}
    for r in csv.DictReader(open(run / "history.csv")):
        ux.setdefault(float(r["step"]), {})[float(r["point"])] = float(r["ux"])
    past, peak, worst = False, 0.0, 0.0
    for a, b in zip(energy, energy[1:]):
        dh = 1e-3 * (float(b["time"]) - float(a["time"]))
        if not dh > 0:
            continue
        force = (float(b["load_work"]) - float(a["load_work"])) / dh
        sigma = force / 0.19
        peak = max(peak, sigma)
        past = past or sigma < 0.95 * peak
        if not past or sigma < 0.1 * ST:
            continue
        p = ux[float(b["step"])]
        u, closed = p[0] - p[1], force * C + WC * (1 - sigma / ST)
        worst = max(worst, 100 * abs(u - closed) / closed)
    return worst


def main():
    bin_dir, out = sys.argv[1], Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    print("| h (m) | Δt (ms) | status | cracks | dissipated (J/m) | vs 19 J/m | worst post-peak (%) |")
    print("|---|---|---|---|---|---|---|")
    for h in (0.1, 0.05, 0.025):
        for dt in (2e-3, 1e-3, 5e-4):
            name = f"bar_{h}_{dt}"
            (out / f"{name}.json").write_text(json.dumps(scene(h, dt)))
            subprocess.run([f"{bin_dir}/nmm-preprocess", out / f"{name}.json", "-o", out / f"{name}.nmm"],
                           check=True, capture_output=True)
            run = out / name
            subprocess.run([f"{bin_dir}/nmm-solve", out / f"{name}.nmm", "-o", run, "-q"], capture_output=True)
            s = json.load(open(run / "summary.json"))
            f = s.get("fracture", {})
            d = f.get("dissipated_j", float("nan"))
            status = "ends" if s["stop_code"] == "ok" else f"stops at t = {s['stop_time']:.3g} s"
            print(f"| {h} | {1e3 * dt:g} | {status} | {f.get('cracks')} | {d:.4g} | {100 * (d / GF_AREA - 1):+.1f} % "
                  f"| {read_off(run):.2f} |")


if __name__ == "__main__":
    main()
