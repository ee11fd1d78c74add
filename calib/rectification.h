// Row rectification of any calibrated rig: rotations that make every epipolar line a row (a vertical baseline gives
// a frame rotated by 90 degrees), one focal length fine enough for both devices, and the rectified image extents, in
// cv::stereoRectify's conventions (R1, R2, P1, P2, Q). Used for rig.yaml and by the depth stage.
#pragma once

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::calib {

// The rectified camera frame has its x axis from the camera centre toward the projector centre, z between the two
// optical axes; the rectified projector frame is the same frame moved to the projector centre, so a point seen at
// rectified camera pixel (u, v) projects to the projector's rectified row v. Image coordinates have pixel centres at
// integers; the rectified images hold every pixel of their device (nothing is cropped).
struct RowRectification {
  cv::Matx33d rect_from_cam;          // R1: X_rect = R1 X_cam
  cv::Matx33d rect_from_proj;         // R2: X_rect_proj = R2 X_proj = X_rect - (baseline_mm, 0, 0)
  double f_px = 0.0;                  // rectified focal length: the largest focal length of either device
  double cx_cam_px = 0.0;             // rectified principal point x of the camera
  double cx_proj_px = 0.0;            // rectified principal point x of the projector
  double cy_px = 0.0;                 // rectified principal point y (shared: rows line up)
  double baseline_mm = 0.0;           // |T| > 0: the projector centre is at (baseline_mm, 0, 0) of the rectified frame
  cv::Size camera_size;               // rectified camera image holding every camera pixel
  cv::Size projector_size;            // rectified projector image: the camera's rows, every projector column
  cv::Mat rect_cam_image_from_rect;   // P1: 3x4 CV_64F, [f 0 cx_cam 0; 0 f cy 0; 0 0 1 0]
  cv::Mat rect_proj_image_from_rect;  // P2: 3x4 CV_64F, [f 0 cx_proj -f b; 0 f cy 0; 0 0 1 0]
  cv::Mat rect_from_disparity;        // Q: 4x4 CV_64F, disparity to depth (cv::reprojectImageTo3D)
};

// Undistortion to tight tolerance for cv::undistortPoints: its default 5 iterations leave ~1e-3 px at the corners of
// a lens with k1 = -0.08, which is a visible depth error.
cv::TermCriteria undistort_criteria();

// Largest side of a rectified image; a rig needing more has devices at a grazing angle to each other.
inline constexpr int kMaxRectifiedSide = 1 << 15;

// Throws InputError naming the rig key at fault (T for a baseline near zero or along the viewing direction, R for a
// rotation that turns the devices away from each other, camera_matrix or projector_matrix for sizes and focal
// lengths) when the rig cannot be rectified into rows.
RowRectification rectify_rig(const StereoRig& rig);

}  // namespace rfrecon::calib
