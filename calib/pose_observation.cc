// Corner detection in the camera and dual images of one pose, and their common order.
#include "calib/pose_observation.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "calib/board_detection.h"

namespace rfrecon::calib {

namespace {
// The projector position of camera point `at`: the nearest known correspondence within a few pixels.
std::optional<cv::Point2f> correspondence_near(const cv::Mat& correspondence, cv::Point2f at) {
  constexpr int kRadius = 3;
  const int cx = static_cast<int>(std::lround(at.x));
  const int cy = static_cast<int>(std::lround(at.y));
  std::optional<cv::Point2f> best;
  float best_distance = 0.0f;
  for (int y = std::max(0, cy - kRadius); y <= std::min(correspondence.rows - 1, cy + kRadius); ++y) {
    for (int x = std::max(0, cx - kRadius); x <= std::min(correspondence.cols - 1, cx + kRadius); ++x) {
      const auto& value = correspondence.at<cv::Vec2f>(y, x);
      if (!std::isfinite(value[0]) || !std::isfinite(value[1])) continue;
      const float distance = std::hypot(static_cast<float>(x) - at.x, static_cast<float>(y) - at.y);
      if (!best || distance < best_distance) {
        best = cv::Point2f(value[0], value[1]);
        best_distance = distance;
      }
    }
  }
  return best;
}

}  // namespace

std::string align_corner_order(const std::vector<cv::Point2f>& camera_corners, const cv::Mat& correspondence,
                               std::vector<cv::Point2f>& projector_corners) {
  if (camera_corners.size() < 2 || camera_corners.size() != projector_corners.size()) {
    return "camera and projector corner counts differ";
  }
  const auto first = correspondence_near(correspondence, camera_corners.front());
  const auto last = correspondence_near(correspondence, camera_corners.back());
  if (!first || !last) {
    return "no projector correspondence near the board's first or last corner: cannot match camera and projector "
           "corners";
  }
  const auto distance = [](cv::Point2f a, cv::Point2f b) { return std::hypot(a.x - b.x, a.y - b.y); };
  const float as_given = distance(*first, projector_corners.front()) + distance(*last, projector_corners.back());
  const float reversed = distance(*first, projector_corners.back()) + distance(*last, projector_corners.front());
  // Each end within half a square: the corners along the first row are one square apart.
  const float square_px = distance(projector_corners[0], projector_corners[1]);
  if (!(std::min(as_given, reversed) < square_px)) {
    return "the camera board's ends map " + std::to_string(std::lround(std::min(as_given, reversed))) +
           " projector px (both ends together) from the dual image's board ends, more than a square (" +
           std::to_string(std::lround(square_px)) +
           " px): the camera and dual images show different parts of the board, so their corners cannot be put in "
           "one order";
  }
  if (reversed < as_given) std::reverse(projector_corners.begin(), projector_corners.end());
  return {};
}

PoseObservation observe_board(const std::string& name, const cv::Mat& camera_image, const cv::Mat& dual_image,
                              const cv::Mat& dual_reached, const cv::Mat& correspondence, const BoardSpec& board) {
  PoseObservation pose;
  pose.name = name;
  pose.camera_image = camera_image;
  pose.dual_image = fill_dual_image_holes(dual_image, dual_reached);
  pose.camera_corners = find_board_corners(pose.camera_image, board);
  if (pose.camera_corners.empty()) {
    pose.problem = "board not found in the camera image (white frame)";
    return pose;
  }
  pose.camera_overhang = board_overhang(pose.camera_image, board, pose.camera_corners);
  pose.projector_corners = find_board_corners(pose.dual_image, board);
  if (pose.projector_corners.empty()) {
    pose.problem = "board not found in the dual image T^T 1 (is the board lit by the projector?)";
    return pose;
  }
  pose.problem = align_corner_order(pose.camera_corners, correspondence, pose.projector_corners);
  return pose;
}

}  // namespace rfrecon::calib
