// Stereo calibration of the camera-projector pair.
#include "calib/stereo_calibration.h"

#include <opencv2/calib3d.hpp>

#include "calib/board_detection.h"

namespace rfrecon::calib {

StereoCalibration calibrate_stereo(const std::vector<StereoView>& views, const BoardSpec& board, cv::Size camera_size,
                                   cv::Size projector_size, const CalibrationOptions& options) {
  std::vector<BoardView> camera_views;
  std::vector<BoardView> projector_views;
  for (const auto& view : views) {
    camera_views.push_back({view.name, view.camera_corners});
    projector_views.push_back({view.name, view.projector_corners});
  }
  StereoCalibration result;
  result.camera = calibrate_camera(camera_views, board, camera_size, options);
  result.projector = calibrate_camera(projector_views, board, projector_size, options);

  StereoRig& rig = result.rig;
  rig.camera_size = camera_size;
  rig.projector_size = projector_size;
  rig.camera_matrix = result.camera.camera_matrix.clone();
  rig.dist_coeffs = result.camera.dist_coeffs.clone();
  rig.projector_matrix = result.projector.camera_matrix.clone();
  rig.projector_dist_coeffs = result.projector.dist_coeffs.clone();
  rig.board = board;

  std::vector<std::vector<cv::Point3f>> object_points(views.size(), board_object_points(board));
  std::vector<std::vector<cv::Point2f>> camera_points;
  std::vector<std::vector<cv::Point2f>> projector_points;
  for (const auto& view : views) {
    camera_points.push_back(view.camera_corners);
    projector_points.push_back(view.projector_corners);
  }
  cv::Mat per_view;  // N x 2: camera, projector
  const int flags = cv::CALIB_USE_INTRINSIC_GUESS | (options.full_distortion ? 0 : cv::CALIB_FIX_K3);
  rig.rms = cv::stereoCalibrate(object_points, camera_points, projector_points, rig.camera_matrix, rig.dist_coeffs,
                                rig.projector_matrix, rig.projector_dist_coeffs, camera_size, rig.R, rig.T, rig.E,
                                rig.F, per_view, flags,
                                cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-12));
  for (int i = 0; i < per_view.rows; ++i) {
    result.per_view_camera_errors.push_back(per_view.at<double>(i, 0));
    result.per_view_projector_errors.push_back(per_view.at<double>(i, 1));
    rig.per_view_errors.push_back(std::hypot(per_view.at<double>(i, 0), per_view.at<double>(i, 1)) / std::sqrt(2.0));
  }
  compute_stereo_geometry(rig);
  return result;
}

}  // namespace rfrecon::calib
