// Nearest-rank percentile by nth_element over the finite values.
#include "host/core/percentile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace rfrecon {

float finite_percentile(const cv::Mat& image, double fraction) {
  if (image.type() != CV_32FC1) throw std::invalid_argument("finite_percentile: the image must be CV_32FC1");
  std::vector<float> values;
  values.reserve(image.total());
  for (auto it = image.begin<float>(); it != image.end<float>(); ++it) {
    if (std::isfinite(*it)) values.push_back(*it);
  }
  if (values.empty()) return std::numeric_limits<float>::quiet_NaN();
  const auto rank =
      static_cast<std::ptrdiff_t>(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[static_cast<std::size_t>(rank)];
}

}  // namespace rfrecon
