// From a compressed T and a calibrated rig to the rectified rows the depth solvers work on: the rectified geometry,
// triangulation of every correspondence, and the normalised primal and dual images resampled onto rectified rows.
#pragma once

#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "host/depth/rectified_rows.h"
#include "host/transport/transport_types.h"

namespace rfrecon::depth {

struct RectificationOptions {
  float epipolar_tolerance_px = 1.0f;  // a correspondence further than this from its rectified row is rejected
  float saturation = 0.97f;            // a pixel with a T entry at or above this (linear, 1 = full scale) is dropped
  float boundary_relative = 0.01f;     // a depth step this large (relative) to a 3x3 neighbour: an occlusion boundary
};

// The rectification the depth stage works in: the rotations R1, R2 of rig.yaml (cv::stereoRectify), at the camera's
// own resolution (rectified focal length = the camera's f_x). rig.yaml's P1, P2 come from stereoRectify with alpha 1,
// which shrinks the focal length (to 58% on the built-in rig) and would sample the camera image coarser than its
// pixels. The rectified camera image just holds every camera pixel; the rectified projector image has the same rows
// and just holds every projector column.
struct Rectification {
  RfRectifiedRig rig{};     // f, principal points (px), projector offset b (mm)
  cv::Size camera_size;     // rectified camera image
  int projector_width = 0;  // rectified projector image width (its rows are the camera's)
  cv::Mat P1, P2;           // 3x4 CV_64F projection matrices of the rectified camera and projector
};

// Throws InputError naming `rig_name` when the rig cannot be rectified into rows: missing or degenerate R1, R2, P1,
// P2, a vertical baseline, rows that do not line up, or a rectified image of absurd size.
Rectification depth_rectification(const calib::StereoRig& rig, const std::string& rig_name);

// Per original camera pixel: triangulation of its correspondence through the rectified rig.
struct CameraGridTriangulation {
  cv::Mat rect_cam;         // CV_32FC2: rectified camera position (u, v) of the pixel centre
  cv::Mat rect_proj_u;      // CV_32F: rectified projector column of the correspondence, NaN where none or rejected
  cv::Mat z_rect_mm;        // CV_32F: triangulated depth along the rectified optical axis, NaN where none
  cv::Mat epipolar_px;      // CV_32F: |v_proj - v| of the correspondence, NaN where none
  int correspondences = 0;  // pixels with a correspondence
  int off_epipolar = 0;     // of them, rejected by the epipolar tolerance (or behind the rig)
  int boundary_pixels = 0;  // of the others, rejected on both sides of occlusion boundaries
};

// Throws InputError when T's camera or projector size differs from the rig's.
CameraGridTriangulation triangulate_camera_grid(const transport::CompressedTransport& transport,
                                                const calib::StereoRig& rig, const Rectification& rectification,
                                                const RectificationOptions& options);

// Rectified rows with e_cam, e_proj and z_tri filled (runs left empty: see host/depth/row_segmentation.h).
// primal = T 1 (camera pixels), dual = T^T 1 (projector pixels).
RectifiedRows rectify_rows(const transport::CompressedTransport& transport, const std::vector<float>& primal,
                           const std::vector<float>& dual, const calib::StereoRig& rig,
                           const Rectification& rectification, const CameraGridTriangulation& triangulation,
                           const RectificationOptions& options);

}  // namespace rfrecon::depth
