// Draws a preview's legend panel (title, colour bar or key image, ticks, notes) with OpenCV's Hershey font.
#include "host/outputs/legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace rfrecon::outputs {

namespace {
constexpr int kMargin = 8;
constexpr int kLine = 16;  // text line height, px
constexpr int kBarWidth = 24;
constexpr double kFontScale = 0.42;
constexpr double kPanelGrey = 48;
constexpr double kTextGrey = 235;

void text(cv::Mat& canvas, const std::string& line, cv::Point origin) {
  cv::putText(canvas, line, origin, cv::FONT_HERSHEY_SIMPLEX, kFontScale, cv::Scalar::all(kTextGrey), 1, cv::LINE_AA);
}

cv::Mat levels_top_down() {
  cv::Mat levels(256, 1, CV_8U);
  for (int row = 0; row < 256; ++row) levels.at<uchar>(row) = static_cast<uchar>(255 - row);
  return levels;
}
}  // namespace

cv::Mat colour_bar_key(int colormap) {
  cv::Mat key;
  cv::applyColorMap(levels_top_down(), key, colormap);
  return key;
}

cv::Mat grey_bar_key() {
  cv::Mat key;
  cv::cvtColor(levels_top_down(), key, cv::COLOR_GRAY2BGR);
  return key;
}

std::vector<std::pair<double, std::string>> bar_ticks(double low, double high, int decimals,
                                                      const std::string& top_prefix) {
  const auto label = [decimals](double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return std::string(buffer);
  };
  return {{0.0, top_prefix + label(high)}, {0.5, label(0.5 * (low + high))}, {1.0, label(low)}};
}

cv::Mat with_legend(const cv::Mat& preview, const Legend& legend) {
  if (preview.type() != CV_8UC3 || legend.key.type() != CV_8UC3 || legend.key.empty()) {
    throw std::invalid_argument("with_legend: preview and key must be CV_8UC3");
  }
  const int height = std::max(preview.rows, kLegendMinHeight);
  cv::Mat canvas(height, preview.cols + kLegendWidth, CV_8UC3, cv::Scalar::all(kPanelGrey));
  preview.copyTo(canvas(cv::Rect(0, 0, preview.cols, preview.rows)));
  const int left = preview.cols + kMargin;
  text(canvas, legend.title, {left, kMargin + kLine - 4});
  const int key_top = kMargin + kLine + 6;
  const int key_bottom = height - kMargin - kLine * static_cast<int>(legend.notes.size()) - 6;
  const int key_height = std::max(key_bottom - key_top, 8);
  cv::Rect key_box;
  if (legend.key.cols == legend.key.rows) {
    const int side = std::min(kLegendWidth - 2 * kMargin, key_height);
    key_box = cv::Rect(left, key_top, side, side);
  } else {
    key_box = cv::Rect(left, key_top + kLine / 2, kBarWidth, std::max(key_height - kLine, 8));
  }
  // Nearest key pixel, the ends onto the ends (the bar's first and last rows show the scale's two ends).
  const auto source = [](int i, int size, int source_size) {
    return size > 1 ? static_cast<int>(std::lround(i * (source_size - 1.0) / (size - 1.0))) : 0;
  };
  for (int y = 0; y < key_box.height; ++y) {
    for (int x = 0; x < key_box.width; ++x) {
      canvas.at<cv::Vec3b>(key_box.y + y, key_box.x + x) = legend.key.at<cv::Vec3b>(
          source(y, key_box.height, legend.key.rows), source(x, key_box.width, legend.key.cols));
    }
  }
  for (const auto& [position, label] : legend.ticks) {
    const int y = key_box.y + static_cast<int>(std::lround(position * (key_box.height - 1)));
    cv::line(canvas, {key_box.x + key_box.width, y}, {key_box.x + key_box.width + 4, y}, cv::Scalar::all(kTextGrey));
    text(canvas, label, {key_box.x + key_box.width + 8, y + 4});
  }
  int y = height - kMargin - kLine * static_cast<int>(legend.notes.size()) + kLine - 4;
  for (const auto& note : legend.notes) {
    text(canvas, note, {left, y});
    y += kLine;
  }
  return canvas;
}

}  // namespace rfrecon::outputs
