"""Session.capture with a camera and projector written in Python: a "screen camera" that sees exactly what the
projector shows (through a gain and an offset, with one frame of display lag) must decode to the identity map; a
repeated frame is grabbed again; errors and cancellation leave nothing behind."""
import numpy as np
import pytest

import rfrecon

SIZE = (64, 48)  # projector and camera, (width, height)


class Screen(rfrecon.Projector):
    """A projector whose shown images a camera can see, `lag` grabs after they are shown."""

    def __init__(self, lag=1):
        super().__init__()
        self.queue = []  # (grab number from which it is visible, image)
        self.visible = np.zeros(SIZE[::-1], np.uint8)
        self.grabs = 0
        self.lag = lag

    def name(self):
        return "numpy screen"

    def size(self):
        return SIZE

    def show(self, image):
        assert image.dtype == np.uint8 and image.shape == SIZE[::-1]
        self.queue.append((self.grabs + 1 + self.lag, image.copy()))

    def advance(self):
        self.grabs += 1
        while self.queue and self.queue[0][0] <= self.grabs:
            self.visible = self.queue.pop(0)[1]
        return self.visible


class ScreenCamera(rfrecon.Camera):
    """A 10-bit camera looking straight at the screen: reading = 40 + 3 * level, plus noise of 1 DN."""

    def __init__(self, screen, repeat_grab=None, fail_at=None, on_grab=None):
        super().__init__()
        self.screen = screen
        self.rng = np.random.default_rng(7)
        self.last = None
        self.repeat_grab = repeat_grab
        self.fail_at = fail_at
        self.on_grab = on_grab
        self.exposures = []

    def name(self):
        return "numpy camera"

    def format(self):
        return rfrecon.CameraFormat(SIZE, bit_depth=10, black_level_dn=40.0)

    def lock_exposure(self, exposure_us):
        self.exposures.append(exposure_us)
        return exposure_us if exposure_us > 0 else 5000.0

    def grab(self, timeout_ms):
        level = self.screen.advance()
        number = self.screen.grabs - 1
        if self.on_grab:
            self.on_grab(number)
        if number == self.fail_at:
            raise RuntimeError("camera unplugged")
        if number == self.repeat_grab and self.last is not None:
            return self.last
        noise = self.rng.normal(0.0, 1.0, level.shape)
        self.last = np.clip(np.rint(40 + 3.0 * level + noise), 0, 1023).astype(np.uint16)
        return self.last


def test_screen_capture_decodes_to_the_identity_map(session, tmp_path):
    screen = Screen(lag=1)
    camera = ScreenCamera(screen)
    report = session.capture(screen, camera, tmp_path / "scan", dot_spacing=0)
    assert report["latency_frames"] == 1
    assert report["recaptured_pairs"] == 0 and report["repeated_frames"] == 0
    manifest = report["manifest"]
    assert manifest.bit_depth == 10 and manifest.black_level == 40.0 and len(manifest) == 2 + 2 * (6 + 6)
    transport, _ = session.transport(rfrecon.Capture.from_directory(tmp_path / "scan"))
    ys, xs = np.mgrid[0:SIZE[1], 0:SIZE[0]]
    assert np.array_equal(transport.pixel_x, xs) and np.array_equal(transport.pixel_y, ys)


def test_repeated_frame_is_grabbed_again(session, tmp_path):
    screen = Screen(lag=0)
    camera = ScreenCamera(screen, repeat_grab=10)  # a Gray frame (no latency measured: grab n shows frame n)
    report = session.capture(screen, camera, tmp_path / "scan", dot_spacing=0, latency_frames=0)
    assert report["repeated_frames"] == 1


def test_camera_error_propagates_and_leaves_nothing(session, tmp_path):
    screen = Screen(lag=0)
    camera = ScreenCamera(screen, fail_at=10)
    with pytest.raises(RuntimeError, match="camera unplugged"):
        session.capture(screen, camera, tmp_path / "scan", dot_spacing=0, latency_frames=0)
    assert list(tmp_path.iterdir()) == []


def test_cancel_stops_at_the_next_pattern(session, tmp_path):
    screen = Screen(lag=0)
    camera = ScreenCamera(screen, on_grab=lambda number: number == 5 and session.cancel())
    with pytest.raises(rfrecon.Cancelled):
        session.capture(screen, camera, tmp_path / "scan", dot_spacing=0, latency_frames=0)
    assert list(tmp_path.iterdir()) == []


def test_dark_camera_is_a_hardware_error(session, tmp_path):
    class Dark(ScreenCamera):
        def grab(self, timeout_ms):
            self.screen.advance()
            return np.full(SIZE[::-1], 40, np.uint16)

    screen = Screen(lag=0)
    with pytest.raises(rfrecon.HardwareError, match="does not see") as error:
        session.capture(screen, Dark(screen), tmp_path / "scan", dot_spacing=0)
    assert error.value.exit_code == 10
    assert list(tmp_path.iterdir()) == []


def test_unknown_camera_spec_is_a_usage_error():
    with pytest.raises(rfrecon.UsageError, match="v4l2:DEVICE"):
        rfrecon.open_camera("firewire:0")
