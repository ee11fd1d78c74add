// Sampling of dense correspondences on the white squares of a calibration board.
#include "calib/dense_correspondences.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "host/core/percentile.h"

namespace rfrecon::calib {

DenseCorrespondences sample_dense_correspondences(const cv::Mat& white, const cv::Mat& correspondence,
                                                  const std::vector<cv::Point2f>& corners, int max_points) {
  DenseCorrespondences dense;
  if (max_points <= 0 || corners.size() < 3 || white.empty() || correspondence.size() != white.size()) return dense;
  std::vector<cv::Point> hull;
  std::vector<cv::Point> corner_pixels;
  corner_pixels.reserve(corners.size());
  for (const auto& c : corners) corner_pixels.emplace_back(cvRound(c.x), cvRound(c.y));
  cv::convexHull(corner_pixels, hull);
  cv::Mat inside = cv::Mat::zeros(white.size(), CV_8U);
  cv::fillConvexPoly(inside, hull, cv::Scalar(255));

  cv::Mat image;
  white.convertTo(image, CV_32F);
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5));
  cv::Mat darkest;
  cv::Mat brightest;
  cv::erode(image, darkest, kernel);
  cv::dilate(image, brightest, kernel);
  // The board's white level: the 90th percentile inside the outline (about half of it is white squares).
  cv::Mat on_board(image.size(), CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  image.copyTo(on_board, inside);
  const float white_level = finite_percentile(on_board, 0.9);
  if (std::isnan(white_level)) return dense;

  std::vector<cv::Point> candidates;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const auto& to = correspondence.at<cv::Vec2f>(y, x);
      if (inside.at<std::uint8_t>(y, x) && image.at<float>(y, x) >= 0.5f * white_level &&
          darkest.at<float>(y, x) >= 0.85f * brightest.at<float>(y, x) && std::isfinite(to[0]) &&
          std::isfinite(to[1])) {
        candidates.emplace_back(x, y);
      }
    }
  }
  const std::size_t stride =
      std::max<std::size_t>(1, (candidates.size() + static_cast<std::size_t>(max_points) - 1) / max_points);
  for (std::size_t i = 0; i < candidates.size(); i += stride) {
    const cv::Point& c = candidates[i];
    const auto& to = correspondence.at<cv::Vec2f>(c);
    dense.camera.emplace_back(static_cast<float>(c.x), static_cast<float>(c.y));
    dense.projector.emplace_back(to[0], to[1]);
  }
  return dense;
}

}  // namespace rfrecon::calib
