// Drawing of the residual field with OpenCV.
#include "calib/residual_field.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "host/core/percentile.h"

namespace rfrecon::calib {

namespace {
// The largest of 1, 2, 5 times a power of ten at most `value`.
double round_down_125(double value) {
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  for (const double step : {5.0, 2.0}) {
    if (step * decade <= value) return step * decade;
  }
  return decade;
}

double percentile_95(const std::vector<std::vector<cv::Point2d>>& residuals_px) {
  std::vector<double> lengths;
  for (const auto& view : residuals_px) {
    for (const auto& r : view) lengths.push_back(std::hypot(r.x, r.y));
  }
  return lengths.empty() ? 0.0 : percentile_of(std::move(lengths), 0.95);
}
}  // namespace

cv::Mat draw_residual_field(const cv::Mat& background, const std::vector<std::string>& view_names,
                            const std::vector<std::vector<cv::Point2f>>& detected_px,
                            const std::vector<std::vector<cv::Point2d>>& residuals_px,
                            const std::vector<std::vector<unsigned char>>& dropped, const std::string& title) {
  cv::Mat field;
  if (background.channels() == 1) {
    cv::cvtColor(background, field, cv::COLOR_GRAY2BGR);
  } else {
    field = background.clone();
  }
  field.convertTo(field, CV_8UC3, 0.45);
  constexpr double kArrowPx = 40.0;  // the 95th percentile residual's arrow
  const double typical = percentile_95(residuals_px);
  const double scale = typical > 0.0 ? round_down_125(kArrowPx / typical) : 1.0;
  const cv::Scalar red(40, 40, 255);
  const cv::Scalar white(255, 255, 255);
  for (std::size_t v = 0; v < residuals_px.size(); ++v) {
    // Hues from orange to violet (OpenCV's 0 to 180 scale), leaving red to the dropped corners.
    const double pose_hue =
        15.0 + 135.0 * static_cast<double>(v) / std::max(static_cast<double>(residuals_px.size()) - 1.0, 1.0);
    cv::Mat hue(1, 1, CV_8UC3, cv::Scalar(pose_hue, 200, 255));
    cv::cvtColor(hue, hue, cv::COLOR_HSV2BGR);
    const cv::Vec3b pose_colour = hue.at<cv::Vec3b>(0, 0);
    for (std::size_t i = 0; i < residuals_px[v].size(); ++i) {
      const bool is_dropped = v < dropped.size() && i < dropped[v].size() && dropped[v][i] != 0;
      const cv::Point2d from = detected_px[v][i];
      const cv::Point2d to = from + residuals_px[v][i] * scale;
      const cv::Scalar colour = is_dropped ? red : cv::Scalar(pose_colour[0], pose_colour[1], pose_colour[2]);
      cv::arrowedLine(field, from, to, colour, 2, cv::LINE_AA, 0, 0.25);
      if (is_dropped) cv::circle(field, from, 8, red, 2, cv::LINE_AA);
    }
    if (v < view_names.size()) {
      cv::putText(field, view_names[v], {10, 60 + 22 * static_cast<int>(v)}, cv::FONT_HERSHEY_SIMPLEX, 0.6,
                  cv::Scalar(pose_colour[0], pose_colour[1], pose_colour[2]), 2);
    }
  }
  // A bar of a round residual length about 100 px long, with the scale.
  const double bar_px = round_down_125(100.0 / scale);
  const int bar_length = static_cast<int>(std::lround(bar_px * scale));
  const cv::Point bar_start(10, field.rows - 20);
  cv::line(field, bar_start, bar_start + cv::Point(bar_length, 0), white, 3);
  char text[160];
  std::snprintf(text, sizeof(text), "%g px residual (arrows x%g)", bar_px, scale);
  cv::putText(field, text, bar_start + cv::Point(bar_length + 10, 5), cv::FONT_HERSHEY_SIMPLEX, 0.6, white, 2);
  std::snprintf(text, sizeof(text), "%s residual field (projected - detected), red: dropped by gating", title.c_str());
  cv::putText(field, text, {10, 30}, cv::FONT_HERSHEY_SIMPLEX, 0.7, white, 2);
  return field;
}

}  // namespace rfrecon::calib
