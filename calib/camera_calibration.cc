// Camera calibration with cv::calibrateCamera and its checks and output.
#include "calib/camera_calibration.h"

#include <cmath>

#include <opencv2/calib3d.hpp>

#include "calib/board_detection.h"
#include "host/core/atomic_file.h"
#include "host/core/errors.h"

namespace rfrecon::calib {

double board_tilt_spread_deg(const std::vector<cv::Mat>& board_rotations) {
  std::vector<cv::Vec3d> normals;
  for (const auto& rvec : board_rotations) {
    cv::Matx33d rotation;
    cv::Rodrigues(rvec, rotation);
    normals.emplace_back(rotation(0, 2), rotation(1, 2), rotation(2, 2));
  }
  double spread = 0.0;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    for (std::size_t j = i + 1; j < normals.size(); ++j) {
      const double cosine = std::clamp(std::abs(normals[i].dot(normals[j])), 0.0, 1.0);
      spread = std::max(spread, std::acos(cosine) * 180.0 / M_PI);
    }
  }
  return spread;
}

CameraCalibration calibrate_camera(const std::vector<BoardView>& views, const BoardSpec& board, cv::Size image_size,
                                   const CalibrationOptions& options) {
  if (static_cast<int>(views.size()) < options.min_views) {
    throw ProcessingError("calibration needs at least " + std::to_string(options.min_views) +
                          " views with the whole board found, got " + std::to_string(views.size()));
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
  result.dist_coeffs = cv::Mat::zeros(1, 5, CV_64F);
  cv::Mat per_view;
  cv::Mat std_intrinsics;
  cv::Mat std_extrinsics;
  const int flags = options.full_distortion ? 0 : cv::CALIB_FIX_K3;
  result.rms =
      cv::calibrateCamera(object_points, image_points, image_size, result.camera_matrix, result.dist_coeffs,
                          result.board_rotations, result.board_translations, std_intrinsics, std_extrinsics, per_view,
                          flags, cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12));
  result.per_view_errors.assign(per_view.begin<double>(), per_view.end<double>());
  const double spread = board_tilt_spread_deg(result.board_rotations);
  if (spread < options.min_tilt_spread_deg) {
    throw ProcessingError("degenerate board poses: all board normals lie within " + std::to_string(spread) +
                          " degrees of each other (need at least " + std::to_string(options.min_tilt_spread_deg) +
                          "); tilt the board differently in some views so the focal length is observable");
  }
  return result;
}

void write_camera_calibration(const CameraCalibration& calibration, const std::filesystem::path& file) {
  cv::FileStorage fs("camera.yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs << "image_size" << calibration.image_size;
  fs << "camera_matrix" << calibration.camera_matrix << "dist_coeffs" << calibration.dist_coeffs;
  fs << "rms" << calibration.rms << "per_view_errors" << calibration.per_view_errors;
  fs << "views" << calibration.view_names;
  fs << "board"
     << "{"
     << "cols" << calibration.board.cols << "rows" << calibration.board.rows << "square_size"
     << calibration.board.square_size << "}";
  write_file_atomically(file, fs.releaseAndGetString());
}

}  // namespace rfrecon::calib
