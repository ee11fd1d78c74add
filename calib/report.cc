// Drawing of calibration report images with OpenCV.
#include "calib/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "calib/board_detection.h"
#include "calib/pose_diversity.h"

namespace rfrecon::calib {

cv::Mat draw_corners(const cv::Mat& image, const calib::BoardSpec& board, const std::vector<cv::Point2f>& corners) {
  cv::Mat colour;
  cv::cvtColor(calib::to_detection_image(image), colour, cv::COLOR_GRAY2BGR);
  if (corners.empty()) {
    const cv::Scalar red(0, 0, 255);
    cv::line(colour, {0, 0}, {colour.cols - 1, colour.rows - 1}, red, 2);
    cv::line(colour, {colour.cols - 1, 0}, {0, colour.rows - 1}, red, 2);
    cv::putText(colour, "board not found", {10, 30}, cv::FONT_HERSHEY_SIMPLEX, 0.8, red, 2);
  } else {
    cv::drawChessboardCorners(colour, cv::Size(board.cols, board.rows), corners, true);
  }
  return colour;
}

cv::Mat draw_error_chart(const std::vector<std::string>& view_names, const std::vector<std::string>& series_names,
                         const std::vector<std::vector<double>>& series_errors_px) {
  const int group_width = 24 * static_cast<int>(std::max<std::size_t>(series_names.size(), 1)) + 16;
  const int left = 70;
  const int top = 40;
  const int plot_height = 300;
  const int width = std::max(left + group_width * static_cast<int>(view_names.size()) + 20, 420);
  const int height = top + plot_height + 110;
  cv::Mat chart(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  double max_error = 1e-6;
  for (const auto& series : series_errors_px) {
    for (const double e : series) max_error = std::max(max_error, e);
  }
  const double scale = plot_height / (max_error * 1.1);
  const cv::Scalar black(0, 0, 0);
  const cv::Scalar colours[] = {{200, 120, 40}, {40, 120, 220}, {60, 170, 60}};
  cv::line(chart, {left, top}, {left, top + plot_height}, black);
  cv::line(chart, {left, top + plot_height}, {width - 10, top + plot_height}, black);
  for (int tick = 0; tick <= 4; ++tick) {
    const double value = max_error * 1.1 * tick / 4.0;
    const int y = top + plot_height - static_cast<int>(value * scale);
    char label[32];
    std::snprintf(label, sizeof(label), "%.3f", value);
    cv::putText(chart, label, {5, y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, black);
    cv::line(chart, {left - 4, y}, {left, y}, black);
  }
  for (std::size_t v = 0; v < view_names.size(); ++v) {
    const int x0 = left + 8 + static_cast<int>(v) * group_width;
    for (std::size_t s = 0; s < series_errors_px.size(); ++s) {
      if (v >= series_errors_px[s].size()) continue;
      const int bar_height = static_cast<int>(series_errors_px[s][v] * scale);
      const int x = x0 + static_cast<int>(s) * 24;
      cv::rectangle(chart, {x, top + plot_height - bar_height}, {x + 20, top + plot_height}, colours[s % 3],
                    cv::FILLED);
    }
    cv::putText(chart, view_names[v].substr(0, 10), {x0, top + plot_height + 15 + 12 * static_cast<int>(v % 2)},
                cv::FONT_HERSHEY_SIMPLEX, 0.35, black);
  }
  cv::putText(chart, "reprojection error per view (px RMS)", {left, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.55, black);
  for (std::size_t s = 0; s < series_names.size(); ++s) {
    const int y = top + plot_height + 50 + 18 * static_cast<int>(s);
    cv::rectangle(chart, {left, y - 10}, {left + 14, y + 2}, colours[s % 3], cv::FILLED);
    cv::putText(chart, series_names[s], {left + 20, y}, cv::FONT_HERSHEY_SIMPLEX, 0.45, black);
  }
  return chart;
}

cv::Mat draw_residuals(const std::vector<std::string>& view_names,
                       const std::vector<std::vector<cv::Point2d>>& residuals_px, const std::string& title) {
  constexpr int kPanel = 170;
  constexpr int kColumns = 5;
  constexpr int kTop = 40;
  const int views = static_cast<int>(residuals_px.size());
  const int rows = std::max(1, (views + kColumns - 1) / kColumns);
  cv::Mat chart(kTop + rows * kPanel, kColumns * kPanel, CV_8UC3, cv::Scalar(255, 255, 255));
  double max_residual = 1e-6;
  for (const auto& view : residuals_px) {
    for (const auto& r : view) max_residual = std::max({max_residual, std::abs(r.x), std::abs(r.y)});
  }
  const double half = kPanel / 2.0 - 18.0;
  const double scale = half / (max_residual * 1.05);
  const cv::Scalar black(0, 0, 0);
  const cv::Scalar grey(190, 190, 190);
  char text[96];
  std::snprintf(text, sizeof(text), "%s residuals per view (px), panel half-width %.3f px", title.c_str(),
                max_residual * 1.05);
  cv::putText(chart, text, {8, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.5, black);
  for (int v = 0; v < views; ++v) {
    const cv::Point origin((v % kColumns) * kPanel, kTop + (v / kColumns) * kPanel);
    const cv::Point centre = origin + cv::Point(kPanel / 2, kPanel / 2 + 6);
    cv::rectangle(chart, origin + cv::Point(4, 4), origin + cv::Point(kPanel - 4, kPanel - 4), grey);
    cv::line(chart, centre - cv::Point(static_cast<int>(half), 0), centre + cv::Point(static_cast<int>(half), 0), grey);
    cv::line(chart, centre - cv::Point(0, static_cast<int>(half)), centre + cv::Point(0, static_cast<int>(half)), grey);
    double sum_sq = 0.0;
    for (const auto& r : residuals_px[v]) {
      sum_sq += r.dot(r);
      cv::circle(
          chart,
          centre + cv::Point(static_cast<int>(std::lround(r.x * scale)), static_cast<int>(std::lround(r.y * scale))), 2,
          cv::Scalar(200, 120, 40), cv::FILLED);
    }
    const double rms = residuals_px[v].empty() ? 0.0 : std::sqrt(sum_sq / static_cast<double>(residuals_px[v].size()));
    const std::string name = v < static_cast<int>(view_names.size()) ? view_names[v] : std::to_string(v);
    std::snprintf(text, sizeof(text), "%.12s %.3f", name.c_str(), rms);
    cv::putText(chart, text, origin + cv::Point(8, 18), cv::FONT_HERSHEY_SIMPLEX, 0.4, black);
  }
  return chart;
}

cv::Mat draw_coverage_map(const std::vector<std::vector<cv::Point2f>>& corners, const BoardSpec& board,
                          cv::Size image_size, const std::string& title) {
  const cv::Mat counts = board_coverage_counts(corners, board, image_size);
  double max_count = 1.0;
  cv::minMaxLoc(counts, nullptr, &max_count);
  cv::Mat levels;
  counts.convertTo(levels, CV_8U, 200.0 / std::max(max_count, 1.0), 55.0);
  levels.setTo(0, counts == 0);
  cv::Mat colour;
  cv::applyColorMap(levels, colour, cv::COLORMAP_VIRIDIS);
  colour.setTo(cv::Scalar(40, 40, 40), counts == 0);
  for (const auto& view : corners) {
    for (const auto& corner : view) cv::circle(colour, corner, 1, cv::Scalar(255, 255, 255), cv::FILLED);
  }
  char text[128];
  std::snprintf(text, sizeof(text), "%s: boards cover %.0f%% (up to %d per pixel)", title.c_str(),
                100.0 * covered_fraction(counts), static_cast<int>(max_count));
  cv::putText(colour, text, {10, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(255, 255, 255), 1);
  return colour;
}

}  // namespace rfrecon::calib
