// The frames' part of each point's depth sigma for a method without a closed form for it (integration, fusion): a
// parametric bootstrap that redraws T's entries with the camera noise and reruns the method on each copy.
#pragma once

#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "host/depth/depth_method.h"

namespace rfrecon::depth {

// One standard deviation (mm, along the rectified axis like solve's depth) of each pixel's depth over `samples` copies
// of scan.transport, each entry w redrawn as w + N(0, v(w)) - b with the camera noise v and b ~ N(0, v(0)) the black
// frame's noise shared by the pixel's entries, the dot centroids recomputed, the correspondences triangulated with
// `rig` and `method` solved again. NaN where a copy has no depth. Empty where it cannot be measured: fewer than two
// samples, T without a camera noise, or correspondences that are not dot centroids. The copies draw from fixed seeds:
// the same scan gives the same sigma.
cv::Mat sampled_observation_sigma(const DepthMethod& method, const MethodScan& scan, const calib::StereoRig& rig,
                                  int samples);

}  // namespace rfrecon::depth
