"""Friction sweep: one mesh, thirteen runs, the block's travel against the friction angle.

    python3 examples/python/friction_sweep.py [OUT]     # writes OUT/friction_sweep.png (OUT: .)

data/block_on_incline.json: a 2 m x 1 m block on a 30 degree incline, the contact between them
of joint set "interface". With friction angle phi < 30 degrees the block slides, from rest,

         ___
        /  /  <- block                 s(t) = 1/2 g (sin 30 - cos 30 tan phi) t^2
    ___/__/____                        (no sliding, s = 0, for phi >= 30)
   /  base  (held)

1. cut the scene once (nmm.preprocess, as nmm-preprocess);
2. for each phi, a Solver on that mesh with joint_sets.interface.friction_deg = phi, run to
   t = 0.3 s, the measure point's travel read from its state (no files written);
3. plot the travel against phi with the closed form.
Takes about 3 s.
"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import nmm

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "..", "data", "block_on_incline.json")
T_END = 0.3  # s
G = 9.81     # m/s², the scene's gravity


def closed_form(phi_deg, t=T_END, slope_deg=30.0):
    a = G * (np.sin(np.radians(slope_deg)) - np.cos(np.radians(slope_deg)) * np.tan(np.radians(phi_deg)))
    return 0.5 * np.maximum(a, 0.0) * t ** 2


def main(out):
    mesh = nmm.preprocess(SCENE)                                    # 1.
    angles = np.arange(10.0, 40.1, 2.5)
    travel = []
    for phi in angles:                                              # 2.
        solver = nmm.Solver(mesh, set={"joint_sets.interface.friction_deg": phi})
        outcome = solver.run_until(T_END)
        if not outcome.ok:
            raise SystemExit(f"phi = {phi}: {outcome.reason}")
        travel.append(np.hypot(*solver.measure_displacement[0]))
        print(f"phi = {phi:4.1f} deg: travel {travel[-1]:.4f} m at t = {solver.time:.3f} s "
              f"(closed form {closed_form(phi):.4f} m)")
    travel = np.array(travel)

    fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")    # 3.
    fine = np.linspace(angles[0], angles[-1], 200)
    ax.plot(fine, 1e3 * closed_form(fine), color="0.5", label="closed form")
    ax.plot(angles, 1e3 * travel, "o", color="C0", label="nmm.Solver")
    ax.set_xlabel("friction angle φ (°)")
    ax.set_ylabel(f"travel at t = {T_END:g} s (mm)")
    ax.set_title("block on a 30° incline: one mesh, thirteen friction angles")
    ax.legend()
    path = os.path.join(out, "friction_sweep.png")
    fig.savefig(path, dpi=120)
    print("wrote", path)
    # What the picture must show: the closed form to a few per cent where the block slides.
    sliding = angles < 28
    worst = np.max(np.abs(travel[sliding] / closed_form(angles[sliding]) - 1))
    if worst > 0.05 or travel[angles > 30].max() > 1e-4:
        raise SystemExit(f"travel off the closed form by {worst:.1%} (or a block at phi > 30 moved)")


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    main(out)
