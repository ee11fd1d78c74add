// The visual calibration report: detected corners over camera and dual images, a per-view error chart, residual
// plots per view and coverage maps (PNG), and the rule that the report survives a failed calibration.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "host/core/atomic_file.h"
#include "host/core/errors.h"

namespace rfrecon::calib {

// An 8-bit colour rendering of `image` with the corners drawn (OpenCV's drawChessboardCorners), or with a red cross
// when `corners` is empty (board not found).
cv::Mat draw_corners(const cv::Mat& image, const calib::BoardSpec& board, const std::vector<cv::Point2f>& corners);

// A bar chart of per-view reprojection errors in pixels: one group per view, one bar per series (e.g. camera and
// projector), with a scale in pixels.
cv::Mat draw_error_chart(const std::vector<std::string>& view_names, const std::vector<std::string>& series_names,
                         const std::vector<std::vector<double>>& series_errors_px);

// The reprojection residuals (projected - detected, px) of each view as a scatter panel, all panels at one scale,
// with the view's name and RMS; `title` names the device.
cv::Mat draw_residuals(const std::vector<std::string>& view_names,
                       const std::vector<std::vector<cv::Point2d>>& residuals_px, const std::string& title);

// How many boards cover each pixel (calib/pose_diversity.h), as a colour map with every corner drawn and the covered
// fraction written on it: where the map is dark, no pose constrains the lens model.
cv::Mat draw_coverage_map(const std::vector<std::vector<cv::Point2f>>& corners, const BoardSpec& board,
                          cv::Size image_size, const std::string& title);

// Runs a calibration step; when it cannot process the views, the report (corner images) is still committed, so the
// user can see which boards were found, and the ProcessingError names it. No calibration file is written then.
template <typename Step>
auto keeping_report(StagingDirectory& report, Step&& step) {
  try {
    return step();
  } catch (const ProcessingError& error) {
    report.commit();
    throw ProcessingError(std::string(error.what()) + "; corner images in " + report.target().string());
  }
}

}  // namespace rfrecon::calib
