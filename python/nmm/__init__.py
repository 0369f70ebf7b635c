"""nmm: the Numerical Manifold Method for jointed rock, from Python (docs/python.md).

The module runs in this process on the same library as the command-line tools:

    scene = nmm.Scene("data/jointed_slope.json")      # or a dict; nmm.SceneError on a bad one
    mesh = nmm.preprocess(scene)                        # nmm-preprocess; mesh.save("slope.nmm")
    solver = nmm.Solver(mesh, set={"joint_sets.bedding.friction_deg": 25})
    solver.run(steps=100)                               # nmm-solve, stepped from Python
    solver.vertex_displacement, solver.contacts(), solver.summary

    run = nmm.solve(mesh, out="slope_run")              # nmm-solve -o slope_run, read back
    run.summary["state_hash"], run.history["uy"]
    nmm.plot.result(run)                                # Matplotlib (import nmm.plot)

The same mesh and settings give the same state_hash as nmm-solve.
"""
import os
import warnings

from .errors import InputError, RunError, SceneError, SceneWarning
from ._nmm import Mesh, Outcome, Scene, Solver, __version__
from . import _nmm
from .run import Frame, Run, read_run

__all__ = ["Scene", "Mesh", "Solver", "Outcome", "Run", "Frame", "preprocess", "solve", "read_run",
           "InputError", "SceneError", "RunError", "SceneWarning", "__version__"]


def preprocess(scene, set=None, strict_joints=False):
    """The mesh of a scene, as nmm-preprocess cuts it (nmm.Mesh).

    scene: an nmm.Scene, a scene file's path or the scene as a dict; set: {PATH: VALUE} (or
    ["PATH=VALUE", ...]) applied first, as nmm-preprocess --set. What nmm-preprocess warns of
    comes as nmm.SceneWarning; strict_joints=True makes a joint touching no body a SceneError
    (nmm-preprocess --strict-joints).
    """
    if isinstance(scene, Scene):
        if set is not None:
            raise TypeError("set: give it to nmm.Scene(...), which applies it before the checks")
    else:
        scene = Scene(scene, set=set)
    mesh, lines = _nmm._cut(scene, strict_joints)
    for line in lines:
        warnings.warn(line, SceneWarning, stacklevel=2)
    return mesh


def solve(mesh, out, set=None, config=None, restart=None, steps=None, pictures=False,
          progress=None, check=False, threads=0, **outputs):
    """Runs a mesh as `nmm-solve MESH -o OUT` does and returns what it wrote (nmm.Run).

    mesh: an nmm.Mesh or a mesh file's path; out: the output folder; set, config, restart: as
    nmm.Solver (nmm-solve --set, --config, --restart); steps: solver.steps' steps by default;
    pictures: nmm-solve --pictures; progress: True for nmm-solve's progress line, or a function
    called with the solver after every step; outputs: text_frames, contacts_every,
    contacts_gzip. The result's .summary is summary.json, .history history.csv's columns as
    arrays, .outcome how the run ended. A run that stops (nmm-solve's exit status 3) is a
    result with outcome.failed, or nmm.RunError with check=True. Ctrl-C stops it after the step
    under way with everything written (status "interrupted"), then raises KeyboardInterrupt.
    """
    if not isinstance(mesh, Mesh):
        mesh = Mesh.load(os.fspath(mesh))
    solver = Solver(mesh, set=set, config=config, restart=restart, out=out, threads=threads,
                    progress=progress, **outputs)
    try:
        outcome = solver.run(steps)
    except BaseException:
        if pictures and solver.outcome.interrupted:
            solver.pictures()  # as nmm-solve --pictures draws an interrupted run
        raise
    if pictures:
        solver.pictures()
    run = read_run(out)
    run.outcome = outcome
    if check and outcome.failed:
        raise RunError(outcome.reason, outcome=outcome, run=run)
    return run
