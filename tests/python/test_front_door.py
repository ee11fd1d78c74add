"""The front door from Python: the same T and reconstruction as the command-line tool, numpy views that outlive
their owners, T as scipy.sparse, errors with the tool's exit codes, progress, logs and cancellation."""
import gc
import sys
import subprocess
from pathlib import Path

import numpy as np
import pytest

import rfrecon

MAPS = ["depth.tiff", "points.tiff", "normals.tiff", "confidence.tiff", "depth_sigma.tiff", "depth_sigma_calibration.tiff",
        "depth_sigma_observation.tiff", "points.ply"]


def frames_of(capture):
    return [capture.frame(i) for i in range(len(capture.manifest))]


@pytest.fixture(scope="module")
def capture(plane):
    return rfrecon.Capture.from_directory(plane / "capture")


@pytest.fixture(scope="module")
def transport(session, capture):
    t, _ = session.transport(rfrecon.Capture.from_frames(capture.manifest, frames_of(capture)))
    return t


def test_version_is_the_projects():
    cmake = (Path(__file__).resolve().parents[2] / "CMakeLists.txt").read_text()
    assert f"project(rfrecon VERSION {rfrecon.__version__} " in cmake


def test_transport_from_memory_equals_the_tools_file(cli, plane, transport, tmp_path):
    subprocess.run([cli, "transport", str(plane / "capture"), "-o", str(tmp_path / "T.h5")], check=True,
                   capture_output=True)
    from_file = rfrecon.read_transport(tmp_path / "T.h5")
    assert transport.camera_size == (64, 48) and transport.projector_size == (64, 48)
    for name in ["indices", "weights", "correspondence", "pixel_x", "pixel_y", "flags", "direct_energy", "white"]:
        np.testing.assert_array_equal(getattr(transport, name), getattr(from_file, name), err_msg=name)
    np.testing.assert_array_equal(transport.gray_x, transport.pixel_x)  # the former names, kept
    np.testing.assert_array_equal(transport.gray_y, transport.pixel_y)


def test_frames_from_a_callback_equal_frames_in_memory(session, capture, transport):
    frames = frames_of(capture)
    asked = []

    def camera(index):
        asked.append(index)
        return frames[index]

    t, _ = session.transport(rfrecon.Capture.from_callback(capture.manifest, camera, "pytest camera"))
    np.testing.assert_array_equal(t.weights, transport.weights)
    assert sorted(asked) == list(range(len(frames)))  # each frame once


def test_reconstruction_equals_the_tools_files_and_is_the_plane(cli, session, plane, transport, tmp_path):
    rig_file = plane / "truth" / "rig.yaml"
    subprocess.run([cli, "transport", str(plane / "capture"), "-o", str(tmp_path / "T.h5")], check=True,
                   capture_output=True)
    # Tuning options by their flags' names, off their defaults on both sides.
    subprocess.run([cli, "reconstruct", str(tmp_path / "T.h5"), "--calib", str(rig_file), "-o", str(tmp_path / "cli"),
                    "--crease", "8", "--sigma-step", "0.2", "--passes", "4"], check=True, capture_output=True)
    maps = session.reconstruct(transport, rfrecon.read_rig(rig_file), "fused", crease=8.0, sigma_step=0.2, passes=4)
    assert {k: maps["summary"]["options"][k] for k in ["crease", "sigma-step", "passes"]} == \
        {"crease": 8.0, "sigma-step": 0.2, "passes": 4}
    rfrecon.write_reconstruction(maps, tmp_path / "api")
    for name in MAPS:
        assert (tmp_path / "api" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name

    # The points lie on a plane: least-squares residual RMS under 0.5 mm (measured 0.1 to 0.2 mm on this 64x48 rig).
    points = maps["points_mm"].reshape(-1, 3)
    points = points[np.isfinite(points).all(axis=1)]
    assert len(points) > 300
    centred = points - points.mean(axis=0)
    normal = np.linalg.svd(centred, full_matrices=False)[2][2]
    assert np.sqrt(np.mean((centred @ normal) ** 2)) < 0.5
    assert maps["depth_mm"].dtype == np.float32 and maps["points_mm"].shape == (48, 64, 3)
    np.testing.assert_array_equal(maps["rig"]["camera_matrix"], rfrecon.read_rig(rig_file)["camera_matrix"])
    # The true rig has no uncertainty: the calibration's part is 0 wherever there is depth; the fusion does not
    # propagate the frames' noise, so neither the observation's part nor the total is known.
    has_depth = np.isfinite(maps["depth_mm"])
    assert np.all(maps["depth_sigma_calibration_mm"][has_depth] == 0)
    assert np.all(np.isnan(maps["depth_sigma_observation_mm"])) and np.all(np.isnan(maps["depth_sigma_mm"]))


def test_primal_and_dual_images_are_t_times_ones(session, transport):
    import scipy.sparse

    matrix = rfrecon.transport_matrix(transport)
    assert isinstance(matrix, scipy.sparse.csr_matrix) and matrix.shape == (64 * 48, 64 * 48)
    primal = session.primal_image(transport)
    dual = session.dual_image(transport)
    assert primal.shape == (48, 64) and dual.shape == (48, 64)
    ones = np.ones(matrix.shape[1], np.float64)
    np.testing.assert_allclose(primal.ravel(), matrix @ ones, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(dual.ravel(), matrix.T @ np.ones(matrix.shape[0]), rtol=1e-5, atol=1e-6)
    # 1^T (T 1) = 1^T (T^T 1): both images hold all of T's light.
    assert primal.sum(dtype=np.float64) == pytest.approx(dual.sum(dtype=np.float64), rel=1e-5)
    assert dual.sum() > 0


def test_views_outlive_their_session_and_transport(plane):
    session = rfrecon.Session()
    capture = rfrecon.Capture.from_directory(plane / "capture")
    t, _ = session.transport(capture)
    weights, indices = t.weights, t.indices
    expected = weights.copy()
    assert not weights.flags.writeable  # T is shared: its views are read-only
    maps = session.reconstruct(t, rfrecon.read_rig(plane / "truth" / "rig.yaml"))
    depth = maps["depth_mm"]
    depth_copy = depth.copy()
    del session, capture, t, maps
    gc.collect()
    _ = [np.zeros(1 << 16) for _ in range(64)]  # reuse freed memory, were any freed
    np.testing.assert_array_equal(weights, expected)
    np.testing.assert_array_equal(depth, depth_copy)
    assert indices.shape == (48, 64, 8)


def test_a_missing_capture_is_the_tools_input_error(cli, tmp_path):
    missing = tmp_path / "no-such-capture"
    with pytest.raises(rfrecon.InputError) as error:
        rfrecon.Capture.from_directory(missing)
    assert error.value.exit_code == 3 and str(missing) in str(error.value)
    tool = subprocess.run([cli, "transport", str(missing), "-o", str(tmp_path / "T.h5")], capture_output=True, text=True)
    assert tool.returncode == error.value.exit_code
    assert str(error.value) in tool.stderr


def test_errors_name_what_is_wrong(session, capture, transport, plane, tmp_path):
    with pytest.raises(rfrecon.DeviceError) as error:
        rfrecon.Session(devices="no-such-device-name")
    assert error.value.exit_code == 4 and "no-such-device-name" in str(error.value)

    frames = frames_of(capture)
    with pytest.raises(rfrecon.InputError, match="5 frames for a manifest"):
        rfrecon.Capture.from_frames(capture.manifest, frames[:5])
    frames[3] = frames[3].astype(np.float32)
    with pytest.raises(rfrecon.InputError, match="frame 3.*uint8 or uint16"):
        rfrecon.Capture.from_frames(capture.manifest, frames)

    rig = rfrecon.read_rig(plane / "truth" / "rig.yaml")
    rig["camera_matrix"] = np.eye(2)
    with pytest.raises(rfrecon.InputError, match="camera_matrix"):
        session.reconstruct(transport, rig)

    maps = session.reconstruct(transport, rfrecon.read_rig(plane / "truth" / "rig.yaml"), "triangulate")
    rfrecon.write_reconstruction(maps, tmp_path / "out")
    before = (tmp_path / "out" / "depth.tiff").read_bytes()
    with pytest.raises(rfrecon.Error, match="not empty"):
        rfrecon.write_reconstruction(maps, tmp_path / "out")
    assert (tmp_path / "out" / "depth.tiff").read_bytes() == before  # nothing lost
    with pytest.raises(rfrecon.InputError, match="no-such-method.*" + ", ".join(rfrecon.depth_methods())):
        session.reconstruct(transport, rfrecon.read_rig(plane / "truth" / "rig.yaml"), "no-such-method")
    assert rfrecon.depth_methods()[:3] == ["triangulate", "integrate", "fused"]
    assert rfrecon.pattern_families() == ["graycode", "phase"]
    with pytest.raises(rfrecon.InputError, match="unknown pattern family 'stripes' \\(graycode, phase\\)"):
        rfrecon.make_manifest((64, 40), (80, 64), family="stripes")
    # Ratio 4 on 64 x 40: columns' periods 16, 64, 128 and rows' 16, 56, three steps each, no order code.
    phase = rfrecon.make_manifest((64, 40), (80, 64), dot_spacing=0, family="phase",
                                  parameters={"phase_steps": 3, "phase_ratio": 4})
    assert phase.family == "phase" and len(phase) == 2 + 3 * 3 + 2 * 3
    # The dot grid after the phases: 4 x 4 frames more, the last lighting every fourth pixel from (3, 3).
    dotted = rfrecon.make_manifest((64, 40), (80, 64), dot_spacing=4, family="phase",
                                   parameters={"phase_steps": 3, "phase_ratio": 4})
    assert dotted.dot_spacing == 4 and len(dotted) == len(phase) + 16
    last = rfrecon.pattern_image(dotted, len(dotted) - 1)
    assert last[3::4, 3::4].min() == 255 and int(last.sum()) == 255 * 16 * 10
    with pytest.raises(rfrecon.InputError, match="phase_ratio = 1 is outside 2 to 64 \\(or 0: "):
        rfrecon.make_manifest((64, 40), (80, 64), dot_spacing=0, family="phase", parameters={"phase_ratio": 1})
    rig = rfrecon.read_rig(plane / "truth" / "rig.yaml")
    with pytest.raises(rfrecon.UsageError, match="'passes' is 0: a whole number from 1 to 20") as error:
        session.reconstruct(transport, rig, passes=0)
    assert error.value.exit_code == 2
    with pytest.raises(rfrecon.UsageError, match="'passes' is 2.5"):
        session.reconstruct(transport, rig, passes=2.5)
    with pytest.raises(rfrecon.UsageError, match="unknown depth option 'no-such-option'.*sigma-step"):
        session.reconstruct(transport, rig, no_such_option=1)
    with pytest.raises(rfrecon.UsageError, match="'crease' must be a number"):
        session.reconstruct(transport, rig, crease="8")


def test_out_of_range_options_and_existing_outputs_are_refused(session, capture, transport, plane, tmp_path):
    for arguments, option in [((100,), "-k"), ((0,), "-k"), ((8, -0.1), "--black-threshold"),
                              ((8, 0.04, float("nan")), "--white-threshold"), ((8, 0.04, 0.0, 0.6), "--noise-threshold")]:
        with pytest.raises(rfrecon.UsageError, match=option) as error:
            session.transport(capture, *arguments)
        assert error.value.exit_code == 2

    rig = rfrecon.read_rig(plane / "truth" / "rig.yaml")
    for name, write in [("T.h5", lambda file, **force: rfrecon.write_transport(transport, file, **force)),
                        ("rig.yaml", lambda file, **force: rfrecon.write_rig(rig, file, **force))]:
        existing = tmp_path / name
        existing.write_bytes(b"an input of the user's")
        with pytest.raises(rfrecon.UsageError, match="exists") as error:
            write(existing)
        assert error.value.exit_code == 2 and existing.read_bytes() == b"an input of the user's"  # nothing lost
        write(existing, force=True)
        assert existing.read_bytes() != b"an input of the user's"
    np.testing.assert_array_equal(rfrecon.read_transport(tmp_path / "T.h5").weights, transport.weights)

    maps = session.reconstruct(transport, rig, "triangulate")
    wrong_type = dict(maps, depth_mm=maps["depth_mm"].astype(np.float64))
    with pytest.raises(rfrecon.InputError, match="reconstruction dict: .*depth_mm must be CV_32FC1"):
        rfrecon.write_reconstruction(wrong_type, tmp_path / "wrong-type")
    without_normals = {key: value for key, value in maps.items() if key != "normals"}
    with pytest.raises(rfrecon.InputError, match="missing key 'normals'"):
        rfrecon.write_reconstruction(without_normals, tmp_path / "without-normals")


def test_progress_logs_and_cancellation(plane):
    steps, lines = [], []
    session = rfrecon.Session(progress=lambda label, done, total, unit: steps.append((label, done, total, unit)),
                              log=lambda level, text: lines.append((level, text)))
    capture = rfrecon.Capture.from_directory(plane / "capture")
    session.transport(capture)
    transport_steps = [s for s in steps if s[0] == "transport"]
    assert transport_steps, steps
    done = [s[1] for s in transport_steps]
    assert done == sorted(done) and done[-1] == transport_steps[-1][2]  # counts up to its total
    assert any("transport" in text for _, text in lines)

    def cancel_at_the_fifth_frame(label, done, total, unit):
        if done >= 5 and not cancelled:
            cancelled.append(done)
            cancelling.cancel()

    cancelled = []
    cancelling = rfrecon.Session(progress=cancel_at_the_fifth_frame)
    with pytest.raises(rfrecon.Cancelled) as error:
        cancelling.transport(capture)
    assert error.value.exit_code == 130
    cancelling.transport(capture)  # the next call runs


def test_tqdm_shows_progress(plane):
    tqdm = pytest.importorskip("tqdm").tqdm
    bars = {}

    def progress(label, done, total, unit):
        bar = bars.get(label) or bars.setdefault(label, tqdm(total=total, desc=label, unit=unit, file=sys.stderr))
        bar.update(done - bar.n)

    rfrecon.Session(progress=progress).transport(rfrecon.Capture.from_directory(plane / "capture"))
    assert bars["transport"].n == bars["transport"].total > 0


def test_rig_round_trips_and_speaks_opencv(plane, tmp_path):
    rig = rfrecon.read_rig(plane / "truth" / "rig.yaml")
    rfrecon.write_rig(rig, tmp_path / "rig.yaml")
    again = rfrecon.read_rig(tmp_path / "rig.yaml")
    for key in ["camera_matrix", "dist_coeffs", "R", "T", "P1", "P2", "Q"]:
        np.testing.assert_allclose(again[key], rig[key], rtol=1e-12, atol=1e-12, err_msg=key)
    assert isinstance(rig, rfrecon.Rig) and isinstance(rig, dict)
    opencv = rig.to_opencv()
    assert opencv["cameraMatrix1"] is rig["camera_matrix"] and opencv["imageSize"] == (64, 48)
    # E = [T]x R, OpenCV's convention, up to scale.
    t = opencv["T"].ravel()
    skew = np.array([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]])
    essential = skew @ opencv["R"]
    np.testing.assert_allclose(essential / np.linalg.norm(essential),
                               opencv["E"] / np.linalg.norm(opencv["E"]), atol=1e-9)
