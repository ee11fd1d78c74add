// Robust image scales: a percentile of an image's finite values, for previews and detection images.
#pragma once

#include <opencv2/core.hpp>

namespace rfrecon {

// The value of rank floor(fraction (n - 1)) among the n finite values of a single-channel CV_32F image (nearest
// rank, no interpolation; fraction in [0, 1]). NaN when the image has no finite value.
float finite_percentile(const cv::Mat& image, double fraction);

}  // namespace rfrecon
