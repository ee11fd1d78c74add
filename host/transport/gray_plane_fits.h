// The plane fits of GraySubpixel::refine over a band of camera rows, built once per instruction set and chosen at run
// time: plain data in, so that the code built for AVX2 shares no inline function with the rest of the program.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rfrecon::transport {
struct GraySubpixelOptions;
}

namespace rfrecon::transport::gray_fits {

// Arrays a fit reads in whole lanes stay inside theirs with this many elements past their last one (AVX-512's 16).
constexpr std::size_t kMaxLanes = 16;

// One axis code's boundary points, row by row (host/transport/gray_subpixel.cc builds them). Row v's points whose
// pair's first pixel is u or right of it start at first_at[v (width + 1) + u]; u = width: the row's end. Each point
// array holds kMaxLanes elements past its last point.
struct BoundaryRowsView {
  int width = 0;
  int height = 0;
  const std::uint32_t* first_at = nullptr;
  const std::int32_t* u = nullptr;    // the pair's first pixel (u, v)
  const float* x_fraction = nullptr;  // camera px right of u: the crossing's fraction t (right) or 0 (down)
  const float* y_fraction = nullptr;  // camera px below v: 0 (right) or t (down)
  const float* value = nullptr;       // projector px
};

// GraySubpixelOptions (host/transport/gray_subpixel.h) as the fits use them: fit_settings(options).
struct FitSettings {
  int radius_px = 0;
  float exponent_per_px2 = 0.0f;  // -1 / (2 weight_sigma_px^2)
  float max_slope2 = 0.0f;        // max_slope^2
  int min_points = 0;
  double min_spread_px2 = 0.0;
  float max_residual_px = 0.0f;
  double max_code_offset_px = 0.0;
};
FitSettings fit_settings(const GraySubpixelOptions& options);

// Camera rows [y_begin, y_end) of one axis: reads flags, moves the axis of the correspondence (two floats per pixel)
// of the valid pixels whose fit is trusted. `scratch`: kScratchFields fields of field_slots = window_slots(radius_px)
// floats each, used by one band at a time.
struct Band {
  const std::uint8_t* flags = nullptr;
  float* correspondence = nullptr;
  int axis = 0;
  int y_begin = 0;
  int y_end = 0;
  float* scratch = nullptr;
  std::size_t field_slots = 0;
};

constexpr std::size_t kScratchFields = 7;  // a window's fields: offsets, value, exponent, weight and two masks

// Slots for one window's candidates: two points per pixel pair of (2 radius + 2)^2 pixels, and a last whole lane.
constexpr std::size_t window_slots(int radius_px) {
  const std::size_t side = 2 * static_cast<std::size_t>(radius_px) + 2;
  return 2 * side * side + kMaxLanes;
}

// 128-bit lanes (SSE2 on x86-64, NEON on ARM): the build's baseline, on every CPU.
namespace baseline {
void fit_rows(const BoundaryRowsView& rows, const FitSettings& settings, const Band& band);
}
// 256-bit lanes with FMA (host/transport/gray_plane_fits_avx2.cc), built on x86-64.
namespace avx2 {
void fit_rows(const BoundaryRowsView& rows, const FitSettings& settings, const Band& band);
}

using FitRows = void (*)(const BoundaryRowsView& rows, const FitSettings& settings, const Band& band);
struct Build {
  const char* name;
  FitRows fit_rows;
};
// The builds this program has and this CPU runs (OpenCV's run-time check, which OPENCV_CPU_DISABLE=AVX2 overrides),
// fastest first.
std::vector<Build> builds_for_this_cpu();

}  // namespace rfrecon::transport::gray_fits
