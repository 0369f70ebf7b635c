"""nmm.read_run on nmm-solve's folder, and nmm.plot's pictures (Matplotlib, Agg)."""
import json
import os

import matplotlib
import numpy as np
import pytest

import nmm
import nmm.plot
from conftest import tool

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def tool_run(meshes, tmp_path_factory):
    out = tmp_path_factory.mktemp("run") / "slope"
    tool("nmm-solve", meshes("jointed_slope"), "-o", out, "-q", "--contacts-gzip", "--set", "solver.steps=20",
         "--set", "solver.output_every=10")
    return str(out)


def test_read_run_of_nmm_solve(tool_run):
    run = nmm.read_run(tool_run)
    with open(os.path.join(tool_run, "summary.json")) as f:
        assert run.summary == json.load(f)
    assert run.ok and run.status == "ok"
    assert [s for _, s in run.frames] == [0, 10, 20]
    assert run.history["step"].dtype == np.int64
    assert set(run.history) == {"step", "time", "point", "x", "y", "ux", "uy"}
    p0 = run.point(0)
    np.testing.assert_array_equal(p0["step"], [0, 10, 20])
    with open(os.path.join(tool_run, "history.csv")) as f:
        last = f.read().strip().split("\n")[-1].split(",")
    assert run.history["uy"][-1] == float(last[-1])  # the same double as the text
    assert run.contacts is not None and (run.contacts["step"] > 0).all()  # read from .csv.gz
    assert run.energy is not None and run.run_history is not None
    frame = run.frame()
    assert frame.step == 20 and frame.displacement.shape[1] == 2
    assert len(frame.polygons()) == frame.stress.shape[0] == run.summary["manifold_elements"]
    with pytest.raises(KeyError, match="no frame of step 5"):
        run.frame(5)


def test_read_run_of_a_missing_folder(tmp_path):
    with pytest.raises(FileNotFoundError):
        nmm.read_run(tmp_path / "nothing")


def test_plot_mesh_and_result(meshes, tool_run, tmp_path):
    mesh = nmm.Mesh.load(meshes("jointed_slope"))
    ax = nmm.plot.mesh(mesh, cover=3, triangles=True)
    assert "physical cover 3" in ax.get_title()
    ax.figure.savefig(tmp_path / "mesh.png")
    ax = nmm.plot.result(nmm.read_run(tool_run))
    assert ax.get_title().startswith("|u| at t = 0.04 s")
    ax.figure.savefig(tmp_path / "result.png")
    solver = nmm.Solver(mesh, set={"solver.steps": 5})
    solver.run()
    ax = nmm.plot.result(solver, field="syy")
    ax.figure.savefig(tmp_path / "syy.png")
    for name in ("mesh.png", "result.png", "syy.png"):
        assert (tmp_path / name).stat().st_size > 10000
    with pytest.raises(ValueError, match="not one of"):
        nmm.plot.result(solver, field="temperature")
