// Tilt spread, coverage and pose-set warnings.
#include "calib/pose_diversity.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace rfrecon::calib {

double board_tilt_spread_deg(const std::vector<cv::Vec3d>& board_rvecs) {
  std::vector<cv::Vec3d> normals;
  for (const auto& rvec : board_rvecs) {
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

cv::Mat board_coverage_counts(const std::vector<std::vector<cv::Point2f>>& corners, const BoardSpec& board,
                              cv::Size image_size) {
  cv::Mat counts = cv::Mat::zeros(image_size, CV_32S);
  const auto at = [&](const std::vector<cv::Point2f>& view, int row, int col) {
    return view[static_cast<std::size_t>(row) * static_cast<std::size_t>(board.cols) + static_cast<std::size_t>(col)];
  };
  for (const auto& view : corners) {
    if (view.size() != static_cast<std::size_t>(board.cols) * static_cast<std::size_t>(board.rows)) continue;
    // Each outer corner of the pattern: the grid's extreme corner moved one square outward along both grid axes.
    std::vector<cv::Point> pattern;
    for (const auto& [row, col] :
         {std::pair{0, 0}, {0, board.cols - 1}, {board.rows - 1, board.cols - 1}, {board.rows - 1, 0}}) {
      const int inward_row = row == 0 ? 1 : row - 1;
      const int inward_col = col == 0 ? 1 : col - 1;
      const cv::Point2f corner = at(view, row, col);
      const cv::Point2f outer = corner + (corner - at(view, row, inward_col)) + (corner - at(view, inward_row, col));
      pattern.emplace_back(cvRound(outer.x), cvRound(outer.y));
    }
    cv::Mat mask = cv::Mat::zeros(image_size, CV_8U);
    cv::fillConvexPoly(mask, pattern, cv::Scalar(1));
    cv::add(counts, cv::Scalar(1), counts, mask);
  }
  return counts;
}

double covered_fraction(const cv::Mat& coverage_counts) {
  const double cell =
      static_cast<double>(std::max(coverage_counts.cols, coverage_counts.rows)) / kCoverageCellsLongSide;
  const int cols = std::max(1, static_cast<int>(std::lround(coverage_counts.cols / cell)));
  const int rows = std::max(1, static_cast<int>(std::lround(coverage_counts.rows / cell)));
  int covered = 0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const int x = std::min(coverage_counts.cols - 1, static_cast<int>((c + 0.5) * coverage_counts.cols / cols));
      const int y = std::min(coverage_counts.rows - 1, static_cast<int>((r + 0.5) * coverage_counts.rows / rows));
      if (coverage_counts.at<int>(y, x) > 0) ++covered;
    }
  }
  return static_cast<double>(covered) / (rows * cols);
}

std::vector<std::string> pose_set_warnings(int views, double tilt_spread_deg) {
  std::vector<std::string> warnings;
  char text[256];
  if (views < kRecommendedPoses) {
    std::snprintf(text, sizeof(text), "only %d poses: %d or more make the focal lengths and the baseline reliable",
                  views, kRecommendedPoses);
    warnings.emplace_back(text);
  }
  if (tilt_spread_deg < kRecommendedTiltSpreadDeg) {
    std::snprintf(text, sizeof(text),
                  "the board's tilts span %.0f degrees: tilt it by 30 to 45 degrees about different axes so the "
                  "focal length is well observed",
                  tilt_spread_deg);
    warnings.emplace_back(text);
  }
  return warnings;
}

std::string coverage_warning(const std::string& device, double coverage) {
  if (coverage >= kRecommendedCoverage) return {};
  char text[256];
  std::snprintf(text, sizeof(text),
                "the boards cover %.0f%% of the %s image: move the board into the uncovered regions (see the "
                "coverage map) so the distortion is constrained everywhere",
                100.0 * coverage, device.c_str());
  return text;
}

}  // namespace rfrecon::calib
