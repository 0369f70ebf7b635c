"""What a user sees of the flow along the joints (docs/flow.md "Outputs"): the network's arrays
from Python while the run steps, the frames' part of the network, result.svg by pressure.

The network is data/tunnel_inflow.json's, whose every joint stays closed (hydraulic aperture =
the residual 0.1 mm), so its pressures are the hand-computed Kirchhoff network of the scene's
header."""
import csv
import os
import re

import numpy as np
import pytest

import nmm
from conftest import tool

# data/tunnel_inflow.json's header: the crossings A, B, C of the cross joint y = 30 and their
# pressures, Pa, by hand (Kirchhoff with a³/(12μL), heads φ = p + ρgy).
HAND = {(13.0, 30.0): 158581.84, (20.15, 30.0): 79084.82, (25.0, 30.0): 22953.97}


def flow_rows(path, step):
    rows = [r for r in csv.DictReader(open(path)) if int(r["step"]) == step]
    return {k: np.array([float(r[k]) for r in rows]) for k in ("node", "x", "y", "pressure", "aperture")}


def test_network_arrays_while_stepping_match_flow_csv_and_the_hand_network(meshes, tmp_path):
    solver = nmm.Solver(nmm.Mesh.load(meshes("tunnel_inflow")), out=tmp_path / "run", text_frames=True)
    first = solver.flow()
    assert first is not None
    n = len(first["pressure"])
    assert first["xy"].shape == first["position"].shape == (n, 2)
    assert not first["pressure"].any()  # initial_pressure 0, before the first step
    solver.step()
    after_one = solver.flow()
    solver.run()
    last = solver.flow()
    # The arrays are copies of each state: the first step's stay as they were.
    assert not np.array_equal(after_one["position"], last["position"])
    # The last state's arrays are flow.csv's last rows.
    rows = flow_rows(tmp_path / "run" / "flow.csv", solver.step_number)
    np.testing.assert_array_equal(rows["node"], np.arange(n))
    # flow.csv's numbers read back to the same doubles: equal to the last bit.
    np.testing.assert_array_equal(last["xy"][:, 0], rows["x"])
    np.testing.assert_array_equal(last["xy"][:, 1], rows["y"])
    np.testing.assert_array_equal(last["pressure"], rows["pressure"])
    np.testing.assert_array_equal(last["aperture"], rows["aperture"])
    # Every joint closed: the residual aperture everywhere (a wrong opening would change it).
    np.testing.assert_allclose(last["segment_aperture"], 1e-4, rtol=1e-12)
    # The crossings' pressures against the hand-computed network, within 0.1 %.
    for (x, y), p in HAND.items():
        at = np.flatnonzero(np.hypot(last["xy"][:, 0] - x, last["xy"][:, 1] - y) < 1e-6)
        assert len(at) == 1, (x, y)
        assert last["pressure"][at[0]] == pytest.approx(p, rel=1e-3), (x, y)
    # Nodes under the top hold 196.2 kPa, those on the tunnel wall 0.
    top, wall = last["boundary"] == 0, last["boundary"] == 1
    assert top.sum() >= 2 and wall.sum() >= 2
    np.testing.assert_allclose(last["pressure"][top], 196200)
    np.testing.assert_allclose(last["pressure"][wall], 0)
    # Segments join nodes; where the nodes are now is where they were plus the faces' motion.
    assert last["segments"].shape == (len(last["segment_joint"]), 2)
    assert last["segments"].max() < n
    moved = np.hypot(*(last["position"] - last["xy"]).T)
    assert 0 < moved.max() < 1e-2


def test_a_run_without_flow_has_none(meshes):
    assert nmm.Solver(nmm.Mesh.load(meshes("block_on_incline"))).flow() is None


def test_frames_carry_the_network_and_result_svg_draws_it_by_pressure(meshes, tmp_path):
    out = tmp_path / "run"
    tool("nmm-solve", meshes("tunnel_inflow"), "-o", out, "-q", "--text-frames", "--pictures",
         "--picture-field", "pressure")
    pvd = (out / "frames.pvd").read_text()
    # Each output step: the elements as part 0, the network as part 1, at the same time.
    parts = re.findall(r'timestep="([^"]+)" group="" part="(\d)" file="frames/(\w+)_(\d+)\.vtu"', pvd)
    assert {p[2] for p in parts if p[1] == "0"} == {"frame"}
    assert {p[2] for p in parts if p[1] == "1"} == {"flow"}
    assert [p[0] for p in parts if p[1] == "0"] == [p[0] for p in parts if p[1] == "1"]
    vtu = (out / "frames" / "flow_000010.vtu").read_text()
    assert 'Name="pressure"' in vtu and 'Name="aperture"' in vtu and 'Name="flux"' in vtu
    types = re.search(r'Name="types"[^>]*>\s*([^<]*)<', vtu).group(1).split()
    assert set(types) == {"3"}  # VTK_LINE
    rows = flow_rows(out / "flow.csv", 10)
    assert len(types) > len(rows["node"]) - 10  # a segment between each pair of neighbours
    # The pressures in the frame are flow.csv's.
    block = re.search(r'<PointData>.*?Name="pressure"[^>]*>\s*([^<]*)<', vtu, re.S).group(1)
    np.testing.assert_allclose(np.array(block.split(), float), rows["pressure"], rtol=1e-15)
    # result.svg: the network by pressure with its bar, kPa, from the wall's 0 up to J3's dead end
    # (15.8, 26), which holds A's head: ρg·(46.1653 − 26) m = 197.8 kPa.
    svg = (out / "result.svg").read_text()
    assert "water pressure in the joints (kPa)" in svg and "flow network&apos;s lowest to highest pressure" in svg
    assert ">0</text>" in svg and ">198</text>" in svg
    assert max(rows["pressure"]) == pytest.approx(9810 * (46.1653 - 26), rel=1e-5)
    # nmm-report redraws it from the frames, byte for byte.
    first = svg
    tool("nmm-report", out)
    assert (out / "result.svg").read_text() == first


def test_pressure_picture_of_a_run_without_flow_is_bad_input(meshes, tmp_path):
    p = tool("nmm-solve", meshes("block_on_incline"), "-o", tmp_path / "run", "-q", "--pictures",
             "--picture-field", "pressure", check=False)
    assert p.returncode == 2
    assert p.stderr.count("\n") == 1 and "no \"flow\" block" in p.stderr
    assert not (tmp_path / "run").exists()  # refused before the output folder is made
    tool("nmm-solve", meshes("block_on_incline"), "-o", tmp_path / "ok", "-q", "--set", "solver.steps=2")
    p = tool("nmm-report", tmp_path / "ok", "--picture-field", "pressure", check=False)
    assert p.returncode == 2 and "flow_000002.vtu" in p.stderr
