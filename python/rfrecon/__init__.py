"""rfrecon: 3D shape of shiny objects from a projector-camera pair, over numpy arrays (docs/python.md).

The compiled module rfrecon._rfrecon wraps the C++ front door (rfrecon/rfrecon.h); this package adds the numpy and
scipy views a Python user expects.
"""
from ._rfrecon import (  # noqa: F401
    Camera,
    CameraFormat,
    Cancelled,
    Capture,
    DeviceError,
    Error,
    HardwareError,
    InputError,
    Manifest,
    OpenCLError,
    OutputError,
    ProcessingError,
    Projector,
    Session,
    Transport,
    UsageError,
    __version__,
    depth_methods,
    make_manifest,
    open_camera,
    open_projector,
    pattern_families,
    pattern_image,
    read_rig,
    read_transport,
    write_reconstruction,
    write_rig,
    write_transport,
)


def transport_matrix(transport):
    """T as a scipy.sparse.csr_matrix of shape (camera pixels, projector pixels), float32.

    Row r is camera pixel (r // width, r % width) in row-major order; column c is projector pixel c, row-major.
    Only the K kept entries of each row are present (empty slots, index -1, are dropped).
    """
    import numpy as np
    import scipy.sparse

    indices = transport.indices.reshape(-1, transport.entries_per_pixel)
    weights = transport.weights.reshape(-1, transport.entries_per_pixel)
    kept = indices >= 0
    rows = np.nonzero(kept)[0]
    width, height = transport.projector_size
    shape = (indices.shape[0], width * height)
    return scipy.sparse.csr_matrix((weights[kept], (rows, indices[kept])), shape=shape)


class Rig(dict):
    """A calibrated rig: rig.yaml's keys (camera_matrix, dist_coeffs, projector_matrix, projector_dist_coeffs, R, T,
    E, F, R1, R2, P1, P2, Q as float64 arrays; camera_size and projector_size as (width, height); rms,
    per_view_errors, board and the standard deviations *_std). R and T map camera coordinates to the projector's:
    X_proj = R X_cam + T, in mm, as OpenCV's stereoCalibrate gives them (docs/formats.md)."""

    def to_opencv(self):
        """The arrays under the names OpenCV's stereo functions take (cameraMatrix1, distCoeffs2, R, T, ...)."""
        return rig_to_opencv(self)


def rig_to_opencv(rig):
    """A rig dict's arrays as OpenCV's stereo calibration names them, for cv2.stereoRectify and friends."""
    return {
        "cameraMatrix1": rig["camera_matrix"],
        "distCoeffs1": rig["dist_coeffs"],
        "cameraMatrix2": rig["projector_matrix"],
        "distCoeffs2": rig["projector_dist_coeffs"],
        "R": rig["R"],
        "T": rig["T"],
        "E": rig["E"],
        "F": rig["F"],
        "R1": rig["R1"],
        "R2": rig["R2"],
        "P1": rig["P1"],
        "P2": rig["P2"],
        "Q": rig["Q"],
        "imageSize": rig["camera_size"],
    }
