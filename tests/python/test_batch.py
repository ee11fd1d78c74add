"""rfrecon.batch on a 2-worker dask LocalCluster: four scans equal to the serial run, reruns keep what exists, a bad
scan is a failed row and not a lost batch."""
import csv

import pytest

import rfrecon
from rfrecon.batch import Scan, reconstruct_scans

from conftest import render_plane

distributed = pytest.importorskip("distributed")

ROTATIONS = [(10.0, -10.0), (-8.0, 12.0), (15.0, 5.0), (0.0, -18.0)]
OUTPUTS = ["T.h5", "reconstruction/depth.tiff", "reconstruction/points.ply", "reconstruction/normals.tiff"]


@pytest.fixture(scope="module")
def scans(session, tmp_path_factory):
    root = tmp_path_factory.mktemp("scans")
    return [Scan(str(render_plane(session, root / f"scan{i}", rotation_deg=r, seed=i + 1) / "capture"), f"scan{i}")
            for i, r in enumerate(ROTATIONS)]


def test_a_local_cluster_gives_the_serial_files(scans, plane, tmp_path):
    rig = str(plane / "truth" / "rig.yaml")  # the scenes share the rig
    serial = reconstruct_scans(None, scans, rig, str(tmp_path / "serial"))
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            parallel = reconstruct_scans(client, scans, rig, str(tmp_path / "parallel"))
            assert len({w["id"] for w in client.scheduler_info()["workers"].values()}) == 2
            again = reconstruct_scans(client, scans, rig, str(tmp_path / "parallel"))
    for a, b in zip(serial, parallel):
        assert a.name == b.name and a.status == b.status == "transport made, reconstruction made"
        assert a.reconstructed_pixels == b.reconstructed_pixels > 300
        for name in OUTPUTS:
            file = f"{a.name}/{name}"
            assert (tmp_path / "parallel" / file).read_bytes() == (tmp_path / "serial" / file).read_bytes(), file
    assert all(r.status == "transport kept, reconstruction kept" for r in again)
    rows = list(csv.DictReader(open(tmp_path / "parallel" / "summary.csv")))
    assert [row["name"] for row in rows] == [s.name for s in scans]


def test_a_bad_scan_is_a_failed_row(scans, plane, tmp_path):
    broken = Scan(str(tmp_path / "missing-capture"), "broken")
    results = reconstruct_scans(None, [scans[0], broken], str(plane / "truth" / "rig.yaml"), str(tmp_path / "out"))
    assert results[0].status == "transport made, reconstruction made"
    assert results[1].status.startswith("failed: InputError") and "missing-capture" in results[1].status
    rows = list(csv.DictReader(open(tmp_path / "out" / "summary.csv")))
    assert rows[1]["status"] == results[1].status


def test_repeated_names_are_refused(scans, plane, tmp_path):
    with pytest.raises(rfrecon.UsageError, match="scan0"):
        reconstruct_scans(None, [scans[0], scans[0]], str(plane / "truth" / "rig.yaml"), str(tmp_path))
