// Corner detection with OpenCV calib3d, and hole filling for dual images.
#include "calib/board_detection.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "host/core/percentile.h"

namespace rfrecon::calib {

std::string board_options_text(const BoardSpec& board) {
  std::ostringstream text;
  text << "--board " << board.cols << "x" << board.rows << " --square " << board.square_size;
  return text.str();
}

std::vector<cv::Point3f> board_object_points(const BoardSpec& board) {
  std::vector<cv::Point3f> points;
  points.reserve(static_cast<std::size_t>(board.cols) * static_cast<std::size_t>(board.rows));
  for (int row = 0; row < board.rows; ++row) {
    for (int col = 0; col < board.cols; ++col) {
      points.emplace_back(static_cast<float>(col * board.square_size), static_cast<float>(row * board.square_size),
                          0.0f);
    }
  }
  return points;
}

namespace {
// One CV_32F channel (BGR images to gray), NaN kept.
cv::Mat float_gray(const cv::Mat& image) {
  cv::Mat gray;
  if (image.channels() == 1) {
    image.convertTo(gray, CV_32F);
  } else {
    cv::Mat converted;
    image.convertTo(converted, CV_32F);
    cv::cvtColor(converted, gray, cv::COLOR_BGR2GRAY);
  }
  return gray;
}
}  // namespace

cv::Mat to_detection_image(const cv::Mat& image) {
  if (image.depth() == CV_8U && image.channels() == 1) return image;
  cv::Mat gray = float_gray(image);
  const float percentile = finite_percentile(gray, 0.995);
  const float high = std::isnan(percentile) ? 1.0f : std::max(percentile, 1e-12f);
  cv::patchNaNs(gray, 0.0);
  cv::Mat out;
  gray.convertTo(out, CV_8U, 255.0 / high);
  return out;
}

namespace {

// The median distance between neighbouring corners along the board's rows, px.
float square_size_px(const std::vector<cv::Point2f>& corners, const BoardSpec& board) {
  std::vector<float> steps;
  for (int row = 0; row < board.rows; ++row) {
    for (int col = 0; col + 1 < board.cols; ++col) {
      const std::size_t i =
          static_cast<std::size_t>(row) * static_cast<std::size_t>(board.cols) + static_cast<std::size_t>(col);
      steps.push_back(static_cast<float>(cv::norm(corners[i + 1] - corners[i])));
    }
  }
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

// The saddle point of a weighted quadratic fit to `image` around `corner`, iterated from it; the corner is kept
// where the surface is not a saddle or the step leaves the fit window.
cv::Point2f saddle_point(const cv::Mat& image, cv::Point2f corner) {
  const int half = static_cast<int>(std::ceil(kSaddleFitRadiusPx)) + 1;
  const double sigma = kSaddleFitRadiusPx / 2.0;
  cv::Point2d p(corner);
  for (int iteration = 0; iteration < 20; ++iteration) {
    const int x0 = static_cast<int>(std::lround(p.x));
    const int y0 = static_cast<int>(std::lround(p.y));
    if (x0 - half < 0 || y0 - half < 0 || x0 + half >= image.cols || y0 + half >= image.rows) break;
    cv::Matx66d normal = cv::Matx66d::zeros();
    cv::Vec6d rhs = cv::Vec6d::all(0.0);
    for (int y = y0 - half; y <= y0 + half; ++y) {
      for (int x = x0 - half; x <= x0 + half; ++x) {
        const double dx = x - p.x;
        const double dy = y - p.y;
        const double w = std::exp(-(dx * dx + dy * dy) / (2.0 * sigma * sigma));
        const cv::Vec6d a(dx * dx, dx * dy, dy * dy, dx, dy, 1.0);
        normal += w * (a * a.t());
        rhs += w * static_cast<double>(image.at<float>(y, x)) * a;
      }
    }
    cv::Vec6d q;
    if (!cv::solve(normal, rhs, q, cv::DECOMP_CHOLESKY)) break;
    // z = q0 dx^2 + q1 dx dy + q2 dy^2 + q3 dx + q4 dy + q5: gradient zero where H s = -(q3, q4).
    const cv::Matx22d hessian(2.0 * q[0], q[1], q[1], 2.0 * q[2]);
    const double det = cv::determinant(hessian);
    if (det >= 0.0) break;  // not a saddle
    const cv::Vec2d step = -(hessian.inv() * cv::Vec2d(q[3], q[4]));
    const double length = std::hypot(step[0], step[1]);
    if (length > kSaddleFitRadiusPx) break;
    p += cv::Point2d(step[0], step[1]);
    if (length < 1e-4) break;
  }
  return cv::Point2f(p);
}

// Both detectors work on the 8-bit image and, on the rendered poses (shot noise, light falling off across the
// board), leave offsets of up to 0.2 px in each pose's mean corner that change with the board's tilt; cornerSubPix
// with a window of a fixed share of the median square reaches into neighbouring squares on foreshortened real
// boards. The saddle fit on the full-precision image does neither (docs/calibration.md).
void refine_on_float_image(const cv::Mat& image, const BoardSpec& board, std::vector<cv::Point2f>& corners) {
  cv::Mat gray = float_gray(image);
  cv::patchNaNs(gray, 0.0);
  cv::Mat illumination;
  cv::GaussianBlur(gray, illumination, cv::Size(), kRefineHighPassSquares * square_size_px(corners, board));
  gray -= illumination;
  cv::GaussianBlur(gray, gray, cv::Size(), kRefineBlurSigmaPx);
  for (auto& corner : corners) corner = saddle_point(gray, corner);
}

// Either detector's corners, or none.
std::vector<cv::Point2f> detect_corners(const cv::Mat& gray, const BoardSpec& board) {
  std::vector<cv::Point2f> corners;
  const cv::Size pattern(board.cols, board.rows);
  if (cv::findChessboardCornersSB(gray, pattern, corners, cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY)) {
    return corners;
  }
  // The classic detector finds some boards the sector detector misses (strong perspective).
  corners.clear();
  if (!cv::findChessboardCorners(gray, pattern, corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
    return {};
  }
  return corners;
}

}  // namespace

std::vector<cv::Point2f> find_board_corners(const cv::Mat& image, const BoardSpec& board) {
  std::vector<cv::Point2f> corners = detect_corners(to_detection_image(image), board);
  if (!corners.empty()) refine_on_float_image(image, board, corners);
  return corners;
}

cv::Mat fill_dual_image_holes(const cv::Mat& dual, const cv::Mat& reached) {
  cv::Mat values;
  dual.convertTo(values, CV_32F);
  const cv::Mat covered = (reached != 0) & (values == values);  // NaN != NaN
  values.setTo(0.0f, ~covered);
  // Gaps are unreached pixels inside the reached region: what a morphological closing adds. Wide unreached areas
  // (dark squares whose transport fell below the noise threshold, the background) are not gaps and stay as they are.
  cv::Mat closed;
  cv::morphologyEx(covered, closed, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(kMaxGapPx * 2 + 1, kMaxGapPx * 2 + 1)));
  const cv::Mat gaps = closed & ~covered;
  cv::Mat weight;
  covered.convertTo(weight, CV_32F, 1.0 / 255.0);
  cv::Mat blurred_values;
  cv::Mat blurred_weight;
  constexpr double kSigmaPx = 1.0;
  cv::GaussianBlur(values, blurred_values, cv::Size(), kSigmaPx);
  cv::GaussianBlur(weight, blurred_weight, cv::Size(), kSigmaPx);
  cv::Mat interpolated;
  cv::divide(blurred_values, cv::max(blurred_weight, 1e-6), interpolated);
  interpolated.copyTo(values, gaps);
  return values;
}

}  // namespace rfrecon::calib
