// Rectified geometry, triangulation on the camera grid and resampling of the normalised images onto rectified rows.
#include "host/depth/rectification.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/depth/bilinear.h"
#include "host/depth/solid_angle.h"

namespace rfrecon::depth {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Undistortion to tight tolerance: the default 5 iterations of cv::undistortPoints leave ~1e-3 px at the corners of
// a lens with k1 = -0.08, which is a visible depth error.
cv::TermCriteria undistort_criteria() { return {cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-12}; }

// A pixel on an occlusion boundary sees both surfaces: its spot mixes theirs and it triangulates onto either, whatever
// its centre sees. Rejects every pixel with a 3x3 neighbour whose depth differs by more than `relative` of its own
// (both sides of the boundary, one pixel each).
void reject_boundary_pixels(CameraGridTriangulation& result, float relative) {
  const cv::Mat z = result.z_rect_mm.clone();
  for (int y = 0; y < z.rows; ++y) {
    for (int x = 0; x < z.cols; ++x) {
      const float centre = z.at<float>(y, x);
      if (std::isnan(centre)) continue;
      bool boundary = false;
      for (int yy = std::max(y - 1, 0); yy <= std::min(y + 1, z.rows - 1); ++yy) {
        for (int xx = std::max(x - 1, 0); xx <= std::min(x + 1, z.cols - 1); ++xx) {
          boundary = boundary || std::abs(z.at<float>(yy, xx) - centre) > relative * centre;  // false for NaN
        }
      }
      if (boundary) {
        result.z_rect_mm.at<float>(y, x) = kNaN;
        result.rect_proj_u.at<float>(y, x) = kNaN;
        ++result.boundary_pixels;
      }
    }
  }
}

}  // namespace

Rectification depth_rectification(const calib::StereoRig& rig, const std::string& rig_name) {
  const auto fail = [&](const std::string& what) {
    throw InputError(rig_name + ": cannot rectify the rig into rows: " + what);
  };
  if (rig.P1.rows != 3 || rig.P1.cols != 4 || rig.P2.rows != 3 || rig.P2.cols != 4 || rig.R1.rows != 3 ||
      rig.R1.cols != 3 || rig.R2.rows != 3 || rig.R2.cols != 3) {
    fail("P1, P2 (3x4) and R1, R2 (3x3) are required");
  }
  const double f_file = rig.P1.at<double>(0, 0);
  if (!(f_file > 0.0) || std::abs(rig.P2.at<double>(0, 0) - f_file) > 1e-9 * f_file ||
      std::abs(rig.P1.at<double>(1, 1) - f_file) > 1e-9 * f_file) {
    fail("the rectified focal lengths of P1 and P2 differ or are not positive");
  }
  if (std::abs(rig.P2.at<double>(1, 3)) > 1e-9 * f_file ||
      std::abs(rig.P1.at<double>(1, 2) - rig.P2.at<double>(1, 2)) > 1e-6) {
    fail("the baseline is vertical or the rectified rows do not line up (P2[1][3] != 0 or cy differs)");
  }
  const double b = -rig.P2.at<double>(0, 3) / f_file;
  if (!(std::abs(b) > 1e-6)) fail("the baseline is zero");

  // Extent of a device's image border in rectified coordinates at focal length f and principal point 0.
  const double f = rig.camera_matrix.at<double>(0, 0);
  const cv::Matx33d unit_projection(f, 0, 0, 0, f, 0, 0, 0, 1);
  const auto extent = [&](const cv::Mat& K, const cv::Mat& dist, const cv::Mat& R, cv::Size size) {
    std::vector<cv::Point2f> border, rectified;
    for (int x = 0; x < size.width; ++x) {
      border.emplace_back(static_cast<float>(x), 0.0f);
      border.emplace_back(static_cast<float>(x), static_cast<float>(size.height - 1));
    }
    for (int y = 0; y < size.height; ++y) {
      border.emplace_back(0.0f, static_cast<float>(y));
      border.emplace_back(static_cast<float>(size.width - 1), static_cast<float>(y));
    }
    cv::undistortPoints(border, rectified, K, dist, R, unit_projection, undistort_criteria());
    return cv::boundingRect(rectified);
  };
  const cv::Rect camera_box = extent(rig.camera_matrix, rig.dist_coeffs, rig.R1, rig.camera_size);
  const cv::Rect projector_box = extent(rig.projector_matrix, rig.projector_dist_coeffs, rig.R2, rig.projector_size);
  constexpr int kMaxSide = 1 << 15;
  if (camera_box.width > kMaxSide || camera_box.height > kMaxSide || projector_box.width > kMaxSide) {
    fail("the rectified images would be larger than 32768 pixels (devices at a grazing angle to each other?)");
  }
  Rectification rectification;
  rectification.rig.f = static_cast<float>(f);
  rectification.rig.cx_cam = static_cast<float>(-camera_box.x);
  rectification.rig.cx_proj = static_cast<float>(-projector_box.x);
  rectification.rig.cy = static_cast<float>(-camera_box.y);
  rectification.rig.b = static_cast<float>(b);
  rectification.camera_size = cv::Size(camera_box.width + 1, camera_box.height + 1);
  rectification.projector_width = projector_box.width + 1;
  rectification.P1 = (cv::Mat_<double>(3, 4) << f, 0, -camera_box.x, 0, 0, f, -camera_box.y, 0, 0, 0, 1, 0);
  rectification.P2 = (cv::Mat_<double>(3, 4) << f, 0, -projector_box.x, -f * b, 0, f, -camera_box.y, 0, 0, 0, 1, 0);
  return rectification;
}

CameraGridTriangulation triangulate_camera_grid(const transport::CompressedTransport& transport,
                                                const calib::StereoRig& rig, const Rectification& rectification,
                                                const RectificationOptions& options) {
  const cv::Size camera_size = transport.setup.camera_size;
  if (camera_size != rig.camera_size || transport.setup.projector_size != rig.projector_size) {
    throw InputError("T (camera " + size_text(camera_size) + ", projector " +
                     size_text(transport.setup.projector_size) + ") and the calibration (camera " +
                     size_text(rig.camera_size) + ", projector " + size_text(rig.projector_size) +
                     ") are of different sizes");
  }
  const RfRectifiedRig& rectified = rectification.rig;
  CameraGridTriangulation result;
  std::vector<cv::Point2f> pixels, correspondences;
  std::vector<int> with_correspondence;
  pixels.reserve(transport.camera_pixels());
  for (int c = 0; c < camera_size.area(); ++c) {
    const int row = c / camera_size.width;  // integer division: the pixel's row
    pixels.emplace_back(static_cast<float>(c % camera_size.width), static_cast<float>(row));
    const float x_p = transport.correspondence[2 * static_cast<std::size_t>(c)];
    if (!std::isnan(x_p)) {
      correspondences.emplace_back(x_p, transport.correspondence[2 * static_cast<std::size_t>(c) + 1]);
      with_correspondence.push_back(c);
    }
  }
  std::vector<cv::Point2f> rect_cam, rect_proj;
  cv::undistortPoints(pixels, rect_cam, rig.camera_matrix, rig.dist_coeffs, rig.R1, rectification.P1,
                      undistort_criteria());
  if (!correspondences.empty()) {
    cv::undistortPoints(correspondences, rect_proj, rig.projector_matrix, rig.projector_dist_coeffs, rig.R2,
                        rectification.P2, undistort_criteria());
  }
  result.rect_cam = cv::Mat(camera_size, CV_32FC2);
  std::copy(rect_cam.begin(), rect_cam.end(), result.rect_cam.begin<cv::Vec2f>());
  result.rect_proj_u = cv::Mat(camera_size, CV_32F, cv::Scalar(kNaN));
  result.z_rect_mm = cv::Mat(camera_size, CV_32F, cv::Scalar(kNaN));
  result.epipolar_px = cv::Mat(camera_size, CV_32F, cv::Scalar(kNaN));
  result.correspondences = static_cast<int>(with_correspondence.size());
  for (std::size_t i = 0; i < with_correspondence.size(); ++i) {
    const int c = with_correspondence[i];
    const int y = c / camera_size.width, x = c % camera_size.width;
    const cv::Point2f cam = rect_cam[static_cast<std::size_t>(c)], proj = rect_proj[i];
    const float off_row = std::abs(proj.y - cam.y);
    result.epipolar_px.at<float>(y, x) = off_row;
    const float disparity = (cam.x - rectified.cx_cam) - (proj.x - rectified.cx_proj);
    const float z = rectified.f * rectified.b / disparity;
    if (off_row > options.epipolar_tolerance_px || !(z > 0.0f)) {
      ++result.off_epipolar;
      continue;
    }
    result.rect_proj_u.at<float>(y, x) = proj.x;
    result.z_rect_mm.at<float>(y, x) = z;
  }
  reject_boundary_pixels(result, options.boundary_relative);
  return result;
}

RectifiedRows rectify_rows(const transport::CompressedTransport& transport, const std::vector<float>& primal,
                           const std::vector<float>& dual, const calib::StereoRig& rig,
                           const Rectification& rectification, const CameraGridTriangulation& triangulation,
                           const RectificationOptions& options) {
  const cv::Size camera_size = transport.setup.camera_size, projector_size = transport.setup.projector_size;
  if (primal.size() != transport.camera_pixels() || dual.size() != transport.projector_pixels()) {
    throw std::invalid_argument("rectify_rows: primal or dual image of the wrong size");
  }
  // Radiance-like images: primal and dual divided by their pixels' solid angles. Camera pixels that cannot carry the
  // ODE (no correspondence, saturated, dark) become NaN so that no interpolated value mixes them in.
  const cv::Mat omega_cam = pixel_solid_angles(rig.camera_matrix, rig.dist_coeffs, camera_size);
  const cv::Mat omega_proj = pixel_solid_angles(rig.projector_matrix, rig.projector_dist_coeffs, projector_size);
  cv::Mat e_cam(camera_size, CV_32F, cv::Scalar(kNaN)), e_proj(projector_size, CV_32F);
  const int k = transport.k();
  std::vector<float> usable;
  for (int c = 0; c < camera_size.area(); ++c) {
    const int y = c / camera_size.width, x = c % camera_size.width;
    const float* weights = &transport.weights[static_cast<std::size_t>(c) * static_cast<std::size_t>(k)];
    const bool saturated = *std::max_element(weights, weights + k) >= options.saturation;
    if (saturated || !(primal[static_cast<std::size_t>(c)] > 0.0f) ||
        std::isnan(triangulation.z_rect_mm.at<float>(y, x))) {
      continue;
    }
    e_cam.at<float>(y, x) = primal[static_cast<std::size_t>(c)] / omega_cam.at<float>(y, x);
    usable.push_back(e_cam.at<float>(y, x));
  }
  for (int p = 0; p < projector_size.area(); ++p) {
    const int y = p / projector_size.width, x = p % projector_size.width;
    e_proj.at<float>(y, x) = std::max(dual[static_cast<std::size_t>(p)], 0.0f) / omega_proj.at<float>(y, x);
  }
  // A common factor cancels in the ODE: scale both so that the camera's median is 1.
  if (!usable.empty()) {
    std::nth_element(usable.begin(), usable.begin() + static_cast<std::ptrdiff_t>(usable.size() / 2), usable.end());
    const float scale = 1.0f / usable[usable.size() / 2];
    e_cam *= scale;
    e_proj *= scale;
  }

  const RfRectifiedRig& rectified = rectification.rig;
  RectifiedRows rows;
  rows.rig = rectified;
  rows.width = rectification.camera_size.width;
  rows.height = rectification.camera_size.height;
  rows.proj_width = rectification.projector_width;
  cv::Mat cam_map_x, cam_map_y, proj_map_x, proj_map_y;
  cv::initUndistortRectifyMap(rig.camera_matrix, rig.dist_coeffs, rig.R1, rectification.P1, rectification.camera_size,
                              CV_32FC1, cam_map_x, cam_map_y);
  cv::initUndistortRectifyMap(rig.projector_matrix, rig.projector_dist_coeffs, rig.R2, rectification.P2,
                              cv::Size(rows.proj_width, rows.height), CV_32FC1, proj_map_x, proj_map_y);
  rows.e_cam.assign(rows.pixels(), kNaN);
  rows.z_tri.assign(rows.pixels(), kNaN);
  rows.e_proj.assign(static_cast<std::size_t>(rows.height) * static_cast<std::size_t>(rows.proj_width), 0.0f);
  rows.runs.assign(rows.pixels(), 0);
  for (int v = 0; v < rows.height; ++v) {
    for (int u = 0; u < rows.width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * static_cast<std::size_t>(rows.width) + u;
      const float x = cam_map_x.at<float>(v, u), y = cam_map_y.at<float>(v, u);
      const float u_proj = sample_bilinear(triangulation.rect_proj_u, x, y);
      const float e = sample_bilinear(e_cam, x, y);
      const float disparity = (static_cast<float>(u) - rectified.cx_cam) - (u_proj - rectified.cx_proj);
      const float z = rectified.f * rectified.b / disparity;
      if (z > 0.0f && e > 0.0f) {  // false for NaN
        rows.z_tri[i] = z;
        rows.e_cam[i] = e;
      }
    }
    for (int u = 0; u < rows.proj_width; ++u) {
      const float e_p = sample_bilinear(e_proj, proj_map_x.at<float>(v, u), proj_map_y.at<float>(v, u));
      if (e_p > 0.0f) rows.e_proj[static_cast<std::size_t>(v) * static_cast<std::size_t>(rows.proj_width) + u] = e_p;
    }
  }
  return rows;
}

}  // namespace rfrecon::depth
