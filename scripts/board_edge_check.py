#!/usr/bin/python3
"""Where a reconstructed board's plane error sits: its white squares' interiors, the squares' edges, the dark squares.

usage: board_edge_check.py RECON_DIR WHITE_IMAGE RIG_YAML [COLS ROWS]
Finds the board's COLS x ROWS inner corners (default 9 x 7) in the white frame, splits the pixels inside their convex
hull by Otsu's threshold of the white frame into bright and dark, and takes as interiors what a 7 x 7 erosion (3 px)
leaves of each; the rest are edge pixels. Fits a plane to the white interiors' points (depth.tiff back-projected with
the rig's camera, 5-sigma outliers left out, five rounds) and prints each class's point count and RMS distance from it
in mm. Needs Debian's python3-opencv and python3-numpy (docs/accuracy.md#results-real-gray-code-captures-of-a-board)."""
import sys

import cv2
import numpy as np


def main():
    if len(sys.argv) not in (4, 6):
        sys.exit(__doc__)
    recon, white, rig = sys.argv[1:4]
    cols, rows = (int(sys.argv[4]), int(sys.argv[5])) if len(sys.argv) == 6 else (9, 7)
    depth = cv2.imread(recon + "/depth.tiff", cv2.IMREAD_UNCHANGED)
    image = cv2.imread(white, cv2.IMREAD_GRAYSCALE)
    if depth is None or image is None:
        sys.exit(f"cannot read {recon}/depth.tiff or {white}")
    storage = cv2.FileStorage(rig, cv2.FILE_STORAGE_READ)
    camera, distortion = storage.getNode("camera_matrix").mat(), storage.getNode("dist_coeffs").mat()
    found, corners = cv2.findChessboardCornersSB(image, (cols, rows),
                                                 flags=cv2.CALIB_CB_EXHAUSTIVE | cv2.CALIB_CB_ACCURACY)
    if not found:
        sys.exit(f"{white}: board not found")
    board = np.zeros(depth.shape, np.uint8)
    cv2.fillConvexPoly(board, cv2.convexHull(corners.reshape(-1, 2)).astype(np.int32), 1)
    threshold, _ = cv2.threshold(image[board > 0].reshape(-1, 1), 0, 255, cv2.THRESH_BINARY + cv2.THRESH_OTSU)
    kernel = np.ones((7, 7), np.uint8)
    white_interior = cv2.erode(((image > threshold) & (board > 0)).astype(np.uint8), kernel) > 0
    dark_interior = cv2.erode(((image <= threshold) & (board > 0)).astype(np.uint8), kernel) > 0
    edge = (board > 0) & ~white_interior & ~dark_interior

    v, u = np.nonzero((board > 0) & np.isfinite(depth))
    z = depth[v, u].astype(np.float64)
    rays = cv2.undistortPoints(np.column_stack([u, v]).reshape(-1, 1, 2).astype(np.float64), camera,
                               distortion).reshape(-1, 2)
    points = np.column_stack([rays[:, 0] * z, rays[:, 1] * z, z])
    fitted = white_interior[v, u]
    keep = fitted.copy()
    for _ in range(5):
        centre = points[keep].mean(0)
        normal = np.linalg.svd(points[keep] - centre, full_matrices=False)[2][2]
        distance = (points - centre) @ normal
        keep = fitted & (np.abs(distance) < 5 * np.sqrt((distance[keep] ** 2).mean()))
    for name, mask in (("white interiors", white_interior), ("edges", edge), ("dark interiors", dark_interior)):
        d = distance[mask[v, u]]
        rms = np.sqrt((d ** 2).mean()) if len(d) else float("nan")
        print(f"{name}: {len(d)} points, {rms:.3f} mm RMS")


if __name__ == "__main__":
    main()
