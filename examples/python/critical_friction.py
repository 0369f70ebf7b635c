"""The critical friction angle of a block, by bisection: each run decides the next.

    python3 examples/python/critical_friction.py [OUT]  # writes OUT/critical_friction.png (OUT: .)

data/block_on_incline.json: a block on a 30 degree incline. It slides when the friction angle
phi of the contact under it is below the critical angle, which for a rigid block on a plane is
the incline's angle, 30 degrees (tan phi = tan 30). The study finds it without being told:

    phi_low (slides) ---- phi_mid ---- phi_high (holds)
                             |
           run phi_mid for 0.2 s: travel > 0.1 mm ?  yes: phi_low = phi_mid
                                                      no:  phi_high = phi_mid

1. cut the scene once;
2. bracket: 20 degrees slides, 40 holds (checked, not assumed);
3. halve the bracket until it is narrower than 0.1 degree, one run per halving, each run the
   same mesh with joint_sets.interface.friction_deg set;
4. plot every trial's travel against phi, the bracket closing on the critical angle.
Takes about 2 s.
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
T_END = 0.2         # s, each trial's run
SLIDES = 1e-4       # m: a block that travelled more than this in T_END slides
TOLERANCE = 0.1     # degrees, the bracket's width at the end


def travel(mesh, phi):
    """The block's travel (m) after T_END with friction angle phi (degrees)."""
    solver = nmm.Solver(mesh, set={"joint_sets.interface.friction_deg": phi})
    outcome = solver.run_until(T_END)
    if not outcome.ok:
        raise SystemExit(f"phi = {phi}: {outcome.reason}")
    return float(np.hypot(*solver.measure_displacement[0]))


def main(out):
    mesh = nmm.preprocess(SCENE)                                     # 1.
    trials = []                                                      # (phi, travel)
    low, high = 20.0, 40.0                                           # 2.
    for phi, must_slide in ((low, True), (high, False)):
        trials.append((phi, travel(mesh, phi)))
        if (trials[-1][1] > SLIDES) != must_slide:
            raise SystemExit(f"the bracket is wrong: phi = {phi} {'holds' if must_slide else 'slides'}")
    while high - low > TOLERANCE:                                    # 3.
        mid = 0.5 * (low + high)
        trials.append((mid, travel(mesh, mid)))
        slides = trials[-1][1] > SLIDES
        print(f"phi = {mid:8.4f} deg: travel {1e3 * trials[-1][1]:8.4f} mm -> {'slides' if slides else 'holds'}")
        low, high = (mid, high) if slides else (low, mid)
    critical = 0.5 * (low + high)
    print(f"critical friction angle: {critical:.2f} deg (between {low:.3f} and {high:.3f}; "
          f"rigid block on a 30 deg plane: 30), {len(trials)} runs")

    fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")     # 4.
    phis, travels = np.array(trials).T
    ax.semilogy(phis, np.maximum(1e3 * travels, 1e-6), "o", color="C0")
    for k, (p, s) in enumerate(trials):
        ax.annotate(str(k + 1), (p, max(1e3 * s, 1e-6)), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.axhline(1e3 * SLIDES, color="0.6", ls=":", label=f"slides: travel > {1e3 * SLIDES:g} mm")
    ax.axvline(30.0, color="C3", lw=0.8, label="tan φ = tan 30°")
    ax.axvspan(low, high, color="C2", alpha=0.3, label=f"bracket at the end: {critical:.2f}°")
    ax.set_xlabel("friction angle φ (°)")
    ax.set_ylabel(f"travel at t = {T_END:g} s (mm)")
    ax.set_title(f"bisection of the critical friction angle: {len(trials)} runs, numbered")
    ax.legend(fontsize="small")
    path = os.path.join(out, "critical_friction.png")
    fig.savefig(path, dpi=120)
    print("wrote", path)
    if abs(critical - 30.0) > 0.5:
        raise SystemExit(f"critical angle {critical:.2f} deg is not 30 +- 0.5")


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    main(out)
