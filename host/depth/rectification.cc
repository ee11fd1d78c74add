// Rectified geometry, triangulation on the camera grid and resampling of the normalised images onto rectified rows.
#include "host/depth/rectification.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "calib/rectification.h"
#include "calib/undistort_points.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/parallel_rows.h"
#include "host/core/percentile.h"
#include "host/depth/bilinear.h"
#include "host/depth/edge_bias.h"
#include "host/depth/solid_angle.h"

namespace rfrecon::depth {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The value at point p of the device (pixel centres at integers) of `grid` (CV_32FC2 over the points (x - 1, y - 1)),
// bilinearly interpolated in double; false where p lies outside it (or is NaN). The grid holds a smooth map (lens
// undistortion and a rotation), which a pixel-spaced bilinear interpolation follows to about 1e-4 px.
bool interpolate_grid(const cv::Mat& grid, cv::Point2f p, cv::Point2f& out) {
  const double x = static_cast<double>(p.x) + 1.0, y = static_cast<double>(p.y) + 1.0;
  if (!(x >= 0.0 && y >= 0.0 && x < grid.cols - 1 && y < grid.rows - 1)) return false;
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double tx = x - x0, ty = y - y0;
  const cv::Vec2f* top = grid.ptr<cv::Vec2f>(y0) + x0;
  const cv::Vec2f* bottom = grid.ptr<cv::Vec2f>(y0 + 1) + x0;
  for (int axis = 0; axis < 2; ++axis) {
    const double upper = top[0][axis] + tx * (top[1][axis] - top[0][axis]);
    const double lower = bottom[0][axis] + tx * (bottom[1][axis] - bottom[0][axis]);
    (axis == 0 ? out.x : out.y) = static_cast<float>(upper + ty * (lower - upper));
  }
  return true;
}

// A pixel on an occlusion boundary sees both surfaces: its spot mixes theirs and it triangulates onto either, whatever
// its centre sees. Rejects every pixel with a neighbour within `radius` pixels whose depth differs by more than
// `relative` of its own (both sides of the boundary, `radius` pixels each). Gray-code-only captures use radius 2:
// there a mixed pixel of a silhouette may fail to decode, leaving a one-pixel gap between the two surfaces.
void reject_boundary_pixels(CameraGridTriangulation& result, float relative, int radius) {
  const cv::Mat z = result.z_rect_mm.clone();
  result.boundary_pixels = count_over_rows(z.rows, [&](int y) {
    int rejected = 0;
    for (int x = 0; x < z.cols; ++x) {
      const float centre = z.at<float>(y, x);
      if (std::isnan(centre)) continue;
      bool boundary = false;
      for (int yy = std::max(y - radius, 0); yy <= std::min(y + radius, z.rows - 1); ++yy) {
        for (int xx = std::max(x - radius, 0); xx <= std::min(x + radius, z.cols - 1); ++xx) {
          boundary = boundary || std::abs(z.at<float>(yy, xx) - centre) > relative * centre;  // false for NaN
        }
      }
      if (boundary) {
        result.z_rect_mm.at<float>(y, x) = kNaN;
        result.rect_proj_u.at<float>(y, x) = kNaN;
        ++rejected;
      }
    }
    return rejected;
  });
}

// A dot's centroid is the weighted mean of the projector pixels lighting the camera pixel's footprint; where the
// footprint straddles an albedo, shadow or silhouette edge, the brighter side weighs more and the centroid moves
// toward it (by up to half a projector pixel on the calibration board's squares). Such a pixel is recognised by its
// direct energy: a 4-neighbour's differs from its own by more than `relative` of it (a neighbour without a
// correspondence counts as 0). On uniform surfaces neighbours differ by a few percent. Gray-code-only captures,
// whose direct energy is white - black, are biased the same way: their crossings move toward the brighter side.
void reject_edge_pixels(CameraGridTriangulation& result, const transport::CompressedTransport& transport,
                        float relative) {
  const cv::Size size = transport.setup.camera_size;
  const auto energy = [&](int x, int y) {
    const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(size.width) + x;
    return std::isnan(transport.correspondence[2 * c]) ? 0.0f : transport.direct_energy[c];
  };
  constexpr int kNeighbours[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
  result.edge_pixels = count_over_rows(size.height, [&](int y) {
    int rejected = 0;
    for (int x = 0; x < size.width; ++x) {
      if (std::isnan(result.z_rect_mm.at<float>(y, x))) continue;
      const float centre = energy(x, y);
      bool edge = false;
      for (const auto& [dx, dy] : kNeighbours) {
        const int xx = x + dx, yy = y + dy;
        if (xx < 0 || yy < 0 || xx >= size.width || yy >= size.height) continue;
        edge = edge || !(std::abs(energy(xx, yy) - centre) <= relative * centre);  // true for NaN
      }
      if (edge) {
        result.z_rect_mm.at<float>(y, x) = kNaN;
        result.rect_proj_u.at<float>(y, x) = kNaN;
        ++rejected;
      }
    }
    return rejected;
  });
}

}  // namespace

Rectification depth_rectification(const calib::StereoRig& rig, const std::string& rig_name, bool with_row_lookups) {
  calib::RowRectification rows;
  try {
    rows = calib::rectify_rig(rig);
  } catch (const InputError& error) {
    throw InputError(rig_name + ": cannot rectify the rig into rows: " + error.what());
  }
  Rectification rectification;
  rectification.rig = {static_cast<float>(rows.f_px), static_cast<float>(rows.cx_cam_px),
                       static_cast<float>(rows.cx_proj_px), static_cast<float>(rows.cy_px),
                       static_cast<float>(rows.baseline_mm)};
  rectification.camera_size = rows.camera_size;
  rectification.projector_width = rows.projector_size.width;
  rectification.rect_from_cam = cv::Mat(rows.rect_from_cam).clone();
  rectification.rect_from_proj = cv::Mat(rows.rect_from_proj).clone();
  rectification.rect_cam_image_from_rect = rows.rect_cam_image_from_rect;
  rectification.rect_proj_image_from_rect = rows.rect_proj_image_from_rect;
  const cv::Size camera_size = rig.camera_size;
  std::vector<cv::Point2f> pixels;
  pixels.reserve(static_cast<std::size_t>(camera_size.area()));
  for (int y = 0; y < camera_size.height; ++y) {
    for (int x = 0; x < camera_size.width; ++x) pixels.emplace_back(static_cast<float>(x), static_cast<float>(y));
  }
  const std::vector<cv::Point2f> rect_cam =
      calib::undistort_points(pixels, rig.camera_matrix, rig.dist_coeffs, rectification.rect_from_cam,
                              rectification.rect_cam_image_from_rect, calib::undistort_criteria());
  rectification.rect_cam = cv::Mat(camera_size, CV_32FC2);
  std::copy(rect_cam.begin(), rect_cam.end(), rectification.rect_cam.begin<cv::Vec2f>());
  std::vector<cv::Point2f> projector_points;
  for (int y = -1; y <= rig.projector_size.height; ++y) {
    for (int x = -1; x <= rig.projector_size.width; ++x) {
      projector_points.emplace_back(static_cast<float>(x), static_cast<float>(y));
    }
  }
  const std::vector<cv::Point2f> proj_grid = calib::undistort_points(
      projector_points, rig.projector_matrix, rig.projector_dist_coeffs, rectification.rect_from_proj,
      rectification.rect_proj_image_from_rect, calib::undistort_criteria());
  rectification.proj_grid = cv::Mat(rig.projector_size + cv::Size(2, 2), CV_32FC2);
  std::copy(proj_grid.begin(), proj_grid.end(), rectification.proj_grid.begin<cv::Vec2f>());
  if (!with_row_lookups) return rectification;
  rectification.omega_cam = pixel_solid_angles(rig.camera_matrix, rig.dist_coeffs, camera_size);
  rectification.omega_proj = pixel_solid_angles(rig.projector_matrix, rig.projector_dist_coeffs, rig.projector_size);
  cv::initUndistortRectifyMap(rig.camera_matrix, rig.dist_coeffs, rectification.rect_from_cam,
                              rectification.rect_cam_image_from_rect, rectification.camera_size, CV_32FC1,
                              rectification.cam_map_x, rectification.cam_map_y);
  cv::initUndistortRectifyMap(rig.projector_matrix, rig.projector_dist_coeffs, rectification.rect_from_proj,
                              rectification.rect_proj_image_from_rect,
                              cv::Size(rectification.projector_width, rectification.camera_size.height), CV_32FC1,
                              rectification.proj_map_x, rectification.proj_map_y);
  return rectification;
}

std::vector<cv::Point2f> rectify_projector_points(const std::vector<cv::Point2f>& points, const calib::StereoRig& rig,
                                                  const Rectification& rectification) {
  std::vector<cv::Point2f> rectified(points.size());
  std::vector<std::uint8_t> on_grid(points.size());
  cv::parallel_for_(cv::Range(0, static_cast<int>(points.size())), [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) {
      const auto at = static_cast<std::size_t>(i);
      on_grid[at] = interpolate_grid(rectification.proj_grid, points[at], rectified[at]) ? 1 : 0;
    }
  });
  std::vector<std::size_t> off_grid;  // points outside the grid, undistorted one by one
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (on_grid[i] == 0) off_grid.push_back(i);
  }
  if (!off_grid.empty()) {
    std::vector<cv::Point2f> exact;
    exact.reserve(off_grid.size());
    for (const std::size_t i : off_grid) exact.push_back(points[i]);
    exact =
        calib::undistort_points(exact, rig.projector_matrix, rig.projector_dist_coeffs, rectification.rect_from_proj,
                                rectification.rect_proj_image_from_rect, calib::undistort_criteria());
    for (std::size_t j = 0; j < off_grid.size(); ++j) rectified[off_grid[j]] = exact[j];
  }
  return rectified;
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
  // The pixels with a correspondence, in pixel order, gathered on every core: counted per row, then each row's
  // written from its offset.
  std::vector<float> corrected;
  if (options.edge_footprint_px2 > 0.0f) {
    if (transport.white.empty()) {
      throw InputError(
          "T has no white frame (dataset 'white'), which the edge correction (--edge-footprint) needs: "
          "run rfrecon transport on the capture again");
    }
    corrected = correct_edge_bias(transport.correspondence, transport.white, camera_size, options.edge_footprint_px2);
  }
  const std::vector<float>& decoded = corrected.empty() ? transport.correspondence : corrected;
  const auto x_of = [](int c) { return 2 * static_cast<std::size_t>(c); };  // in decoded
  const auto has_correspondence = [&](int c) { return !std::isnan(decoded[x_of(c)]); };
  std::vector<int> row_start(static_cast<std::size_t>(camera_size.height) + 1, 0);
  for_each_row(camera_size.height, [&](int y) {
    int count = 0;
    for (int c = y * camera_size.width; c < (y + 1) * camera_size.width; ++c) count += has_correspondence(c) ? 1 : 0;
    row_start[static_cast<std::size_t>(y) + 1] = count;
  });
  std::partial_sum(row_start.begin(), row_start.end(), row_start.begin());
  std::vector<cv::Point2f> correspondences(static_cast<std::size_t>(row_start.back()));
  std::vector<int> with_correspondence(correspondences.size());
  for_each_row(camera_size.height, [&](int y) {
    auto at = static_cast<std::size_t>(row_start[static_cast<std::size_t>(y)]);
    for (int c = y * camera_size.width; c < (y + 1) * camera_size.width; ++c) {
      if (!has_correspondence(c)) continue;
      correspondences[at] = {decoded[x_of(c)], decoded[x_of(c) + 1]};
      with_correspondence[at++] = c;
    }
  });
  const std::vector<cv::Point2f> rect_proj = rectify_projector_points(correspondences, rig, rectification);
  result.rect_cam = rectification.rect_cam;
  result.rect_proj_u = filled_on_every_core(camera_size, CV_32F, cv::Scalar(kNaN));
  result.z_rect_mm = filled_on_every_core(camera_size, CV_32F, cv::Scalar(kNaN));
  result.epipolar_px = filled_on_every_core(camera_size, CV_32F, cv::Scalar(kNaN));
  result.correspondences = static_cast<int>(with_correspondence.size());
  std::atomic<int> off_epipolar{0};
  cv::parallel_for_(cv::Range(0, result.correspondences), [&](const cv::Range& range) {
    int off = 0;
    for (int i = range.start; i < range.end; ++i) {
      const int c = with_correspondence[static_cast<std::size_t>(i)];
      const int y = c / camera_size.width, x = c % camera_size.width;
      const cv::Vec2f cam = rectification.rect_cam.at<cv::Vec2f>(y, x);
      const cv::Point2f proj = rect_proj[static_cast<std::size_t>(i)];
      const float off_row = std::abs(proj.y - cam[1]);
      result.epipolar_px.at<float>(y, x) = off_row;
      const float disparity = (cam[0] - rectified.cx_cam) - (proj.x - rectified.cx_proj);
      const float z = rectified.f * rectified.b / disparity;
      if (off_row > options.epipolar_tolerance_px || !(z > 0.0f)) {
        ++off;
        continue;
      }
      result.rect_proj_u.at<float>(y, x) = proj.x;
      result.z_rect_mm.at<float>(y, x) = z;
    }
    off_epipolar += off;
  });
  result.off_epipolar = off_epipolar;
  reject_boundary_pixels(result, options.boundary_relative, transport.setup.dot_spacing == 0 ? 2 : 1);
  reject_edge_pixels(result, transport, options.edge_relative);
  return result;
}

RectifiedRows rectify_rows(const transport::CompressedTransport& transport, const std::vector<float>& primal,
                           const std::vector<float>& dual, const Rectification& rectification,
                           const CameraGridTriangulation& triangulation, const RectificationOptions& options) {
  const cv::Size camera_size = transport.setup.camera_size, projector_size = transport.setup.projector_size;
  if (primal.size() != transport.camera_pixels() || dual.size() != transport.projector_pixels()) {
    throw std::invalid_argument("rectify_rows: primal or dual image of the wrong size");
  }
  if (rectification.omega_cam.empty()) {
    throw std::invalid_argument("rectify_rows: the rectification was computed without its row lookups");
  }
  // Radiance-like images: primal and dual divided by their pixels' solid angles. Camera pixels that cannot carry the
  // ODE (no correspondence, saturated, dark) become NaN so that no interpolated value mixes them in.
  cv::Mat e_cam = filled_on_every_core(camera_size, CV_32F, cv::Scalar(kNaN)), e_proj;
  const int k = transport.k();
  for_each_row(camera_size.height, [&](int y) {
    for (int x = 0; x < camera_size.width; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(camera_size.width) + x;
      const float* weights = &transport.weights[c * static_cast<std::size_t>(k)];
      const bool saturated = *std::max_element(weights, weights + k) >= options.saturation;
      if (saturated || !(primal[c] > 0.0f) || std::isnan(triangulation.z_rect_mm.at<float>(y, x))) continue;
      e_cam.at<float>(y, x) = primal[c] / rectification.omega_cam.at<float>(y, x);
    }
  });
  cv::divide(cv::max(cv::Mat(projector_size, CV_32F, const_cast<float*>(dual.data())), 0.0f), rectification.omega_proj,
             e_proj);
  // A common factor cancels in the ODE: scale both so that the camera's median (rank n / 2 of n) is 1.
  const float median = finite_value_of_rank(e_cam, [](std::size_t usable) { return usable / 2; });
  if (!std::isnan(median)) {
    const float scale = 1.0f / median;
    e_cam *= scale;
    e_proj *= scale;
  }

  const RfRectifiedRig& rectified = rectification.rig;
  RectifiedRows rows;
  rows.rig = rectified;
  rows.width = rectification.camera_size.width;
  rows.height = rectification.camera_size.height;
  rows.proj_width = rectification.projector_width;
  rows.e_cam.assign(rows.pixels(), kNaN);
  rows.z_tri.assign(rows.pixels(), kNaN);
  rows.e_proj.assign(static_cast<std::size_t>(rows.height) * static_cast<std::size_t>(rows.proj_width), 0.0f);
  rows.runs.assign(rows.pixels(), 0);
  // Each sample written by its own pixel, in tiles on every core (the rectification turns the images).
  for_each_pixel_in_tiles(rows.height, rows.width, [&](int v, int u) {
    const std::size_t i = static_cast<std::size_t>(v) * static_cast<std::size_t>(rows.width) + u;
    const float x = rectification.cam_map_x.at<float>(v, u), y = rectification.cam_map_y.at<float>(v, u);
    const float u_proj = sample_bilinear(triangulation.rect_proj_u, x, y);
    const float e = sample_bilinear(e_cam, x, y);
    const float disparity = (static_cast<float>(u) - rectified.cx_cam) - (u_proj - rectified.cx_proj);
    const float z = rectified.f * rectified.b / disparity;
    if (z > 0.0f && e > 0.0f) {  // false for NaN
      rows.z_tri[i] = z;
      rows.e_cam[i] = e;
    }
  });
  for_each_pixel_in_tiles(rows.height, rows.proj_width, [&](int v, int u) {
    const float e_p =
        sample_bilinear(e_proj, rectification.proj_map_x.at<float>(v, u), rectification.proj_map_y.at<float>(v, u));
    if (e_p > 0.0f) rows.e_proj[static_cast<std::size_t>(v) * static_cast<std::size_t>(rows.proj_width) + u] = e_p;
  });
  return rows;
}

}  // namespace rfrecon::depth
