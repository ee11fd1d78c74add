// From a compressed T and a calibrated rig to the rectified rows the depth solvers work on: the rectified geometry,
// triangulation of every correspondence, and the normalised primal and dual images resampled onto rectified rows.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "host/depth/rectified_rows.h"
#include "host/transport/transport_types.h"

namespace rfrecon::depth {

struct RectificationOptions {
  float epipolar_tolerance_px = 1.0f;  // a correspondence further than this from its rectified row is rejected
  float saturation = 0.97f;            // a pixel with a T entry at or above this (linear, 1 = full scale) is dropped
  float boundary_relative = 0.01f;     // a depth step this large (relative) to a 3x3 neighbour: an occlusion boundary
  float edge_relative = 0.3f;  // a direct-energy step this large (relative) to a 4-neighbour: an albedo or shadow edge
  // > 0: correspondences corrected for a camera-pixel footprint of this second moment (px^2) on albedo and shadow
  // edges before triangulation (host/depth/edge_bias.h; needs T's white frame); 0: as decoded.
  float edge_footprint_px2 = 0.0f;
};

// The rectification the depth stage works in: calib::rectify_rig, computed from the rig's intrinsics and projector pose
// (the rectification keys of rig.yaml are not read, so a file of any version gives the same rows). Rows are epipolar
// lines for any baseline direction; the focal length is the finer of the two devices', so neither image is sampled
// coarser than its pixels. With it, the per-pixel lookups that depend on the rig alone: computed once per
// calibration, they serve every scan made with it (docs/performance.md, "Rig geometry").
struct Rectification {
  RfRectifiedRig rig{};               // f, principal points (px), projector offset b (mm, > 0)
  cv::Size camera_size;               // rectified camera image
  int projector_width = 0;            // rectified projector image width (its rows are the camera's)
  cv::Mat rect_from_cam;              // 3x3 CV_64F rotation (rig.yaml R1)
  cv::Mat rect_from_proj;             // 3x3 CV_64F rotation (rig.yaml R2)
  cv::Mat rect_cam_image_from_rect;   // 3x4 CV_64F projection of the rectified camera (rig.yaml P1)
  cv::Mat rect_proj_image_from_rect;  // 3x4 CV_64F projection of the rectified projector (rig.yaml P2)
  cv::Mat rect_cam;   // CV_32FC2, camera size: rectified camera position (u, v) of each camera pixel centre
  cv::Mat proj_grid;  // CV_32FC2, projector size + 2: rectified projector position of each projector
                      // point (x - 1, y - 1), pixel centres and a pixel of margin around the image
  // Row lookups, for rectify_rows (the integration and the fusion; empty where not asked for):
  cv::Mat omega_cam;               // CV_32F, camera size: solid angle of each camera pixel (host/depth/solid_angle.h)
  cv::Mat omega_proj;              // CV_32F, projector size: the same for each projector pixel
  cv::Mat cam_map_x, cam_map_y;    // CV_32F, rectified camera size: camera pixel seen at each rectified pixel
  cv::Mat proj_map_x, proj_map_y;  // CV_32F, rectified projector size: the same for the projector
};

// Throws InputError naming `rig_name` and the key when the rig cannot be rectified into rows (degenerate baseline,
// devices facing away or at a grazing angle to each other). with_row_lookups = false leaves the row lookups empty
// (triangulation alone needs none).
Rectification depth_rectification(const calib::StereoRig& rig, const std::string& rig_name,
                                  bool with_row_lookups = true);

// Rectified projector positions of projector points (pixels, distorted): interpolated in rectification.proj_grid where
// they lie on it, within 2.5e-4 px of the exact undistortion on a strong lens (tests/depth/rectification_test.cc);
// undistorted exactly elsewhere. `rectification` is the rig's.
std::vector<cv::Point2f> rectify_projector_points(const std::vector<cv::Point2f>& points, const calib::StereoRig& rig,
                                                  const Rectification& rectification);

// Per original camera pixel: triangulation of its correspondence through the rectified rig.
struct CameraGridTriangulation {
  cv::Mat rect_cam;         // CV_32FC2: rectified camera position (u, v) of the pixel centre
  cv::Mat rect_proj_u;      // CV_32F: rectified projector column of the correspondence, NaN where none or rejected
  cv::Mat z_rect_mm;        // CV_32F: triangulated depth along the rectified optical axis, NaN where none
  cv::Mat epipolar_px;      // CV_32F: |v_proj - v| of the correspondence, NaN where none
  int correspondences = 0;  // pixels with a correspondence
  int off_epipolar = 0;     // of them, rejected by the epipolar tolerance (or behind the rig)
  int boundary_pixels = 0;  // of the others, rejected on both sides of occlusion boundaries
  int edge_pixels = 0;      // of the others, rejected on albedo, shadow and silhouette edges (biased centroids)
};

// Throws InputError when T's camera or projector size differs from the rig's. `rectification` is the rig's.
CameraGridTriangulation triangulate_camera_grid(const transport::CompressedTransport& transport,
                                                const calib::StereoRig& rig, const Rectification& rectification,
                                                const RectificationOptions& options);

// Throws std::invalid_argument when `rectification` has no row lookups. Rectified rows with e_cam, e_proj and z_tri
// filled (runs left empty: see host/depth/row_segmentation.h).
// primal = T 1 (camera pixels), dual = T^T 1 (projector pixels).
RectifiedRows rectify_rows(const transport::CompressedTransport& transport, const std::vector<float>& primal,
                           const std::vector<float>& dual, const Rectification& rectification,
                           const CameraGridTriangulation& triangulation, const RectificationOptions& options);

}  // namespace rfrecon::depth
