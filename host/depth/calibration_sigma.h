// The part of each point's depth uncertainty that comes from the calibration: the rig's parameter covariance
// (calib::RigUncertainty) propagated to depth, as mrcal propagates it to projections. It is common to every scan made
// with the rig (a bias that does not average out over scans), unlike the observation's part (observation_sigma.h).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::depth {

// The rig's parameter covariance, G x G (calib::rig_parameter_count): its parameter_covariance, or for a rig written
// before it was kept a diagonal one from its standard deviations; empty for a rig without uncertainty (ground truth).
cv::Mat rig_parameter_covariance(const calib::StereoRig& rig);

// The principal directions of `covariance` (G x G), each scaled by its standard deviation: G-vectors whose outer
// products sum to the covariance (parameters of zero variance left out).
std::vector<std::vector<double>> principal_steps(const cv::Mat& covariance);

// One standard deviation (mm) of the depth of each point of `depth_mm` (CV_32F, the camera frame's z, NaN where none)
// that the calibration causes: the same correspondence (camera pixel, and the projector point the rig projects the
// point to) triangulated with the rig moved along each principal direction of `covariance` by one standard deviation,
// the depth taken, as the rectified rows take it, along the epipolar line. Computed exactly on a grid of 17 x 17 camera
// positions by 9 inverse depths spanning the map's and interpolated (the relative variance, trilinear in inverse
// depth) at each pixel. CV_32F
// of depth_mm's size, NaN where depth_mm is NaN. Throws std::invalid_argument when `covariance` is not G x G.
cv::Mat calibration_depth_sigma(const calib::StereoRig& rig, const cv::Mat& covariance, const cv::Mat& depth_mm);

}  // namespace rfrecon::depth
