"""Cracks and crack tips as NumPy arrays while the run steps (docs/python.md "Cracks and crack
tips"): Solver.cracks() and Solver.crack_tips() give, step by step, what cracks.csv and
crack_tips.csv of the same run hold.

The run: a 2 m × 4 m plate with a centre crack 2a = 1 m (h = 0.1 m, plane strain), pulled by its
top edge (a support moving up; the bottom on rollers), K_Ic = 1.5 MPa·√m and a strength it never
reaches (tests/test_crack_tips.cpp TipsGrowWhenKReachesTheToughness at h = a/5): the first step
loads it to about 90 % of the critical load, each further step by 0.5 % more, so its two tips
grow straight ahead by toughness after about twenty steps."""
import csv
import math

import numpy as np
import pytest

import nmm

STEPS = 30


def plate():
    w, h, a, size = 1.0, 2.0, 0.5, 0.1
    return {
        "plane": "strain",
        "materials": {"rock": {"density": 2500, "young": 1e10, "poisson": 0.25,
                               "strength": {"tensile": 1e9, "cohesion": 1e9, "friction_deg": 30,
                                            "toughness": 1.5e6}}},
        "joint_sets": {"crack": {"friction_deg": 30, "normal": {"model": "constant", "kn": 1e12},
                                 "shear": {"model": "constant", "ks": 4e11}}},
        "bodies": [{"material": "rock", "outer": [[-w, -h], [w, -h], [w, h], [-w, h]]}],
        "joints": [{"set": "crack", "points": [[-a, 0], [a, 0]]}],
        "fracture": {"crack_set": "crack"},
        "mesh": {"size": size},
        "fixed_points": [[0, -h + 0.01 * size]],
        "supports": [{"points": [[-w, -h], [w, -h]], "fix": "y"},
                     {"points": [[-w, h], [w, h]], "fix": "xy", "velocity": [0, 2e-6],
                      "table": [[0, 210], [1, 210], [1.000001, 1]]}],
        "solver": {"time_step": 1, "steps": STEPS, "dynamic": False, "static_mode": "equilibrium",
                   "output_every": 1},
    }


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """The plate stepped from Python: the arrays after every step, then the run's CSV files."""
    out = tmp_path_factory.mktemp("cracks") / "run"
    solver = nmm.Solver(nmm.preprocess(plate()), out=out)
    tips, cracks = {}, {}
    for _ in range(STEPS):
        assert solver.step().ok
        tips[solver.step_number] = solver.crack_tips()
        cracks[solver.step_number] = solver.cracks()
    solver.flush()
    return solver, tips, cracks, out


def rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_segments_are_cracks_csv(run):
    solver, _, cracks, out = run
    table = rows(out / "cracks.csv")
    last = cracks[STEPS]
    assert len(table) > 0, "the tips must grow within the run"
    assert len(last["x0"]) == len(table) and solver.summary["fracture"]["segments"] == len(table)
    for k in ("x0", "y0", "x1", "y1", "time"):
        assert last[k].dtype == np.float64
        np.testing.assert_allclose(last[k], [float(r[k]) for r in table], rtol=1e-8, atol=1e-12)
    np.testing.assert_array_equal(last["step"], [int(r["step"]) for r in table])
    np.testing.assert_array_equal(last["mode"], [0 if r["mode"] == "tensile" else 1 for r in table])
    # Mode I growth by toughness: tensile segments, along the crack's line.
    assert np.all(last["mode"] == 0)
    assert np.max(np.abs(last["y1"])) < math.tan(math.radians(0.5)) * 1.0
    # While it steps: none before the first growth, the same rows from then on.
    first = int(table[0]["step"])
    for step, c in cracks.items():
        assert len(c["x0"]) == sum(1 for r in table if int(r["step"]) <= step), step
    assert len(cracks[first - 1]["x0"]) == 0


def test_tips_are_crack_tips_csv_at_every_step(run):
    _, tips, _, out = run
    table = rows(out / "crack_tips.csv")
    by_step = {}
    for r in table:
        by_step.setdefault(int(r["step"]), []).append(r)
    # The start and every step while there are tips (output_every 1): the tips run to the plate's
    # sides within the step they start growing (load control of a centre crack is unstable).
    assert sorted(by_step) == list(range(0, max(by_step) + 1)) and max(by_step) >= 20
    for step, t in tips.items():
        expected = by_step.get(step, [])
        assert len(t["tip"]) == len(expected), step
        np.testing.assert_array_equal(t["tip"], [int(r["tip"]) for r in expected])
        for k, col in (("x", "x"), ("y", "y"), ("k1", "k1"), ("k2", "k2")):
            np.testing.assert_allclose(t[k], [float(r[col]) for r in expected], rtol=1e-8, atol=1e-3)
        # crack_tips.csv writes the angle to 6 significant digits.
        np.testing.assert_allclose(t["angle_deg"], [float(r["angle_deg"]) for r in expected], atol=1e-3)
        assert t["direction"].shape == (len(expected), 2)
        np.testing.assert_allclose(np.hypot(t["direction"][:, 0], t["direction"][:, 1]), 1.0, rtol=1e-12)


def test_tips_before_growth_are_mode_one(run):
    """The symmetric crack opens in mode I: K_II is 0.2 % of K_I (its closed form is 0; the top's
    support, held in x, adds the 0.2 %), and each tip's growth direction is straight ahead within
    0.5° (0° at the right tip, 180° at the left)."""
    _, tips, cracks, _ = run
    step = min(s for s, c in cracks.items() if len(c["x0"]) > 0) - 1
    t = tips[step]
    assert len(t["tip"]) == 2 and np.all(t["k1"] > 1e6)
    assert np.all(np.abs(t["k2"]) < 5e-3 * t["k1"])
    right, left = np.argmax(t["x"]), np.argmin(t["x"])
    assert abs(t["angle_deg"][right]) < 0.5 and abs(abs(t["angle_deg"][left]) - 180) < 0.5
    # Just before growth K_I is just below K_Ic.
    assert np.all(t["k1"] < 1.5e6) and np.all(t["k1"] > 0.97 * 1.5e6)
