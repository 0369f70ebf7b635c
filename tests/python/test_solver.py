"""nmm.Solver: the run of nmm-solve stepped from Python — the same answers, the state as arrays,
outputs only when asked, restart, Ctrl-C, the progress callback, two solvers in two threads."""
import json
import os
import signal
import threading

import numpy as np
import pytest

import nmm
from conftest import tool


def summary_of(folder):
    with open(os.path.join(folder, "summary.json"), encoding="utf-8") as f:
        return json.load(f)


# Three scenes, each with a step count short enough for a test: nmm-solve and nmm.Solver on the
# same mesh file with the same --set give the same state_hash (docs/python.md, "Same answers").
SAME_ANSWER_RUNS = [("block_on_incline", 150), ("jointed_slope", 30), ("tunnel", 10)]


@pytest.mark.parametrize("name,steps", SAME_ANSWER_RUNS)
def test_state_hash_equals_nmm_solve(meshes, tmp_path, name, steps):
    tool("nmm-solve", meshes(name), "-o", tmp_path / "tool", "-q", "--set", f"solver.steps={steps}")
    expected = summary_of(tmp_path / "tool")["state_hash"]
    mesh = nmm.Mesh.load(meshes(name))
    solver = nmm.Solver(mesh, set={"solver.steps": steps})
    assert solver.run().ok
    assert solver.state_hash == expected
    # nmm.solve writes the same folder nmm-solve does
    run = nmm.solve(mesh, out=tmp_path / "py", set={"solver.steps": steps})
    assert run.state_hash == expected
    assert sorted(os.listdir(tmp_path / "py")) == sorted(os.listdir(tmp_path / "tool"))


def test_mesh_from_preprocess_runs_as_the_tools_mesh(meshes, tmp_path):
    tool("nmm-solve", meshes("block_on_incline"), "-o", tmp_path / "tool", "-q", "--set", "solver.steps=20")
    solver = nmm.Solver(nmm.preprocess(os.path.join(os.environ.get("NMM_SOURCE", "."), "data",
                                                    "block_on_incline.json")), set={"solver.steps": 20})
    solver.run()
    assert solver.state_hash == summary_of(tmp_path / "tool")["state_hash"]


def test_step_run_and_run_until_are_one_run(meshes):
    mesh = nmm.Mesh.load(meshes("block_on_incline"))
    whole = nmm.Solver(mesh)
    whole.run(steps=30)
    parts = nmm.Solver(mesh)
    for _ in range(10):
        assert parts.step().ok
    assert parts.steps_done == 10 and parts.time == pytest.approx(0.01)
    parts.run(steps=10)
    parts.run_until(0.03)
    assert parts.steps_done == whole.steps_done == 30
    assert parts.state_hash == whole.state_hash


def test_state_arrays_match_the_csvs(meshes, tmp_path):
    mesh = nmm.Mesh.load(meshes("jointed_slope"))
    solver = nmm.Solver(mesh, out=tmp_path / "run", set={"solver.steps": 20, "solver.output_every": 10},
                        text_frames=True)
    solver.run()
    run = nmm.read_run(tmp_path / "run")
    last = run.history["step"] == 20
    np.testing.assert_allclose(solver.measure_displacement[:, 0], run.history["ux"][last], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(solver.measure_displacement[:, 1], run.history["uy"][last], rtol=1e-12, atol=1e-15)
    frame = run.frame()
    assert frame.step == 20
    np.testing.assert_allclose(frame.displacement, solver.vertex_displacement, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(frame.stress, solver.element_stress, rtol=1e-12, atol=1e-6)
    contacts = solver.contacts()
    rows = run.contacts["step"] == 20
    assert len(contacts["x"]) == rows.sum() > 0
    for column in ("x", "y", "state", "normal_force", "shear_force", "vertex", "edge", "normal_stress"):
        np.testing.assert_allclose(contacts[column], run.contacts[column][rows], rtol=1e-12, err_msg=column)
    assert solver.summary["state_hash"] == run.summary["state_hash"]
    assert set(run.summary) <= set(solver.summary) | {"inputs", "files"}


def test_state_arrays_are_read_only_views_that_follow_the_run(meshes):
    solver = nmm.Solver(nmm.Mesh.load(meshes("block_on_incline")))
    u = solver.vertex_displacement
    assert u.shape == (solver.mesh.vertex_count, 2) and not u.flags.writeable
    with pytest.raises(ValueError):
        u[0, 0] = 1
    assert not u.any()
    solver.run(steps=50)
    assert u.any()  # the view follows the state
    np.testing.assert_allclose(solver.vertex_position, solver.mesh.element_vertices + u, rtol=0, atol=1e-12)
    assert solver.cover_unknowns.shape == (solver.mesh.cover_count, 2)
    assert solver.stress_coefficients.shape == (solver.mesh.element_count, 1, 3)


def test_block_slides_as_the_closed_form_says(meshes):
    # s(t) = ½ g (sin 30° − cos 30° tan 20°) t²: 0.226 m at t = 0.5 s (the scene's header)
    solver = nmm.Solver(nmm.Mesh.load(meshes("block_on_incline")))
    solver.run_until(0.5)
    travel = np.hypot(*solver.measure_displacement[0])
    closed = 0.5 * 9.81 * (np.sin(np.radians(30)) - np.cos(np.radians(30)) * np.tan(np.radians(20))) * 0.5 ** 2
    assert travel == pytest.approx(closed, rel=0.05)


def test_nothing_written_without_out(meshes, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    solver = nmm.Solver(nmm.Mesh.load(meshes("block_on_incline")))
    solver.run(steps=20)
    assert solver.out is None
    assert os.listdir(tmp_path) == []
    with pytest.raises(ValueError, match="out=DIR"):
        solver.pictures()


def test_restart_from_a_checkpoint_continues_the_run(meshes, tmp_path):
    mesh = nmm.Mesh.load(meshes("jointed_slope"))
    first = nmm.Solver(mesh, out=tmp_path / "a", set={"solver.steps": 15})
    first.run()
    second = nmm.Solver(mesh, restart=tmp_path / "a" / "checkpoint.nmmstate", set={"solver.steps": 15})
    assert second.step_number == 15 and second.steps_done == 0
    second.run()
    whole = nmm.Solver(mesh, set={"solver.steps": 30})
    whole.run()
    assert second.step_number == 30
    assert second.state_hash == whole.state_hash
    # the tool continues the same checkpoint to the same state
    tool("nmm-solve", mesh.path, "-o", tmp_path / "b", "-q", "--restart", tmp_path / "a" / "checkpoint.nmmstate",
         "--set", "solver.steps=15")
    assert summary_of(tmp_path / "b")["state_hash"] == whole.state_hash


def test_bad_checkpoint_and_bad_variants(meshes, tmp_path):
    mesh = nmm.Mesh.load(meshes("block_on_incline"))
    (tmp_path / "x.nmmstate").write_bytes(b"not a checkpoint")
    with pytest.raises(nmm.InputError) as e:
        nmm.Solver(mesh, restart=tmp_path / "x.nmmstate")
    assert e.value.file == str(tmp_path / "x.nmmstate") and not isinstance(e.value, nmm.SceneError)
    with pytest.raises(nmm.SceneError) as e:
        nmm.Solver(mesh, set={"solver.time_step": -1})
    assert e.value.where == "/solver/time_step"
    with pytest.raises(nmm.SceneError) as e:
        nmm.Solver(mesh, config={"joint_sets": {"interface": {"friction_deg": "steep"}}})
    assert "<config dict>" in e.value.file and e.value.where == "/joint_sets/interface/friction_deg"


def test_config_dict_is_a_merge_patch_as_config_file(meshes, tmp_path):
    patch = {"joint_sets": {"interface": {"friction_deg": 25}}, "solver": {"steps": 20}}
    (tmp_path / "v.json").write_text(json.dumps(patch))
    tool("nmm-solve", meshes("block_on_incline"), "-o", tmp_path / "tool", "-q", "--config", tmp_path / "v.json")
    solver = nmm.Solver(nmm.Mesh.load(meshes("block_on_incline")), config=patch)
    solver.run()
    assert solver.scene["joint_sets"]["interface"]["friction_deg"] == 25
    assert solver.state_hash == summary_of(tmp_path / "tool")["state_hash"]


def test_ctrl_c_keeps_the_results(meshes, tmp_path):
    mesh = nmm.Mesh.load(meshes("block_on_incline"))

    def interrupt(s):
        if s.steps_done == 7:
            os.kill(os.getpid(), signal.SIGINT)

    solver = nmm.Solver(mesh, out=tmp_path / "run", progress=interrupt)
    with pytest.raises(KeyboardInterrupt):
        solver.run(steps=100)
    assert solver.steps_done == 7 and solver.outcome.interrupted
    run = nmm.read_run(tmp_path / "run")
    assert run.status == "interrupted" and run.summary["steps_completed"] == 7
    assert run.state_hash == solver.state_hash
    # and it goes on from where it stopped: the checkpoint written, and the solver itself
    again = nmm.Solver(mesh, restart=tmp_path / "run" / "checkpoint.nmmstate")
    assert again.step_number == 7
    solver.run(steps=3)
    assert solver.steps_done == 10


def test_progress_callback_and_its_exception(meshes):
    seen = []
    solver = nmm.Solver(nmm.Mesh.load(meshes("block_on_incline")), progress=lambda s: seen.append(s.time))
    solver.run(steps=5)
    assert seen == pytest.approx([0.001 * k for k in range(1, 6)])

    def fail(s):
        raise RuntimeError("stop here")

    solver = nmm.Solver(nmm.Mesh.load(meshes("block_on_incline")), progress=fail)
    with pytest.raises(RuntimeError, match="stop here"):
        solver.run(steps=5)
    assert solver.steps_done == 1


def test_two_solvers_in_two_threads(meshes):
    mesh = nmm.Mesh.load(meshes("jointed_slope"))
    alone = nmm.Solver(mesh, set={"solver.steps": 20})
    alone.run()
    solvers = [nmm.Solver(mesh, set={"solver.steps": 20}) for _ in range(2)]
    errors = []

    def run(s):
        try:
            s.run()
        except BaseException as e:  # noqa: B902 - reported below
            errors.append(e)

    threads = [threading.Thread(target=run, args=(s,)) for s in solvers]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    assert solvers[0].state_hash == solvers[1].state_hash == alone.state_hash


def test_the_gil_is_released_while_stepping(meshes):
    # Another Python thread runs while a solver steps: it counts while run() is under way.
    solver = nmm.Solver(nmm.Mesh.load(meshes("jointed_slope")), set={"solver.steps": 20})
    count, done = [0], threading.Event()

    def counter():
        while not done.is_set():
            count[0] += 1

    t = threading.Thread(target=counter)
    t.start()
    before = count[0]
    solver.run()
    during = count[0] - before
    done.set()
    t.join()
    assert during > 1000


def test_one_solver_steps_in_one_thread_at_a_time(meshes):
    solver = nmm.Solver(nmm.Mesh.load(meshes("block_on_incline")), progress=lambda s: s.step())
    with pytest.raises(ValueError, match="stepping already"):
        solver.run(steps=2)
