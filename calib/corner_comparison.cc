// Detected corners (corners.json) against true corners (board_poses.json) projected through the true rig.
#include "calib/corner_comparison.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <opencv2/calib3d.hpp>

#include "host/core/errors.h"
#include "host/core/json_file.h"
#include "host/core/message_text.h"

namespace rfrecon::calib {

namespace {
struct ErrorSums {
  cv::Point2d sum;
  double squares = 0.0;
  double max = 0.0;
  int count = 0;

  // Adds detected - expected, in whichever of the two numberings of the board is closer.
  void add(std::vector<cv::Point2f> detected, const std::vector<cv::Point2d>& expected) {
    if (detected.empty()) return;
    if (detected.size() != expected.size()) {
      throw std::invalid_argument("compare_corners: " + std::to_string(detected.size()) + " detected corners for " +
                                  std::to_string(expected.size()) + " true ones");
    }
    if (cv::norm(cv::Point2d(detected.front()) - expected.front()) >
        cv::norm(cv::Point2d(detected.front()) - expected.back())) {
      std::reverse(detected.begin(), detected.end());
    }
    for (std::size_t i = 0; i < detected.size(); ++i) {
      const cv::Point2d d = cv::Point2d(detected[i]) - expected[i];
      sum += d;
      squares += d.dot(d);
      max = std::max(max, std::hypot(d.x, d.y));
      ++count;
    }
  }

  CornerErrors errors() const {
    CornerErrors e;
    if (count == 0) return e;
    e.mean_px = sum / count;
    e.rms_px = std::sqrt(squares / (2.0 * count));
    e.max_px = max;
    e.corners = count;
    return e;
  }
};

// The points of `field` in `file`: an array of arrays of `dims` numbers.
std::vector<std::vector<double>> read_points(const nlohmann::json& list, std::size_t dims,
                                             const std::filesystem::path& file, const std::string& field) {
  std::string problem;
  auto points = json_as<std::vector<std::vector<double>>>(list, problem);
  if (points && std::any_of(points->begin(), points->end(), [&](const auto& p) { return p.size() != dims; })) {
    points.reset();
    problem = "an array of [" + std::string(dims == 2 ? "x, y" : "x, y, z") + "] points";
  }
  if (!points) throw InputError(file.string() + ": " + field + " must be " + problem);
  return *points;
}

std::vector<cv::Point2f> read_pixels(const nlohmann::json& list, const std::filesystem::path& file,
                                     const std::string& field) {
  std::vector<cv::Point2f> out;
  for (const auto& p : read_points(list, 2, file, field)) out.emplace_back(p[0], p[1]);
  return out;
}

std::vector<cv::Point2d> project(const std::vector<cv::Point3d>& points, const cv::Mat& rotation,
                                 const cv::Mat& translation, const cv::Mat& matrix, const cv::Mat& dist) {
  std::vector<cv::Point2d> out;
  if (!points.empty()) cv::projectPoints(points, rotation, translation, matrix, dist, out);
  return out;
}
}  // namespace

std::vector<ViewCorners> read_view_corners(const std::filesystem::path& corners,
                                           const std::filesystem::path& board_poses) {
  std::map<std::string, std::vector<cv::Point3d>> truth;
  for (const auto& pose : read_json_file(board_poses)) {
    if (!pose.is_object() || !pose.contains("view") || !pose["view"].is_string() ||
        !pose.contains("inner_corners_cam_mm")) {
      throw InputError(board_poses.string() + ": every entry needs \"view\" and \"inner_corners_cam_mm\"");
    }
    auto& corners_mm = truth[pose["view"].get<std::string>()];
    for (const auto& p : read_points(pose["inner_corners_cam_mm"], 3, board_poses, "inner_corners_cam_mm")) {
      corners_mm.emplace_back(p[0], p[1], p[2]);
    }
  }
  const auto found = read_json_file(corners);
  if (!found.contains("views") || !found["views"].is_array()) {
    throw InputError(corners.string() + ": no \"views\" array (not a corners.json of `rfrecon calibrate`)");
  }
  std::vector<ViewCorners> views;
  for (const auto& view : found["views"]) {
    if (!view.is_object() || !view.contains("name") || !view["name"].is_string()) {
      throw InputError(corners.string() + ": every view needs a \"name\"");
    }
    const std::string name = view["name"].get<std::string>();
    const auto known = truth.find(name);
    if (known == truth.end()) {
      throw InputError(corners.string() + ": view '" + excerpt(name) + "' is not in " + board_poses.string());
    }
    views.push_back({known->second, read_pixels(view.value("camera_px", nlohmann::json()), corners, "camera_px"),
                     read_pixels(view.value("projector_px", nlohmann::json()), corners, "projector_px")});
    if (views.back().camera_px.size() != known->second.size() ||
        views.back().projector_px.size() != known->second.size()) {
      throw InputError(corners.string() + ": view '" + excerpt(name) + "' has other corner counts than its board");
    }
  }
  return views;
}

CornerComparison compare_corners(const std::vector<ViewCorners>& views, const StereoRig& truth) {
  ErrorSums camera, projector;
  const cv::Mat identity = cv::Mat::eye(3, 3, CV_64F);
  const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
  for (const auto& view : views) {
    camera.add(view.camera_px,
               project(view.true_corners_cam_mm, identity, zero, truth.camera_matrix, truth.dist_coeffs));
    projector.add(view.projector_px,
                  project(view.true_corners_cam_mm, truth.proj_from_cam_rotation, truth.proj_from_cam_translation_mm,
                          truth.projector_matrix, truth.projector_dist_coeffs));
  }
  return {camera.errors(), projector.errors()};
}

}  // namespace rfrecon::calib
