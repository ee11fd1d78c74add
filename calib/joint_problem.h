// The joint problem of a camera-projector calibration as one parameter vector: both devices' intrinsics and
// distortion, the stereo pose (om, T: projector from camera) and every board pose, with the residuals (projected -
// observed, px) of the board corners in both devices and of dense correspondences on the board: a camera pixel's ray
// meets the board's plane, and that point is projected into the projector and compared with the pixel's projector
// position from T. Central-difference Jacobians, per view, and a Levenberg-Marquardt adjustment.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "calib/distortion_model.h"

namespace rfrecon::calib {

// How much one series of a pose's observations (one device's corners, or the dense correspondences) counts in the
// adjustment: every residual is multiplied by sqrt(pose), and a point marked in `dropped` counts not at all
// (calib/residual_gating.h decides both).
struct ObservationWeights {
  double pose = 1.0;
  std::vector<unsigned char> dropped;  // per point; empty: none dropped
  bool kept(std::size_t point) const { return dropped.empty() || dropped[point] == 0; }
  double of(std::size_t point) const { return kept(point) ? pose : 0.0; }
};

// One board pose's observations: its corners in both devices, in the same order as its object points, and dense
// correspondences on the board (camera pixel, projector position; possibly none), with their weights.
struct StereoCorners {
  std::vector<cv::Point2f> camera;
  std::vector<cv::Point2f> projector;
  std::vector<cv::Point2f> dense_camera;
  std::vector<cv::Point2f> dense_projector;
  ObservationWeights camera_weights;
  ObservationWeights projector_weights;
  ObservationWeights dense_weights;
};

// Where each value lies in the parameter vector: camera then projector (fx, fy, cx, cy, distortion), om, T, then
// (rvec, tvec) per view, camera from board.
struct JointLayout {
  int dist_size = 5;
  int views = 0;
  int device_block() const { return 4 + dist_size; }
  int om() const { return 2 * device_block(); }
  int t() const { return om() + 3; }
  int pose(int view) const { return t() + 3 + 6 * view; }
  int size() const { return pose(views); }
};

// The estimated entries of the parameter vector (the model's distortion coefficients only) and their difference
// steps, the global ones first, then each view's six.
struct JointColumns {
  std::vector<int> index;
  std::vector<double> step;
  int globals = 0;  // entries before the first pose
};
JointColumns joint_columns(const JointLayout& layout, DistortionModel model);

class JointProblem {
 public:
  JointProblem(const std::vector<std::vector<cv::Point3f>>& object_points, const std::vector<StereoCorners>& corners,
               JointLayout layout);

  const JointLayout& layout() const { return layout_; }

  // View `view`'s residuals as the adjustment weighs them (each times the square root of its weight): camera corners,
  // projector corners, then dense correspondences, x and y interleaved.
  void view_residuals(const std::vector<double>& p, int view, std::vector<double>& out) const;
  std::vector<double> residuals(const std::vector<double>& p) const;
  // The same residuals unweighted (projected - observed, px), dropped points included.
  void view_errors(const std::vector<double>& p, int view, std::vector<double>& out) const;

  // The central-difference Jacobian of view `view`'s residuals over the parameters `index` (steps `step`).
  cv::Mat view_jacobian(const std::vector<double>& p, int view, const std::vector<int>& index,
                        const std::vector<double>& step) const;

  // Gauss-Newton on one view's pose with everything else fixed.
  void refine_pose(std::vector<double>& p, int view) const;

  // J^T J and J^T r over every estimated column (in the order of `columns`), assembled view by view: a view's
  // residuals depend on the global columns and its own pose only.
  void normal_equations(const std::vector<double>& p, const JointColumns& columns, cv::Mat& jtj, cv::Mat& jtr) const;

  // Levenberg-Marquardt over every estimated column; returns the final sum of squared residuals.
  double adjust(std::vector<double>& p, const JointColumns& columns) const;

 private:
  // The rays (undistorted normalised coordinates) of view `view`'s dense camera pixels under p's camera intrinsics and
  // distortion; empty without dense correspondences. Only the camera block of p changes them.
  std::vector<cv::Point2d> dense_rays(const std::vector<double>& p, int view) const;
  // view_residuals (weighted) or view_errors with those rays given.
  void view_residuals(const std::vector<double>& p, int view, const std::vector<cv::Point2d>& rays, bool weighted,
                      std::vector<double>& out) const;

  std::vector<std::vector<cv::Point3d>> object_points_;  // double, so projectPoints works in double
  const std::vector<StereoCorners>& corners_;
  JointLayout layout_;
};

}  // namespace rfrecon::calib
