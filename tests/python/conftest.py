"""Fixtures of the module's tests (CTest python.pytest runs them with the build's nmm on
PYTHONPATH, NMM_BIN the tools' folder, NMM_SOURCE the source tree, MPLBACKEND=Agg)."""
import os
import subprocess

import pytest

SOURCE = os.environ.get("NMM_SOURCE", os.path.join(os.path.dirname(__file__), "..", ".."))
BIN = os.environ.get("NMM_BIN", os.path.join(SOURCE, "build", "bin"))


def scene_path(name):
    """data/NAME.json of the source tree."""
    return os.path.join(SOURCE, "data", name + ".json")


def tool(name, *args, check=True):
    """Runs build/bin/NAME with args; the completed process (stdout, stderr as text)."""
    p = subprocess.run([os.path.join(BIN, name), *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"{name} {' '.join(map(str, args))}: exit {p.returncode}: {p.stderr}")
    return p


@pytest.fixture(scope="session")
def meshes(tmp_path_factory):
    """A function scene name -> mesh file cut by nmm-preprocess (each once per session)."""
    folder = tmp_path_factory.mktemp("meshes")
    made = {}

    def mesh(name):
        if name not in made:
            out = folder / (name + ".nmm")
            tool("nmm-preprocess", scene_path(name), "-o", out, "-q")
            made[name] = str(out)
        return made[name]

    return mesh
