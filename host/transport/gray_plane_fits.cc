// The plane fits in the build's baseline lanes (128 bits), for every CPU; their settings; the choice among builds.
#include "host/transport/gray_plane_fits.h"

#include <vector>

#include <opencv2/core/utility.hpp>

#include "host/transport/gray_subpixel.h"

#define RFRECON_SIMD_NAMESPACE baseline
#include "host/transport/gray_plane_fits.simd.h"
#undef RFRECON_SIMD_NAMESPACE

namespace rfrecon::transport::gray_fits {

FitSettings fit_settings(const GraySubpixelOptions& options) {
  FitSettings settings;
  settings.radius_px = options.radius_px;
  settings.exponent_per_px2 = static_cast<float>(-0.5 / (options.weight_sigma_px * options.weight_sigma_px));
  settings.max_slope2 = static_cast<float>(options.max_slope * options.max_slope);
  settings.min_points = options.min_points;
  settings.min_spread_px2 = options.min_spread_px2;
  settings.max_residual_px = static_cast<float>(options.max_residual_px);
  settings.max_code_offset_px = options.max_code_offset_px;
  return settings;
}

std::vector<Build> builds_for_this_cpu() {
  std::vector<Build> builds;
#ifdef RFRECON_GRAY_FITS_AVX2
  if (cv::checkHardwareSupport(CV_CPU_AVX2) && cv::checkHardwareSupport(CV_CPU_FMA3)) {
    builds.push_back({"AVX2", avx2::fit_rows});
  }
#endif
  builds.push_back({"baseline", baseline::fit_rows});
  return builds;
}

}  // namespace rfrecon::transport::gray_fits
