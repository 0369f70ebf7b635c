"""A run folder read back into arrays: nmm.read_run(DIR) → nmm.Run.

What nmm-solve (or nmm.solve, or an nmm.Solver with out=DIR) wrote, read with the readers
nmm-report uses (CSV plain or gzip, frames.pvd, binary or text .vtu): summary.json as a dict,
history.csv, contacts.csv(.gz), energy.csv and run_history.csv as dicts of column arrays, and
the frames as nmm.Frame objects. File formats: docs/interface.md.
"""
import functools
import json
import os

import numpy as np

from . import _nmm


def _table(path):
    """{column: array} of a run's CSV (plain or gzip); integer columns as integers."""
    names, values = _nmm.read_number_csv(path)
    table = {}
    for k, name in enumerate(names):
        column = values[:, k]
        integral = name in ("step", "point", "contact", "state", "set", "vertex", "edge", "iterations",
                            "cuts", "closed_contacts")
        table[name] = column.astype(np.int64) if integral else column
    return table


def _optional(path):
    return _table(path) if os.path.exists(path) else None


class Frame:
    """One frame of a run (frames/frame_STEP.vtu): the element polygons at that time.

    points (n, 2) m, the polygons' vertices where they were; offsets, connectivity: cell c's
    polygon is points[connectivity[offsets[c]:offsets[c + 1]]]; displacement (n, 2) m since the
    start; stress (cells, 3) Pa, σxx σyy τxy of each element; block, body (cells); point_data
    and cell_data: every array of the file by name.
    """

    def __init__(self, path, time, step):
        grid = _nmm.read_vtu(path)
        self.path, self.time, self.step = path, time, step
        self.points = grid["points"]
        self.offsets = grid["offsets"]
        self.connectivity = grid["connectivity"]
        self.point_data = grid["point_data"]
        self.cell_data = grid["cell_data"]
        self.displacement = self.point_data["displacement"][:, :2]
        self.stress = self.cell_data["stress"]
        self.block = self.cell_data.get("block")
        self.body = self.cell_data.get("body")

    def polygons(self):
        """Each element's polygon, a list of arrays (k, 2) m."""
        return [self.points[self.connectivity[a:b]] for a, b in zip(self.offsets[:-1], self.offsets[1:])]

    def __repr__(self):
        return f"<nmm.Frame step {self.step}, t = {self.time:g} s, {len(self.offsets) - 1} elements>"


class Run:
    """What a run wrote into its folder (nmm.read_run).

    summary: summary.json (dict); history: history.csv's columns (step, time, point, x, y, ux,
    uy) as arrays, one row per measure point per output step; contacts, energy, run_history:
    contacts.csv(.gz), energy.csv, run_history.csv likewise (None where the run wrote none),
    each read when first used;
    frames: [(time, step), ...] of frames.pvd; frame(step=None): that frame (the last one by
    default); point(i): measure point i's history rows. outcome: the nmm.Outcome of a run made
    by nmm.solve (None when read back).
    """

    def __init__(self, folder):
        self.dir = os.fspath(folder)
        with open(os.path.join(self.dir, "summary.json"), encoding="utf-8") as f:
            self.summary = json.load(f)
        self.history = _table(os.path.join(self.dir, "history.csv"))
        pvd = os.path.join(self.dir, "frames.pvd")
        self.frames = _nmm.list_run_frames(self.dir) if os.path.exists(pvd) else []
        self.outcome = None

    # Read when first asked for: contacts.csv is the large one (16 MB for the jointed slope's
    # 500 steps, 0.2 s to read), and nmm.solve returns a Run that may never look at it.
    @functools.cached_property
    def contacts(self):
        gz = os.path.join(self.dir, "contacts.csv.gz")
        return _table(gz) if os.path.exists(gz) else _optional(os.path.join(self.dir, "contacts.csv"))

    @functools.cached_property
    def energy(self):
        return _optional(os.path.join(self.dir, "energy.csv"))

    @functools.cached_property
    def run_history(self):
        return _optional(os.path.join(self.dir, "run_history.csv"))

    @property
    def status(self):
        """summary.json's status: "ok", "interrupted" or why the run stopped."""
        return self.summary["status"]

    @property
    def ok(self):
        return self.summary.get("stop_code", "ok") == "ok"

    @property
    def state_hash(self):
        return self.summary["state_hash"]

    def point(self, i):
        """Measure point i's rows of history.csv: {column: array}."""
        rows = self.history["point"] == i
        return {name: column[rows] for name, column in self.history.items()}

    def frame(self, step=None):
        """The frame of `step` (the last frame by default), an nmm.Frame."""
        if not self.frames:
            raise FileNotFoundError(os.path.join(self.dir, "frames.pvd") + ": the run wrote no frames")
        if step is None:
            time, step = self.frames[-1]
        else:
            times = {s: t for t, s in self.frames}
            if step not in times:
                steps = [s for _, s in self.frames]
                raise KeyError(f"no frame of step {step} ({len(steps)} frames, steps {steps[0]} to {steps[-1]})")
            time = times[step]
        return Frame(os.path.join(self.dir, _nmm.frame_file_name(step)), time, step)

    def __repr__(self):
        return (f"<nmm.Run {self.dir}: {self.status}, {self.summary.get('steps_completed')} steps to "
                f"t = {self.summary.get('simulated_time')} s>")


def read_run(folder):
    """The run in `folder` (what nmm-solve -o folder wrote), as an nmm.Run."""
    return Run(folder)
