"""Fixtures of the Python suite: one Session, a small rendered plane (64x48, two seconds), the command-line tool."""
import json
import os
import shutil
from pathlib import Path

import pytest

import rfrecon

REPO = Path(__file__).resolve().parents[2]

# A 64x48 camera and projector (f = 80 px) 150 mm apart, toed in to a 160 x 120 mm Lambertian plane 500 mm ahead
# turned (rx, ry) degrees, the 4x4 dot grid that the fused method needs (the scene of tests/install/consumer).
def plane_scene(rotation_deg=(10.0, -10.0), seed=1):
    return {
        "name": "pytest-plane",
        "camera": {"size": [64, 48], "focal": [80.0, 80.0]},
        "projector": {"size": [64, 48], "focal": [80.0, 80.0],
                      "pose": {"position": [150.0, 0.0, 0.0], "look_at": [0.0, 0.0, 500.0]}},
        "radiometry": {"intensity": 7.0e5},
        "capture": {"dot_spacing": 4},
        "render": {"supersample": 1, "seed": seed},
        "objects": [{"name": "plane", "shape": "plane", "size": [160.0, 120.0],
                     "pose": {"position": [0.0, 0.0, 500.0], "rotation_deg": [rotation_deg[0], rotation_deg[1], 0.0]},
                     "material": {"brdf": "lambert", "diffuse": 0.6}}],
    }


def render_plane(session, directory, **scene_args):
    """Renders plane_scene(**scene_args) into directory/sim; returns that directory."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    scene_file = directory / "scene.json"
    scene_file.write_text(json.dumps(plane_scene(**scene_args)))
    session.simulate(str(scene_file), directory / "sim")
    return directory / "sim"


@pytest.fixture(scope="session")
def session():
    return rfrecon.Session()


@pytest.fixture(scope="session")
def plane(session, tmp_path_factory):
    """The rendered plane: its directory (capture/, truth/rig.yaml)."""
    return render_plane(session, tmp_path_factory.mktemp("plane"))


@pytest.fixture(scope="session")
def cli():
    """The command-line tool of this checkout's build (build/rfrecon), or $RFRECON_CLI."""
    tool = os.environ.get("RFRECON_CLI") or shutil.which("rfrecon", path=str(REPO / "build"))
    if not tool:
        pytest.skip("no rfrecon tool in build/ (build the project first, or set RFRECON_CLI)")
    return tool
