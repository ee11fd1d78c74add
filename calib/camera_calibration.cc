// Camera calibration with cv::calibrateCamera and its checks and output.
#include "calib/camera_calibration.h"

#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include <opencv2/calib3d.hpp>

#include "calib/board_detection.h"
#include "calib/pose_diversity.h"
#include "host/core/atomic_file.h"
#include "host/core/errors.h"

namespace rfrecon::calib {

CameraCalibration calibrate_camera(const std::vector<BoardView>& views, const BoardSpec& board, cv::Size image_size,
                                   const CalibrationOptions& options) {
  if (static_cast<int>(views.size()) < options.min_views) {
    throw ProcessingError("calibration needs at least " + std::to_string(options.min_views) +
                          " views with the whole board found, got " + std::to_string(views.size()) + " with " +
                          board_options_text(board) + ": " + kBoardAdvice);
  }
  const auto object = board_object_points(board);
  std::vector<std::vector<cv::Point3f>> object_points(views.size(), object);
  std::vector<std::vector<cv::Point2f>> image_points;
  CameraCalibration result;
  for (const auto& view : views) {
    image_points.push_back(view.corners);
    result.view_names.push_back(view.name);
  }
  result.image_size = image_size;
  result.board = board;
  result.camera_matrix = cv::Mat::eye(3, 3, CV_64F);
  result.dist_coeffs = cv::Mat::zeros(1, distortion_vector_size(options.distortion), CV_64F);
  std::vector<cv::Mat> rvecs;
  std::vector<cv::Mat> tvecs;
  cv::Mat per_view;
  cv::Mat std_intrinsics;
  cv::Mat std_extrinsics;
  const int flags = distortion_flags(options.distortion);
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12);
  if (options.refine_board) {
    cv::Mat new_object;
    cv::Mat std_object;
    result.rms = cv::calibrateCameraRO(object_points, image_points, image_size, board.cols - 1, result.camera_matrix,
                                       result.dist_coeffs, rvecs, tvecs, new_object, std_intrinsics, std_extrinsics,
                                       std_object, per_view, flags, criteria);
    result.board_points.assign(new_object.begin<cv::Point3f>(), new_object.end<cv::Point3f>());
  } else {
    result.rms = cv::calibrateCamera(object_points, image_points, image_size, result.camera_matrix, result.dist_coeffs,
                                     rvecs, tvecs, std_intrinsics, std_extrinsics, per_view, flags, criteria);
    result.board_points = object;
  }
  result.per_view_errors.assign(per_view.begin<double>(), per_view.end<double>());
  for (std::size_t i = 0; i < rvecs.size(); ++i) {
    result.board_rvecs.emplace_back(rvecs[i]);
    result.board_tvecs.emplace_back(tvecs[i]);
    std::vector<cv::Point2d> projected;
    const std::vector<cv::Point3d> board_points(result.board_points.begin(), result.board_points.end());
    cv::projectPoints(board_points, rvecs[i], tvecs[i], result.camera_matrix, result.dist_coeffs, projected);
    std::vector<cv::Point2d> residuals;
    for (std::size_t k = 0; k < projected.size(); ++k) {
      residuals.emplace_back(projected[k].x - image_points[i][k].x, projected[k].y - image_points[i][k].y);
    }
    result.residuals_px.push_back(std::move(residuals));
  }
  result.intrinsics_std = std_intrinsics.rowRange(0, 4).reshape(1, 1).clone();
  result.dist_coeffs_std =
      std_intrinsics.rowRange(4, 4 + static_cast<int>(result.dist_coeffs.total())).reshape(1, 1).clone();
  result.tilt_spread_deg = board_tilt_spread_deg(result.board_rvecs);
  if (result.tilt_spread_deg < options.min_tilt_spread_deg) {
    throw ProcessingError("degenerate board poses: all board normals lie within " +
                          std::to_string(result.tilt_spread_deg) + " degrees of each other (need at least " +
                          std::to_string(options.min_tilt_spread_deg) +
                          "); tilt the board differently in some views so the focal length is observable");
  }
  result.coverage = covered_fraction(board_coverage_counts(image_points, board, image_size));
  result.warnings = pose_set_warnings(static_cast<int>(views.size()), result.tilt_spread_deg);
  if (auto warning = coverage_warning("camera", result.coverage); !warning.empty()) {
    result.warnings.push_back(std::move(warning));
  }
  return result;
}

namespace {
// "fx 1479.84 +- 434.50 px (29 % of the value, limit 10 %)"
std::string spread_text(const char* name, double value, double std_px, double share, const char* of) {
  char text[160];
  std::snprintf(text, sizeof(text), "%s %.2f +- %.2f px (%.0f %% of %s, limit %.0f %%)", name, value, std_px,
                share * 100.0, of, kMaxIntrinsicsStdShare * 100.0);
  return text;
}
}  // namespace

void check_intrinsics_determined(const std::string& device, const cv::Mat& camera_matrix, const cv::Mat& intrinsics_std,
                                 double rms_px, cv::Size image_size, const BoardSpec& board, std::size_t views) {
  std::vector<std::string> evidence;
  const double fx = camera_matrix.at<double>(0, 0);
  const double fy = camera_matrix.at<double>(1, 1);
  if (!(fx > 0.0 && fy > 0.0)) {
    evidence.push_back("focal lengths fx " + std::to_string(fx) + ", fy " + std::to_string(fy) + " px (not positive)");
  } else {
    for (const auto& [name, value, std_px, scale, of] :
         {std::tuple{"fx", fx, intrinsics_std.at<double>(0), fx, "the value"},
          std::tuple{"fy", fy, intrinsics_std.at<double>(1), fy, "the value"},
          std::tuple{"cx", camera_matrix.at<double>(0, 2), intrinsics_std.at<double>(2),
                     static_cast<double>(image_size.width), "the image width"},
          std::tuple{"cy", camera_matrix.at<double>(1, 2), intrinsics_std.at<double>(3),
                     static_cast<double>(image_size.height), "the image height"}}) {
      const double share = std_px / scale;
      if (!(share <= kMaxIntrinsicsStdShare)) evidence.push_back(spread_text(name, value, std_px, share, of));
    }
  }
  if (!(rms_px <= kMaxCalibrationRmsPx)) {
    char text[96];
    std::snprintf(text, sizeof(text), "reprojection RMS %.2f px (limit %.0f px)", rms_px, kMaxCalibrationRmsPx);
    evidence.emplace_back(text);
  }
  if (evidence.empty()) return;
  std::string listed;
  for (const auto& item : evidence) listed += (listed.empty() ? "" : "; ") + item;
  throw ProcessingError(board_options_text(board) + ": the " + device + " intrinsics from " + std::to_string(views) +
                        " views are not determined (" + listed + "): " + kBoardAdvice +
                        ", and that the poses are many and tilted differently");
}

void write_camera_calibration(const CameraCalibration& calibration, const std::filesystem::path& file) {
  cv::FileStorage fs("camera.yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs << "image_size" << calibration.image_size;
  fs << "camera_matrix" << calibration.camera_matrix << "dist_coeffs" << calibration.dist_coeffs;
  fs << "intrinsics_std" << calibration.intrinsics_std << "dist_coeffs_std" << calibration.dist_coeffs_std;
  fs << "rms" << calibration.rms << "per_view_errors" << calibration.per_view_errors;
  fs << "views" << calibration.view_names;
  fs << "board"
     << "{"
     << "cols" << calibration.board.cols << "rows" << calibration.board.rows << "square_size"
     << calibration.board.square_size << "}";
  write_file_atomically(file, fs.releaseAndGetString());
}

}  // namespace rfrecon::calib
