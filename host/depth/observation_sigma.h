// The part of each point's depth uncertainty that comes from the observation: the frames' noise (T's camera noise)
// propagated through the correspondence and the triangulation. It averages out over repeated scans, unlike the
// calibration's part (calibration_sigma.h).
#pragma once

#include <opencv2/core.hpp>

#include "host/depth/rectification.h"
#include "host/transport/transport_types.h"

namespace rfrecon::depth {

// One standard deviation (px) of each camera pixel's rectified projector column: the covariance of its dot centroid
// (each of T's entries a frame minus the black frame, both with the camera noise at their signal, the black frame's
// noise common to all entries) through the rectification's local Jacobian. CV_32F of the camera's size, NaN where the
// pixel has no correspondence. Empty where it is not known: T without a camera noise (written before it was
// measured), or a correspondence that is not the dot centroid (Gray code alone, phase).
cv::Mat rectified_column_sigma_px(const transport::CompressedTransport& transport, const Rectification& rectification);

// One standard deviation (mm, along the rectified axis) of the triangulated depth z_rect_mm = f b / disparity for a
// column noise column_sigma_px: z^2 sigma / (f b). CV_32F, NaN where either is.
cv::Mat triangulated_depth_sigma(const cv::Mat& z_rect_mm, const cv::Mat& column_sigma_px, const RfRectifiedRig& rig);

}  // namespace rfrecon::depth
