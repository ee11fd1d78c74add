// The stereo rig file (rig.yaml): camera and projector intrinsics, their relative pose and rectification, as an
// OpenCV FileStorage YAML that the calibration stage writes, the synthetic rig writes as ground truth, and the
// reconstruction stage reads. Loadable from Python with cv2.FileStorage. Format documented in docs/sim.md.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon::calib {

struct BoardSpec {
  int cols = 0;              // inner corners along the board's x axis
  int rows = 0;              // inner corners along the board's y axis
  double square_size = 0.0;  // mm
};

// One standard deviation of each value a calibration estimated (empty matrices for a ground-truth rig), from the
// joint adjustment's covariance (calib/stereo_fit.h). Coefficients held fixed have 0.
struct RigUncertainty {
  cv::Mat camera_intrinsics;     // 1x4: fx, fy, cx, cy (px)
  cv::Mat camera_dist_coeffs;    // 1xN, the order of dist_coeffs
  cv::Mat projector_intrinsics;  // 1x4
  cv::Mat projector_dist_coeffs;
  cv::Mat proj_from_cam_rotation_vector;  // 1x3: cv::Rodrigues of proj_from_cam_rotation, rad (rig.yaml: om_std)
  cv::Mat proj_from_cam_translation_mm;   // 1x3, mm (rig.yaml: T_std)
  // The joint covariance of all of them (rig.yaml: parameter_covariance), G x G with G = 2 (4 + N) + 6 in the order
  // camera fx fy cx cy and its N distortion coefficients, the projector's the same, om (3), T (3); rows and columns of
  // coefficients held fixed are 0. Empty in a rig written before it was kept: only the diagonal is known then.
  cv::Mat parameter_covariance;
  bool empty() const { return camera_intrinsics.empty(); }
};

// Projector pose: X_proj = proj_from_cam_rotation X_cam + proj_from_cam_translation_mm (rig.yaml's R and T, as
// cv::stereoCalibrate returns them); lengths in millimetres. Frames are named b_from_a: the matrix takes a's
// coordinates to b's. "rect" is the rectified camera frame (calib/rectification.h). All matrices are CV_64F; the
// comment after each field gives its rig.yaml key (OpenCV's name).
struct StereoRig {
  cv::Size camera_size;
  cv::Size projector_size;
  cv::Mat camera_matrix;                 // 3x3
  cv::Mat dist_coeffs;                   // 1x5: k1 k2 p1 p2 k3 (OpenCV order; 1x4, 1x8, 1x12, 1x14 also accepted)
  cv::Mat projector_matrix;              // 3x3
  cv::Mat projector_dist_coeffs;         // 1xN as dist_coeffs
  cv::Mat proj_from_cam_rotation;        // R: 3x3
  cv::Mat proj_from_cam_translation_mm;  // T: 3x1
  cv::Mat essential;                     // E: 3x3, x_proj^T E x_cam = 0 for normalized image points
  cv::Mat fundamental;                   // F: 3x3, x_proj^T F x_cam = 0 for pixels
  // Row rectification in cv::stereoRectify's conventions (calib/rectification.h):
  cv::Mat rect_from_cam;              // R1: 3x3 rotation
  cv::Mat rect_from_proj;             // R2: 3x3 rotation
  cv::Mat rect_cam_image_from_rect;   // P1: 3x4, the rectified camera's projection
  cv::Mat rect_proj_image_from_rect;  // P2: 3x4, the rectified projector's projection
  cv::Mat rect_from_disparity;        // Q: 4x4, (u, v, disparity, 1) to homogeneous X_rect
  cv::Size rectified_camera_size;     // the images P1 and P2 map into (initUndistortRectifyMap sizes)
  cv::Size rectified_projector_size;
  double rms = 0.0;                     // reprojection RMS of the calibration, px (0 for ground truth)
  std::vector<double> per_view_errors;  // px per board pose, both devices (empty for ground truth)
  RigUncertainty uncertainty;
  BoardSpec board;
};

// G, the size of RigUncertainty::parameter_covariance for this rig's distortion model: 2 (4 + N) + 6 with N the
// camera's distortion coefficients (the projector has as many).
int rig_parameter_count(const StereoRig& rig);
// The rig's parameters in that order with `dist_size` coefficients per device (those beyond a device's own are 0),
// and the rig with them set from the first 2 (4 + dist_size) + 6 of `parameters` (a joint adjustment's board poses
// may follow): intrinsics, distortion, R from its rotation vector, T; the derived keys are left to
// compute_stereo_geometry. std::invalid_argument when there are fewer.
std::vector<double> rig_parameters(const StereoRig& rig, int dist_size);
void set_rig_parameters(StereoRig& rig, const std::vector<double>& parameters, int dist_size);

// rig.yaml's `format` and `version` keys; files without them (version 1) are still read.
inline constexpr const char* kRigFormat = "rfrecon-rig";
inline constexpr int kRigVersion = 2;

// Fills the essential and fundamental matrices and the row rectification (rectified sizes included) from the
// intrinsics and the projector pose.
// Throws InputError naming the key when the rig is degenerate (calib/rectification.h).
void compute_stereo_geometry(StereoRig& rig);

// The rig with its measured keys (sizes, intrinsics, distortion, projector pose) checked and its derived keys (E, F,
// the rectification) computed, as read_rig does for a file. Throws InputError starting with `where` and naming the key.
StereoRig complete_rig(StereoRig rig, const std::string& where);

// Writes the rig atomically. Throws InputError when a matrix has the wrong size.
void write_rig(const StereoRig& rig, const std::filesystem::path& file);

// Reads a rig file (with its standard deviations when it has them) and recomputes its derived keys (E, F, the
// rectification) from the intrinsics and the projector pose, so that a file of an older version reads the same as a new
// one. Throws InputError naming the file and the key when a key is missing, mis-sized or not finite, or the rig is
// degenerate.
StereoRig read_rig(const std::filesystem::path& file);

}  // namespace rfrecon::calib
