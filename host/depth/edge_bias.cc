// The edge-bias correction: Sobel gradients of the white frame, the Jacobian of the correspondences from NaN-aware
// window means of their central differences, and the offset moved back through it.
#include "host/depth/edge_bias.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace rfrecon::depth {

namespace {

constexpr int kJacobianWindow = 9;       // px, square
constexpr int kJacobianMinSamples = 10;  // central differences in the window
constexpr float kMaxStepPerPx = 5.0f;    // projector px per camera px: larger differences cross a depth edge
constexpr float kDarkestWhite = 1e-3f;   // the white frame's floor in the relative gradient

// d/dx (dx = 1) or d/dy of `values` by central differences, NaN where a neighbour is NaN or the step too large.
cv::Mat central_difference(const cv::Mat& values, int dx, int dy) {
  cv::Mat result(values.size(), CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  cv::parallel_for_(cv::Range(dy, values.rows - dy), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      for (int x = dx; x < values.cols - dx; ++x) {
        const float step = 0.5f * (values.at<float>(y + dy, x + dx) - values.at<float>(y - dy, x - dx));
        if (std::abs(step) < kMaxStepPerPx) result.at<float>(y, x) = step;  // false for NaN
      }
    }
  });
  return result;
}

// The mean of the finite values in a window around each pixel; NaN with fewer than kJacobianMinSamples of them.
cv::Mat window_mean(const cv::Mat& values) {
  const cv::Mat finite = values == values;  // 255 where not NaN
  cv::Mat zeroed = values.clone();
  zeroed.setTo(0.0f, ~finite);
  cv::Mat sums, counts;
  const cv::Size window(kJacobianWindow, kJacobianWindow);
  cv::boxFilter(zeroed, sums, CV_32F, window, cv::Point(-1, -1), false);
  cv::Mat finite_float;
  finite.convertTo(finite_float, CV_32F, 1.0 / 255.0);
  cv::boxFilter(finite_float, counts, CV_32F, window, cv::Point(-1, -1), false);
  cv::Mat mean = sums / cv::max(counts, 1.0f);
  mean.setTo(std::numeric_limits<float>::quiet_NaN(), counts < static_cast<float>(kJacobianMinSamples) - 0.5f);
  return mean;
}

}  // namespace

std::vector<float> correct_edge_bias(const std::vector<float>& correspondence, const std::vector<float>& white,
                                     cv::Size camera_size, double footprint_px2) {
  const auto pixels = static_cast<std::size_t>(camera_size.area());
  if (correspondence.size() != 2 * pixels || white.size() != pixels) {
    throw std::invalid_argument("correct_edge_bias: correspondence or white frame of the wrong size");
  }
  std::vector<float> corrected = correspondence;
  if (!(footprint_px2 > 0.0)) return corrected;
  const cv::Mat w(camera_size, CV_32F, const_cast<float*>(white.data()));
  cv::Mat gx, gy;
  cv::Sobel(w, gx, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(w, gy, CV_32F, 0, 1, 3, 1.0 / 8.0);
  cv::Mat uv[2];
  cv::split(cv::Mat(camera_size, CV_32FC2, const_cast<float*>(correspondence.data())), uv);
  // d(projector x)/d(camera x), d(projector x)/d(camera y), d(projector y)/d(camera x), d(projector y)/d(camera y).
  const cv::Mat jacobian[4] = {
      window_mean(central_difference(uv[0], 1, 0)), window_mean(central_difference(uv[0], 0, 1)),
      window_mean(central_difference(uv[1], 1, 0)), window_mean(central_difference(uv[1], 0, 1))};
  const auto s2 = static_cast<float>(footprint_px2);
  const float half_width = std::sqrt(3.0f * s2);
  cv::parallel_for_(cv::Range(0, camera_size.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      for (int x = 0; x < camera_size.width; ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(camera_size.width) + x;
        if (std::isnan(correspondence[2 * c])) continue;
        const float scale = s2 / std::max(w.at<float>(y, x), kDarkestWhite);
        float dx = scale * gx.at<float>(y, x), dy = scale * gy.at<float>(y, x);
        const float length = std::hypot(dx, dy);
        if (length > half_width) {
          dx *= half_width / length;
          dy *= half_width / length;
        }
        const float shift_x = jacobian[0].at<float>(y, x) * dx + jacobian[1].at<float>(y, x) * dy;
        const float shift_y = jacobian[2].at<float>(y, x) * dx + jacobian[3].at<float>(y, x) * dy;
        if (!std::isfinite(shift_x) || !std::isfinite(shift_y)) continue;
        corrected[2 * c] -= shift_x;
        corrected[2 * c + 1] -= shift_y;
      }
    }
  });
  return corrected;
}

}  // namespace rfrecon::depth
