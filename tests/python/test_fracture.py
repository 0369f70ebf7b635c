"""A run that cracks, stepped from Python (docs/fracture.md, docs/python.md): the same state hash
as nmm-solve, and state arrays that are copies, since a crack re-cuts the mesh and the state's
arrays grow."""
import json
import os

import nmm
from conftest import tool


def test_brazilian_disc_cracks_as_nmm_solve_does(meshes, tmp_path):
    steps = 1060  # past the first crack (step 1049)
    tool("nmm-solve", meshes("brazilian_disc"), "-o", tmp_path / "tool", "-q", "--set", f"solver.steps={steps}")
    with open(tmp_path / "tool" / "summary.json", encoding="utf-8") as f:
        expected = json.load(f)
    assert expected["fracture"]["segments"] > 0
    solver = nmm.Solver(nmm.Mesh.load(meshes("brazilian_disc")), set={"solver.steps": steps})
    assert solver.run(steps=1040).ok
    before = solver.cover_unknowns
    covers = before.shape[0]
    assert solver.run_until(steps * 1e-3).ok
    after = solver.cover_unknowns
    assert after.shape[0] > covers                 # the cracks cut new covers
    assert before.shape[0] == covers               # the earlier array is a copy: still whole
    assert solver.summary["fracture"]["segments"] == expected["fracture"]["segments"]
    assert solver.state_hash == expected["state_hash"]
