// The files of a calibration report beside the corner images: the per-view error chart, residual plots and coverage
// maps per device (PNG), report.json (per-view errors, standard deviations, pose-set checks and warnings) and
// corners.json (the corners found in each view, docs/formats.md).
#pragma once

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "calib/camera_calibration.h"
#include "calib/stereo_calibration.h"

namespace rfrecon::calib {

nlohmann::json camera_report_json(const CameraCalibration& calibration);
nlohmann::json stereo_report_json(const StereoCalibration& calibration);
nlohmann::json corners_json(const std::vector<StereoView>& views);

// errors.png, residuals_camera.png, coverage_camera.png and report.json, into `dir`.
void write_camera_report(const std::filesystem::path& dir, const CameraCalibration& calibration,
                         const std::vector<BoardView>& views);

// errors.png, residuals_{camera,projector}.png, residual_field_{camera,projector}.png (over the backgrounds: 8-bit
// images of each device's size, e.g. the poses' images together; black where empty), coverage_{camera,projector}.png,
// report.json (with the gating decisions) and corners.json, into `dir`.
void write_stereo_report(const std::filesystem::path& dir, const StereoCalibration& calibration,
                         const std::vector<StereoView>& views, const cv::Mat& camera_background,
                         const cv::Mat& projector_background);

}  // namespace rfrecon::calib
