// Each point's depth uncertainty, in its two parts: the calibration's (calibration_sigma.h), common to every scan made
// with the rig, and the observation's (observation_sigma.h), which averages out over repeated scans.
#pragma once

#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "host/outputs/reconstruction.h"

namespace rfrecon::depth {

// One part of the depth sigma: per camera pixel (CV_32F, mm of the camera frame's z, NaN where unknown; empty: unknown
// everywhere) and where it came from, in words (summary.json).
struct SigmaPart {
  cv::Mat sigma_mm;
  std::string source;
};

// A sigma along the rectified axis at the pixel's depth z_rect_mm, scaled to the camera frame's z depth_mm.
cv::Mat camera_z_sigma(const cv::Mat& rect_sigma_mm, const cv::Mat& z_rect_mm, const cv::Mat& depth_mm);

// Fills maps.depth_sigma_calibration_mm and _observation_mm from the parts (NaN where maps.depth_mm is), and
// maps.depth_sigma_mm, their root sum of squares where both are known. Adds "depth_sigma_mm" to `summary`: median and
// 95th percentile of each (mm) and where each part came from.
void add_depth_sigma(outputs::Reconstruction& maps, const SigmaPart& calibration, const SigmaPart& observation,
                     nlohmann::json& summary);

}  // namespace rfrecon::depth
