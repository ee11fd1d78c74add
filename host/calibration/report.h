// The visual calibration report: detected corners over camera and dual images, and a per-view error chart (PNG).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::calibration {

// An 8-bit colour rendering of `image` with the corners drawn (OpenCV's drawChessboardCorners), or with a red cross
// when `corners` is empty (board not found).
cv::Mat draw_corners(const cv::Mat& image, const calib::BoardSpec& board, const std::vector<cv::Point2f>& corners);

// A bar chart of per-view reprojection errors in pixels: one group per view, one bar per series (e.g. camera and
// projector), with a scale in pixels.
cv::Mat draw_error_chart(const std::vector<std::string>& view_names, const std::vector<std::string>& series_names,
                         const std::vector<std::vector<double>>& series_errors_px);

// Writes an image atomically (format from the extension); throws std::runtime_error naming the file on failure.
void write_image(const std::filesystem::path& file, const cv::Mat& image);

}  // namespace rfrecon::calibration
