// Brings depth from the rectified rows back to the camera's own pixel grid and frame: depth, 3D points and normals.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "host/depth/rectified_rows.h"
#include "host/outputs/reconstruction.h"

namespace rfrecon::depth {

// Depth along the rectified axis at each camera pixel, interpolated from `z_rect` (rows.height x rows.width) at the
// pixel's rectified position rect_cam (CV_32FC2). Inverse depth is interpolated, which is exact on planes; a pixel
// whose four rectified neighbours are not all finite, or differ by more than `jump_relative`, gets NaN.
cv::Mat sample_rectified_depth(const std::vector<float>& z_rect, const RectifiedRows& rows, const cv::Mat& rect_cam,
                               float jump_relative);

// Camera-frame maps from the rectified depth z_rect_mm at each camera pixel (CV_32F, NaN where none): X_rect =
// z (a, beta, 1) at the pixel's rectified position, X_cam = rect_from_cam^T X_rect. Normals come from central
// differences of neighbouring points (one-sided at the edge of a region), turned toward the camera. Confidence is left
// at 0.
outputs::Reconstruction camera_frame_maps(const cv::Mat& z_rect_mm, const cv::Mat& rect_cam, const RfRectifiedRig& rig,
                                          const cv::Mat& rect_from_cam);

}  // namespace rfrecon::depth
