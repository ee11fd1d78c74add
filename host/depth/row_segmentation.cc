// Run codes of the rectified rows from signal, triangulated depth and the ODE's slope at the triangulated depth.
#include "host/depth/row_segmentation.h"

#include <cmath>
#include <mutex>
#include <vector>

#include <opencv2/core.hpp>

#include "kernels/depth/row_runs.h"

namespace rfrecon::depth {

namespace {

constexpr double kDegreesPerRadian = 57.29577951308232;

// Row v's run codes (rows.runs all RF_RUN_MASKED before); adds its counts to stats. slope_angle: scratch of the
// row's width.
void segment_row(RectifiedRows& rows, int v, const SegmentationOptions& options, std::vector<float>& slope_angle,
                 SegmentationStats& stats) {
  const std::size_t row = static_cast<std::size_t>(v) * static_cast<std::size_t>(rows.width);
  const float* e_cam = rows.e_cam.data() + row;
  const float* z_tri = rows.z_tri.data() + row;
  const float* e_proj = rows.e_proj.data() + static_cast<std::size_t>(v) * static_cast<std::size_t>(rows.proj_width);
  bool previous_usable = false;
  for (int u = 0; u < rows.width; ++u) {
    const std::size_t i = row + static_cast<std::size_t>(u);
    if (!(e_cam[u] > 0.0f && z_tri[u] > 0.0f)) {
      previous_usable = false;
      continue;
    }
    int ok = 1;
    const float slope =
        rf_slope(rows.rig, rows.beta(v), static_cast<float>(u), z_tri[u], e_cam[u], e_proj, rows.proj_width, &ok);
    if (!ok) {
      ++stats.ode_breakdowns;
      previous_usable = false;
      continue;
    }
    ++stats.usable;
    // Angle of the surface within the epipolar plane: dz/du * f / z is the tangent of its tilt along the row.
    slope_angle[static_cast<std::size_t>(u)] =
        static_cast<float>(std::atan(slope * rows.rig.f / z_tri[u]) * kDegreesPerRadian);
    std::uint8_t code = RF_RUN_START;
    if (previous_usable) {
      const bool jump = std::abs(z_tri[u] - z_tri[u - 1]) > options.jump_relative * z_tri[u];
      const bool crease = std::abs(slope_angle[static_cast<std::size_t>(u)] -
                                   slope_angle[static_cast<std::size_t>(u) - 1]) > options.crease_deg;
      if (crease && !jump) {
        // One of the two pixels straddles the crease and mixes both faces: drop both.
        ++stats.creases;
        stats.usable -= 2;
        const std::uint8_t dropped = rows.runs[i - 1];
        rows.runs[i - 1] = RF_RUN_MASKED;
        stats.runs -= dropped == RF_RUN_START ? 1 : 0;
        previous_usable = false;
        continue;
      }
      stats.jumps += jump ? 1 : 0;
      if (!jump) code = RF_RUN_CONTINUE;
    }
    stats.runs += code == RF_RUN_START ? 1 : 0;
    rows.runs[i] = code;
    previous_usable = true;
  }
}

}  // namespace

SegmentationStats segment_rows(RectifiedRows& rows, const SegmentationOptions& options) {
  rows.runs.assign(rows.pixels(), RF_RUN_MASKED);
  SegmentationStats total;
  std::mutex total_lock;
  // Rows on every core: each writes only its own run codes; the counts are summed per block of rows.
  cv::parallel_for_(cv::Range(0, rows.height), [&](const cv::Range& range) {
    SegmentationStats stats;
    std::vector<float> slope_angle(static_cast<std::size_t>(rows.width));
    for (int v = range.start; v < range.end; ++v) segment_row(rows, v, options, slope_angle, stats);
    const std::lock_guard<std::mutex> guard(total_lock);
    total.usable += stats.usable;
    total.runs += stats.runs;
    total.jumps += stats.jumps;
    total.creases += stats.creases;
    total.ode_breakdowns += stats.ode_breakdowns;
  });
  return total;
}

}  // namespace rfrecon::depth
