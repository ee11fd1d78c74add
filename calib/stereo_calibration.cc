// Stereo calibration of the camera-projector pair.
#include "calib/stereo_calibration.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/calib3d.hpp>

#include "calib/board_detection.h"
#include "calib/pose_diversity.h"
#include "host/core/errors.h"

namespace rfrecon::calib {

namespace {
constexpr int kGatingRounds = 3;

// The RMS length of the corner residuals in both devices, as cv::stereoCalibrate reports it (per point, not per
// coordinate): of the corners kept, or with `all` of every corner.
double corner_rms(const StereoFit& fit, const std::vector<StereoCorners>& corners, bool all) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t v = 0; v < corners.size(); ++v) {
    for (const auto& [residuals, weights] :
         {std::pair{&fit.camera_residuals_px[v], &corners[v].camera_weights},
          std::pair{&fit.projector_residuals_px[v], &corners[v].projector_weights}}) {
      for (std::size_t i = 0; i < residuals->size(); ++i) {
        if (!all && !weights->kept(i)) continue;
        sum += (*residuals)[i].dot((*residuals)[i]);
        ++count;
      }
    }
  }
  return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

// One gating round over the fit's residuals: both devices' corners, then the dense correspondences per pose.
std::vector<GatingDecision> gate_fit(const StereoFit& fit, const std::vector<StereoView>& views,
                                     std::vector<StereoCorners>& corners, const GatingThresholds& thresholds, int round,
                                     bool dense) {
  std::vector<std::string> names;
  names.reserve(views.size());
  for (const auto& view : views) names.push_back(view.name);
  std::vector<GatingDecision> decisions;
  const auto gate = [&](const char* series, const std::vector<std::vector<cv::Point2d>>& residuals, bool per_point,
                        ObservationWeights StereoCorners::*member) {
    std::vector<ObservationWeights*> weights;
    weights.reserve(corners.size());
    for (auto& view : corners) weights.push_back(&(view.*member));
    const auto made = gate_series(names, series, residuals, per_point, thresholds, round, weights);
    decisions.insert(decisions.end(), made.begin(), made.end());
  };
  gate("camera", fit.camera_residuals_px, true, &StereoCorners::camera_weights);
  gate("projector", fit.projector_residuals_px, true, &StereoCorners::projector_weights);
  if (dense) gate("dense", fit.dense_residuals_px, false, &StereoCorners::dense_weights);
  return decisions;
}
}  // namespace

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
  check_intrinsics_determined("camera", result.camera.camera_matrix, result.camera.intrinsics_std, result.camera.rms,
                              camera_size, board, views.size());
  CalibrationOptions projector_options = options;
  projector_options.refine_board = false;  // the camera's board is the one used jointly
  result.projector = calibrate_camera(projector_views, board, projector_size, projector_options);
  check_intrinsics_determined("projector", result.projector.camera_matrix, result.projector.intrinsics_std,
                              result.projector.rms, projector_size, board, views.size());

  StereoRig& rig = result.rig;
  rig.camera_size = camera_size;
  rig.projector_size = projector_size;
  rig.camera_matrix = result.camera.camera_matrix.clone();
  rig.dist_coeffs = result.camera.dist_coeffs.clone();
  rig.projector_matrix = result.projector.camera_matrix.clone();
  rig.projector_dist_coeffs = result.projector.dist_coeffs.clone();
  rig.board = board;

  const std::vector<std::vector<cv::Point3f>> object_points(views.size(), result.camera.board_points);
  std::vector<std::vector<cv::Point2f>> camera_points;
  std::vector<std::vector<cv::Point2f>> projector_points;
  std::vector<StereoCorners> corners;
  for (const auto& view : views) {
    camera_points.push_back(view.camera_corners);
    projector_points.push_back(view.projector_corners);
    corners.push_back(
        {view.camera_corners, view.projector_corners, view.dense.camera, view.dense.projector, {}, {}, {}});
  }
  const int flags = cv::CALIB_USE_INTRINSIC_GUESS | distortion_flags(options.distortion);
  rig.rms =
      cv::stereoCalibrate(object_points, camera_points, projector_points, rig.camera_matrix, rig.dist_coeffs,
                          rig.projector_matrix, rig.projector_dist_coeffs, camera_size, rig.proj_from_cam_rotation,
                          rig.proj_from_cam_translation_mm, rig.essential, rig.fundamental, flags,
                          cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-12));
  const bool dense = std::any_of(views.begin(), views.end(), [](const auto& v) { return !v.dense.camera.empty(); });
  std::size_t outliers = 0;
  if (dense) {
    // 1 px: beyond the corners-only solution's error at those points (it leaves none of the rendered boards' out),
    // below a misdecoded correspondence's (a Gray bit wrong: a projector pixel or more).
    outliers = reject_dense_outliers(rig, object_points, corners, options.distortion, 1.0);
    adjust_stereo(rig, object_points, corners, options.distortion);
  }
  result.fit = analyse_stereo_fit(rig, object_points, corners, options.distortion);
  for (int round = 1; options.gating && round <= kGatingRounds; ++round) {
    const auto decisions = gate_fit(result.fit, views, corners, result.gating_thresholds, round, dense);
    if (decisions.empty()) break;
    result.gating.insert(result.gating.end(), decisions.begin(), decisions.end());
    adjust_stereo(rig, object_points, corners, options.distortion);
    result.fit = analyse_stereo_fit(rig, object_points, corners, options.distortion);
  }
  if (dense || !result.gating.empty()) rig.rms = corner_rms(result.fit, corners, false);
  result.rms_all_px = corner_rms(result.fit, corners, true);
  for (const auto& view : corners) {
    result.camera_dropped.push_back(view.camera_weights.dropped);
    result.projector_dropped.push_back(view.projector_weights.dropped);
  }
  rig.uncertainty = result.fit.uncertainty;
  for (std::size_t i = 0; i < views.size(); ++i) {
    rig.per_view_errors.push_back(std::hypot(result.fit.camera_view_rms_px[i], result.fit.projector_view_rms_px[i]) /
                                  std::sqrt(2.0));
  }
  check_intrinsics_determined("jointly adjusted camera", rig.camera_matrix, rig.uncertainty.camera_intrinsics, rig.rms,
                              camera_size, board, views.size());
  check_intrinsics_determined("jointly adjusted projector", rig.projector_matrix, rig.uncertainty.projector_intrinsics,
                              rig.rms, projector_size, board, views.size());
  try {
    compute_stereo_geometry(rig);
  } catch (const InputError& error) {  // the rig is degenerate: a calibration's failure, not a rig file's
    throw ProcessingError(board_options_text(board) + ": the rig calibrated from " + std::to_string(views.size()) +
                          " poses cannot be rectified (" + error.what() + "): " + kBoardAdvice);
  }

  result.warnings = pose_set_warnings(static_cast<int>(views.size()), result.camera.tilt_spread_deg);
  if (outliers > 0) {
    result.warnings.push_back(std::to_string(outliers) +
                              " dense correspondences lay over 1 px from the corners' solution and were left out");
  }
  for (auto warning :
       {coverage_warning("camera", result.camera.coverage), coverage_warning("projector", result.projector.coverage)}) {
    if (!warning.empty()) result.warnings.push_back(std::move(warning));
  }
  return result;
}

}  // namespace rfrecon::calib
