// Each point's depth uncertainty, in its two parts: the calibration's (calibration_sigma.h), common to every scan made
// with the rig, and the observation's (observation_sigma.h), which averages out over repeated scans.
#pragma once

#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "host/outputs/reconstruction.h"

namespace rfrecon::depth {

// Fills maps.depth_sigma_* from maps.depth_mm (the camera frame's z): the calibration's part from the rig's
// covariance (0 for a rig without uncertainty, a ground truth), the observation's from `observation_rect_sigma_mm`
// (the method's, along the rectified axis at the pixel's depth z_rect_mm; empty: not propagated by the method, NaN),
// scaled to the camera's z; the total where both are known. Adds "depth_sigma_mm" to `summary`: median and 95th
// percentile of each part (mm) and where each came from (the observation's: `observation_source`).
void add_depth_sigma(outputs::Reconstruction& maps, const cv::Mat& z_rect_mm, const cv::Mat& observation_rect_sigma_mm,
                     const std::string& observation_source, const calib::StereoRig& rig, nlohmann::json& summary);

}  // namespace rfrecon::depth
