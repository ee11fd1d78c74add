// Previews with their legend: a panel beside the camera-grid image naming the quantity, its units and its scale.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon::outputs {

struct Legend {
  std::string title;  // the quantity and its units, e.g. "depth z (mm)"
  // The key drawn under the title: a colour bar (one column, top row = the top of the scale) stretched to the
  // panel's height, or a square image (e.g. the normals' disc) scaled to the panel's width.
  cv::Mat key;                                        // CV_8UC3 BGR
  std::vector<std::pair<double, std::string>> ticks;  // position along the bar (0 top, 1 bottom) and its label
  std::vector<std::string> notes;                     // lines under the key, e.g. "black: no depth"
};

// Colour bar keys of 256 rows, level 255 at the top: an OpenCV colour map (cv::COLORMAP_TURBO), or grey.
cv::Mat colour_bar_key(int colormap);
cv::Mat grey_bar_key();

// Ticks at the bottom, middle and top of a bar from `low` to `high`, printed with `decimals`; `top_prefix` goes
// before the top label (">= " for a scale that saturates).
std::vector<std::pair<double, std::string>> bar_ticks(double low, double high, int decimals,
                                                      const std::string& top_prefix = "");

// `preview` (CV_8UC3) at the top left, its pixels unchanged, and the legend in a panel of kLegendWidth px to its
// right; the canvas is at least kLegendMinHeight px tall (below a shorter preview: the panel's grey).
inline constexpr int kLegendWidth = 180;
inline constexpr int kLegendMinHeight = 240;
cv::Mat with_legend(const cv::Mat& preview, const Legend& legend);

}  // namespace rfrecon::outputs
