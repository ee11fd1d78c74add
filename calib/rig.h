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
  cv::Mat om;  // 1x3: the rotation vector of R (cv::Rodrigues), rad
  cv::Mat T;   // 1x3, mm
  bool empty() const { return camera_intrinsics.empty(); }
};

// Projector pose: X_proj = R X_cam + T (cv::stereoCalibrate convention); lengths in millimetres.
// All matrices are CV_64F.
struct StereoRig {
  cv::Size camera_size;
  cv::Size projector_size;
  cv::Mat camera_matrix;           // 3x3
  cv::Mat dist_coeffs;             // 1x5: k1 k2 p1 p2 k3 (OpenCV order; 1x4, 1x8, 1x12, 1x14 also accepted)
  cv::Mat projector_matrix;        // 3x3
  cv::Mat projector_dist_coeffs;   // 1xN as dist_coeffs
  cv::Mat R;                       // 3x3, projector from camera
  cv::Mat T;                       // 3x1, projector from camera, mm
  cv::Mat E, F;                    // 3x3 essential and fundamental matrices
  cv::Mat R1, R2, P1, P2, Q;       // row rectification, cv::stereoRectify conventions (calib/rectification.h)
  cv::Size rectified_camera_size;  // the images P1, P2 map into (initUndistortRectifyMap sizes)
  cv::Size rectified_projector_size;
  double rms = 0.0;                     // reprojection RMS of the calibration, px (0 for ground truth)
  std::vector<double> per_view_errors;  // px per board pose, both devices (empty for ground truth)
  RigUncertainty uncertainty;
  BoardSpec board;
};

// rig.yaml's `format` and `version` keys; files without them (version 1) are still read.
inline constexpr const char* kRigFormat = "rfrecon-rig";
inline constexpr int kRigVersion = 2;

// Fills E, F and the row rectification (R1, R2, P1, P2, Q, rectified sizes) from the intrinsics, R and T.
// Throws InputError naming the key when the rig is degenerate (calib/rectification.h).
void compute_stereo_geometry(StereoRig& rig);

// The rig with its measured keys (sizes, intrinsics, distortion, R, T) checked and its derived keys (E, F, the
// rectification) computed, as read_rig does for a file. Throws InputError starting with `where` and naming the key.
StereoRig complete_rig(StereoRig rig, const std::string& where);

// Writes the rig atomically. Throws InputError when a matrix has the wrong size.
void write_rig(const StereoRig& rig, const std::filesystem::path& file);

// Reads a rig file (with its standard deviations when it has them) and recomputes its derived keys (E, F, the
// rectification) from the intrinsics, R and T, so that a file of an older version reads the same as a new one. Throws
// InputError naming the file and the key when a key is missing, mis-sized or not finite, or the rig is degenerate.
StereoRig read_rig(const std::filesystem::path& file);

}  // namespace rfrecon::calib
