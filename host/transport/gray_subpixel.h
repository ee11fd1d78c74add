// Sub-pixel projector coordinates of Gray-code-only captures: where each Gray bit flips between neighbouring camera
// pixels, and a local plane fitted through those boundary points around every pixel.
#pragma once

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "host/transport/graycode_accumulator.h"

namespace rfrecon::transport {

// Measured on the cube-anisotropic scene captured without dots (docs/formats.md): a Gaussian weight of 1 px in a
// 7 x 7 window follows the cube's creases, where wider, flat weights blur the slope change.
struct GraySubpixelOptions {
  int radius_px = 3;             // boundary points within this many camera px (x and y) of a pixel are fitted
  double weight_sigma_px = 1.0;  // with weight exp(-d^2 / (2 sigma^2)) at distance d camera px
  int min_points = 8;            // a fit needs at least this many boundary points
  double min_spread_px2 = 0.1;   // and their positions' weighted covariance eigenvalues at least this
  // Points farther than 1 + max_slope * d projector px from the pixel's position are dropped; at least 0 (the
  // window compares squares).
  double max_slope = 1.5;
  double max_residual_px = 0.5;  // the plane is fitted again without points farther than this from it
  double max_code_offset_px =
      1.0;  // and its value this close to the pixel's decoded position (host/transport/gray_decision.h)
};

// Fed every Gray pair's whole frames, keeps per camera pixel and axis code only the crossing fraction of the bit
// that flips towards its right and lower neighbours (O(camera pixels), whatever the number of frames). refine()
// then turns them into boundary points and fits value = a + b dx + c dy (weighted least squares) around each valid
// pixel, separately for the column and the row code, so any direction of the code's gradient on the camera works.
class GraySubpixel {
 public:
  explicit GraySubpixel(cv::Size camera_size, GraySubpixelOptions options = {});

  // One Gray pair (linear continuous CV_32FC1 frames of the camera size), pairs and axes in any order.
  void add_gray_pair(GrayAxis axis, const cv::Mat& pattern, const cv::Mat& inverse);

  // Moves each axis of the correspondence of kFlagValid pixels that have one (not NaN: their code, or a position
  // between two adjacent codes, host/transport/gray_decision.h) to the fitted coordinate where the fit is trusted.
  // Uses the final binary codes.
  void refine(CompressedTransport& transport) const;

 private:
  cv::Size camera_size_;
  GraySubpixelOptions options_;
  // [axis][0: right, 1: down] neighbour of camera pixel c: fraction t in [0, 1] of the way to it where
  // pattern - inverse crosses zero, for the last bit whose sign differs between them; NaN where none.
  std::array<std::array<std::vector<float>, 2>, 2> crossing_;
};

}  // namespace rfrecon::transport
