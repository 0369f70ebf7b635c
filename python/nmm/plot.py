"""Pictures of meshes and results on Matplotlib: a picture in three lines.

    import nmm, nmm.plot
    run = nmm.solve("incline.nmm", out="incline_run")
    nmm.plot.result(run).figure.savefig("incline.png")

nmm.plot.mesh(mesh) draws the manifold elements by block, the joints, optionally the
mathematical triangles and one physical cover (what nmm-inspect --svg --cover draws);
nmm.plot.result(source) the deformed elements coloured by displacement or a stress component
with the rules of result.svg (docs/guide.md): the colour bar over the area-weighted 1st–99th
percentile (displacement from 0), small displacements drawn exaggerated by a round factor named
in the title, closed contacts marked by state (sticking blue, sliding orange). Both return the
Matplotlib Axes (given as ax=, or a new figure's).
"""
import numpy as np
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection

from . import _nmm
from .run import Frame, Run

# result.svg's contact colours (result_picture.cpp): sticking blue, sliding orange.
CONTACT_COLOURS = {1: "#1f77b4", 2: "#ff7f0e"}
FIELDS = {"displacement": ("|u|", "mm"), "sxx": ("σxx", "MPa"), "syy": ("σyy", "MPa"), "sxy": ("τxy", "MPa")}


def _axes(ax):
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 5), layout="constrained")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    return ax


def _polygons(points, offsets, connectivity=None):
    index = connectivity if connectivity is not None else np.arange(len(points))
    return [points[index[a:b]] for a, b in zip(offsets[:-1], offsets[1:])]


def _areas(polygons):
    return np.array([0.5 * abs(np.dot(p[:, 0], np.roll(p[:, 1], -1)) - np.dot(p[:, 1], np.roll(p[:, 0], -1)))
                     for p in polygons])


def mesh(m, ax=None, cover=None, triangles=False, joints=True, cmap="tab20"):
    """The mesh `m` (nmm.Mesh): its manifold elements filled by block, the joints dark red;
    triangles=True adds the mathematical triangles; cover=i outlines physical cover i's elements
    in red and marks its node (nmm-inspect --cover i)."""
    ax = _axes(ax)
    if triangles:
        ax.triplot(m.nodes[:, 0], m.nodes[:, 1], m.triangles, color="0.75", lw=0.4)
    polygons = _polygons(m.element_vertices, m.element_offsets)
    ax.add_collection(PolyCollection(polygons, array=m.element_block % 20, cmap=cmap, clim=(0, 19),
                                     edgecolors="white", linewidths=0.3))
    if joints:
        for j in m.scene.joints:
            ax.plot(j[:, 0], j[:, 1], color="darkred", lw=1.2)
    title = f"{m.element_count} manifold elements, {m.cover_count} physical covers, {m.block_count} blocks"
    if cover is not None:
        c = m.cover(cover)
        ax.add_collection(PolyCollection([polygons[e] for e in c["elements"]], facecolors="none",
                                         edgecolors="red", linewidths=1.2))
        ax.plot(*c["node_xy"], "o", color="red")
        title = f"physical cover {cover}: node {c['node']}, {len(c['elements'])} elements, {c['area']:.4g} m²"
    ax.set_title(title)
    ax.autoscale_view()
    return ax


def _state_of(source, step):
    """(start positions, displacement, element stress, polygon offsets and connectivity, time,
    contacts {x, y, state, vertex}) of a run's frame, a frame or a solver's current state."""
    if isinstance(source, Run):
        source = source.frame(step), source
    if isinstance(source, tuple):
        frame, run = source
    elif isinstance(source, Frame):
        frame, run = source, None
    else:  # an nmm.Solver: its current state
        m = source.mesh
        contacts = source.contacts()
        return (m.element_vertices, source.vertex_displacement, source.element_stress, m.element_offsets, None,
                source.time, contacts)
    contacts = None
    if run is not None and run.contacts is not None:
        rows = run.contacts["step"] == frame.step
        contacts = {k: v[rows] for k, v in run.contacts.items()}
    return (frame.points - frame.displacement, frame.displacement, frame.stress, frame.offsets,
            frame.connectivity, frame.time, contacts)


def result(source, ax=None, field="displacement", step=None, exaggerate=None, contacts=True,
           colorbar=True, cmap="viridis"):
    """The deformed elements of `source` — an nmm.Run (its last frame, or the frame of `step`),
    an nmm.Frame, or an nmm.Solver (its current state) — coloured by `field`: "displacement"
    (|u|, mm) or "sxx", "syy", "sxy" (MPa, tension positive). exaggerate: the factor the
    displacements are drawn with (default: result.svg's automatic one, 1 above 1 % of the model
    size). contacts: mark the closed contacts by state."""
    if field not in FIELDS:
        raise ValueError(f"field: {field!r} is not one of {', '.join(FIELDS)}")
    start, u, stress, offsets, connectivity, time, rows = _state_of(source, step)
    ax = _axes(ax)
    start_polygons = _polygons(start, offsets, connectivity)
    u_polygons = _polygons(u, offsets, connectivity)
    area = _areas(start_polygons)
    if field == "displacement":
        value = np.array([1e3 * np.hypot(p[:, 0], p[:, 1]).mean() for p in u_polygons])
        lo = 0.0
    else:
        value = 1e-6 * stress[:, ["sxx", "syy", "sxy"].index(field)]
        lo = _nmm.weighted_quantile(value, area, 0.01)
    hi = _nmm.weighted_quantile(value, area, 0.99)
    if not hi > lo:
        hi = lo + (1e-9 if lo == 0 else abs(lo) * 1e-6)
    size = np.ptp(start, axis=0).max()
    umax = np.hypot(u[:, 0], u[:, 1]).max() if len(u) else 0.0
    factor = exaggerate if exaggerate else _nmm.automatic_exaggeration(umax, size)
    drawn = start + factor * u
    collection = PolyCollection(_polygons(drawn, offsets, connectivity), array=value, cmap=cmap,
                                clim=(lo, hi), edgecolors="face", linewidths=0.2)
    ax.add_collection(collection)
    if contacts and rows is not None and len(rows["x"]):
        vertex = np.asarray(rows["vertex"])
        at = drawn[vertex]  # a contact's vertex is a frame point (the loop vertex, docs/interface.md)
        for state, colour in CONTACT_COLOURS.items():
            pick = np.asarray(rows["state"]) == state
            if pick.any():
                ax.plot(at[pick, 0], at[pick, 1], ".", ms=3, color=colour,
                        label=("sticking" if state == 1 else "sliding") + f" ({pick.sum()})")
        ax.legend(loc="best", fontsize="small", title="closed contacts", title_fontsize="small")
    name, unit = FIELDS[field]
    if colorbar:
        ax.figure.colorbar(collection, ax=ax, label=f"{name} ({unit})", shrink=0.8)
    ax.set_title(f"{name} at t = {time:g} s" + (f", displacements drawn × {factor:g}" if factor != 1 else ""))
    ax.autoscale_view()
    return ax
