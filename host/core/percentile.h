// Robust image scales: a value of given rank among an image's finite values (a percentile, a median), selected on
// every core, for previews, detection images and the depth stage's normalisation.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon {

// The value of rank rank_of(n) (0-based, below n) among the n finite values of a single-channel CV_32F image: the
// value std::nth_element would put there. NaN when the image has no finite value.
float finite_value_of_rank(const cv::Mat& image, const std::function<std::size_t(std::size_t)>& rank_of);

// The value of rank floor(fraction (n - 1)) among the n finite values of a single-channel CV_32F image (nearest
// rank, no interpolation; fraction in [0, 1]). NaN when the image has no finite value.
float finite_percentile(const cv::Mat& image, double fraction);

// The value of rank floor(fraction (n - 1)) among the n `values` (nearest rank, no interpolation, so 0.5 gives the
// lower median of an even count; fraction in [0, 1]; the values finite): for a handful to a few thousand values, on
// one core. NaN when there is none.
double percentile_of(std::vector<double> values, double fraction);

}  // namespace rfrecon
