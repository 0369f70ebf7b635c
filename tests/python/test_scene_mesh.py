"""nmm.Scene, nmm.preprocess, nmm.Mesh against nmm-preprocess and nmm-inspect."""
import json

import numpy as np
import pytest

import nmm
from conftest import scene_path, tool


def test_scene_from_path_and_dict_agree():
    from_path = nmm.Scene(scene_path("block_on_incline"))
    from_dict = nmm.Scene(from_path.to_dict())
    assert from_path.name == from_dict.name == "block-on-incline"
    assert from_dict.file == "<scene dict>"
    assert from_path.materials == from_dict.materials == ["bedrock", "rock"]  # index order
    assert from_path.joint_sets == ["interface"]
    assert from_path.mesh_size == 0.5
    np.testing.assert_array_equal(from_path.bodies[1]["outer"], from_dict.bodies[1]["outer"])


def test_scene_set_edits_before_the_checks():
    s = nmm.Scene(scene_path("block_on_incline"), set={"mesh.size": 0.25})
    assert s.mesh_size == 0.25
    s = nmm.Scene(scene_path("block_on_incline"), set=["mesh.size=0.4"])
    assert s.mesh_size == 0.4


def test_bad_scene_dict_raises_scene_error_with_its_json_path():
    d = nmm.Scene(scene_path("block_on_incline")).to_dict()
    d["bodies"][1]["outer"][2] = [9.89, "x"]
    with pytest.raises(nmm.SceneError) as e:
        nmm.Scene(d)
    assert e.value.file == "<scene dict>"
    assert e.value.where.startswith("/bodies/1/outer/2")
    assert str(e.value).startswith("<scene dict>: /bodies/1/outer/2")
    assert isinstance(e.value, nmm.InputError) and isinstance(e.value, ValueError)


def test_bad_scene_file_has_the_tools_line(tmp_path):
    bad = tmp_path / "bad.json"
    text = open(scene_path("block_on_incline")).read().replace('"time_step": 1e-3', '"time_step": -1')
    bad.write_text(text)
    with pytest.raises(nmm.SceneError) as e:
        nmm.Scene(bad)
    p = tool("nmm-preprocess", bad, "-o", tmp_path / "bad.nmm", check=False)
    assert p.returncode == 2
    assert e.value.where == "/solver/time_step"
    assert str(e.value) in p.stderr  # the same one line as the tool's


def test_missing_scene_file():
    with pytest.raises(nmm.InputError) as e:
        nmm.Scene("no/such/scene.json")
    assert e.value.file == "no/such/scene.json"


def test_bad_set_path():
    with pytest.raises(nmm.SceneError) as e:
        nmm.Scene(scene_path("block_on_incline"), set={"joint_sets.nosuch.friction_deg": 3})
    assert e.value.where == "/joint_sets/nosuch"


def test_set_must_not_be_one_string():
    with pytest.raises(TypeError):
        nmm.Scene(scene_path("block_on_incline"), set="mesh.size=0.4")


def test_mesh_counts_and_arrays_match_nmm_inspect(meshes, tmp_path):
    mesh = nmm.preprocess(scene_path("jointed_slope"))
    report = json.loads(tool("nmm-inspect", meshes("jointed_slope"), "--json", "--full").stdout)
    assert mesh.node_count == report["nodes"]
    assert mesh.triangle_count == report["triangles"]
    assert mesh.cover_count == report["physical_covers"]
    assert mesh.element_count == report["manifold_elements"]
    assert mesh.block_count == report["blocks"]
    assert mesh.vertex_count == report["loop_vertices"]
    assert mesh.area == pytest.approx(report["area"], rel=1e-12)
    np.testing.assert_array_equal(mesh.nodes, np.array(report["node_xy"]))
    np.testing.assert_array_equal(mesh.triangles, np.array(report["triangle_nodes"]))
    np.testing.assert_array_equal(mesh.cover_node, report["physical_cover_node"])
    np.testing.assert_array_equal(mesh.cover_body, report["physical_cover_body"])
    np.testing.assert_array_equal(mesh.block_body, report["block_body"])
    elements = report["elements"]
    np.testing.assert_array_equal(mesh.element_block, [e["block"] for e in elements])
    np.testing.assert_array_equal(mesh.element_triangle, [e["triangle"] for e in elements])
    np.testing.assert_array_equal(mesh.element_covers, [e["covers"] for e in elements])
    for e in (0, 17, len(elements) - 1):
        np.testing.assert_array_equal(mesh.element_polygon(e), np.array(elements[e]["polygon"]))
    np.testing.assert_allclose(mesh.element_areas(), [e["area"] for e in elements], rtol=1e-12)
    # the same dict as nmm-inspect --json --full, but for the file the mesh came from
    mine = mesh.report(full=True)
    for key in ("nodes", "physical_covers", "elements", "scene_sha256", "contact_edges"):
        assert mine[key] == report[key], key


def test_mesh_arrays_are_read_only_views():
    mesh = nmm.preprocess(scene_path("block_on_incline"))
    nodes = mesh.nodes
    assert not nodes.flags.writeable and not nodes.flags.owndata
    with pytest.raises(ValueError):
        nodes[0, 0] = 1.0
    assert mesh.element_offsets[-1] == len(mesh.element_vertices) == mesh.vertex_count
    del mesh  # the view keeps the mesh alive
    assert np.isfinite(nodes).all()


def test_cover_is_what_nmm_inspect_cover_shows(meshes):
    mesh = nmm.Mesh.load(meshes("jointed_slope"))
    for i in (0, 3, mesh.cover_count - 1):
        shown = json.loads(tool("nmm-inspect", meshes("jointed_slope"), "--cover", i, "--json").stdout)["cover"]
        c = mesh.cover(i)
        assert c["node"] == shown["node"] and c["body"] == shown["body"]
        np.testing.assert_array_equal(c["elements"], shown["elements"])
        np.testing.assert_array_equal(c["node_xy"], shown["node_xy"])
        assert c["area"] == pytest.approx(shown["area"], rel=1e-12)
    with pytest.raises(IndexError, match="1347"):
        mesh.cover(mesh.cover_count)


def test_save_load_round_trip_reads_in_the_tools(tmp_path):
    mesh = nmm.preprocess(scene_path("block_on_incline"))
    assert mesh.path is None
    mesh.save(tmp_path / "incline.nmm")
    assert mesh.path == str(tmp_path / "incline.nmm")
    again = nmm.Mesh.load(str(tmp_path / "incline.nmm"))
    np.testing.assert_array_equal(again.element_vertices, mesh.element_vertices)
    shown = json.loads(tool("nmm-inspect", tmp_path / "incline.nmm", "--json").stdout)
    assert shown["manifold_elements"] == mesh.element_count
    assert again.scene.name == "block-on-incline"


def test_load_damaged_mesh_raises_input_error(tmp_path):
    bad = tmp_path / "bad.nmm"
    bad.write_bytes(b"NMMMESH\0" + b"\0" * 40)
    with pytest.raises(nmm.InputError) as e:
        nmm.Mesh.load(str(bad))
    assert e.value.file == str(bad)


def test_preprocess_warns_as_nmm_preprocess():
    d = nmm.Scene(scene_path("block_on_incline")).to_dict()
    d["joints"] = [{"set": "interface", "points": [[30, 30], [31, 31]]}]  # touches no body
    with pytest.warns(nmm.SceneWarning, match="joint"):
        nmm.preprocess(d)
    with pytest.raises(nmm.SceneError):
        nmm.preprocess(d, strict_joints=True)
