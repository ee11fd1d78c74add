// Both parts of each point's depth sigma for a method without a closed form for them (integration, fusion), measured
// by rerunning the method: on noisy copies of T (the frames' part, a parametric bootstrap) and on the rig moved along
// each principal direction of its covariance (the calibration's part).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "host/depth/depth_method.h"

namespace rfrecon::depth {

// One standard deviation (mm, the camera frame's z like depth_mm) of each pixel's depth over `samples` copies of
// scan.transport, each entry w redrawn as w + N(0, v(w)) - b with the camera noise v and b ~ N(0, v(0)) the black
// frame's noise shared by the pixel's entries, the dot centroids recomputed, the correspondences triangulated with
// `rig` and `method` solved again. NaN where a copy has no depth. Empty where it cannot be measured: fewer than two
// samples, T without a camera noise, or correspondences that are not dot centroids. The copies draw from fixed seeds:
// the same scan gives the same sigma.
cv::Mat sampled_observation_sigma(const DepthMethod& method, const MethodScan& scan, const calib::StereoRig& rig,
                                  int samples);

// One standard deviation (mm, the camera frame's z) of each pixel's depth `depth_mm` that the calibration causes:
// `rig` moved by each of `steps` (principal_steps of its covariance: one standard deviation along each principal
// direction), rectified again, the correspondences triangulated and `method` solved again; the squares of the depth's
// changes summed (forward differences, as calibration_depth_sigma). Where a moved rig loses a pixel, `first_order` is
// kept there (calibration_depth_sigma's figure); NaN where depth_mm is NaN.
cv::Mat rerun_calibration_sigma(const DepthMethod& method, const MethodScan& scan, const calib::StereoRig& rig,
                                const std::vector<std::vector<double>>& steps, const cv::Mat& depth_mm,
                                const cv::Mat& first_order);

}  // namespace rfrecon::depth
