"""docs/python.md's walkthrough runs as written: every ```python block in order, in one namespace, in an empty
directory; a block whose first line is "# not run by the tests" (it needs a Slurm cluster) is left out."""
import os
import re
from pathlib import Path

import pytest

PAGE = Path(__file__).resolve().parents[2] / "docs" / "python.md"


def blocks():
    found = re.findall(r"^```python\n(.*?)^```", PAGE.read_text(), flags=re.MULTILINE | re.DOTALL)
    return [block for block in found if not block.startswith("# not run by the tests")]


def test_the_walkthrough_runs_as_written(tmp_path, monkeypatch):
    pytest.importorskip("open3d")
    pytest.importorskip("tqdm")
    pytest.importorskip("distributed")
    assert len(blocks()) >= 6
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "walkthrough"}
    for number, block in enumerate(blocks()):
        exec(compile(block, f"{PAGE}:block {number}", "exec"), namespace)
    # What the walkthrough promised: a calibration good to a fraction of a pixel, the cube reconstructed, its
    # Open3D cloud and the batch's files written.
    rig, truth = namespace["rig"], namespace["rfrecon"].read_rig("sim/poses/truth/rig.yaml")
    assert rig["rms"] < 0.5
    for key in ["camera_matrix", "projector_matrix"]:  # focal lengths within 1 %
        focal, true_focal = rig[key][[0, 1], [0, 1]], truth[key][[0, 1], [0, 1]]
        assert abs(focal / true_focal - 1).max() < 0.01, (key, focal, true_focal)
    assert namespace["found"].sum() > 1000
    assert os.path.getsize("cube-open3d.ply") > 0 and Path("cube/depth.tiff").exists()
    assert namespace["results"][0].status == "transport made, reconstruction made"
    assert Path("batch/summary.csv").exists()
