// Selection by rank on every core gives the value std::nth_element gives over the finite values, whatever the rank,
// the sign, the duplicates and the NaN and infinite values among them, on whole images and on views into them.
#include "host/core/percentile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace rfrecon {
namespace {

// The value of `rank` among the finite values of `image`, by sorting them.
float sorted_rank(const cv::Mat& image, std::size_t rank) {
  std::vector<float> finite;
  for (auto it = image.begin<float>(); it != image.end<float>(); ++it) {
    if (std::isfinite(*it)) finite.push_back(*it);
  }
  std::sort(finite.begin(), finite.end());
  return finite.at(rank);
}

cv::Mat mixed_image(int rows, int cols, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<float> normal(1.0f, 0.3f);
  std::uniform_int_distribution<int> kind(0, 19);
  cv::Mat image(rows, cols, CV_32F);
  for (auto it = image.begin<float>(); it != image.end<float>(); ++it) {
    switch (kind(random)) {
      case 0:
        *it = std::numeric_limits<float>::quiet_NaN();
        break;
      case 1:
        *it = std::numeric_limits<float>::infinity();
        break;
      case 2:
        *it = -std::numeric_limits<float>::infinity();
        break;
      case 3:
        *it = -normal(random);
        break;
      case 4:
        *it = 1.0f;
        break;  // duplicates
      default:
        *it = normal(random);
    }
  }
  return image;
}

TEST(PercentileTest, RankSelectionEqualsSortingTheFiniteValues) {
  for (const unsigned seed : {1U, 2U, 3U}) {
    const cv::Mat image = mixed_image(517, 389, seed);
    std::size_t finite = 0;
    for (auto it = image.begin<float>(); it != image.end<float>(); ++it) finite += std::isfinite(*it) ? 1 : 0;
    for (const std::size_t rank : {std::size_t{0}, finite / 4, finite / 2, finite - 1}) {
      EXPECT_EQ(finite_value_of_rank(image, [&](std::size_t n) { return n == finite ? rank : n; }),
                sorted_rank(image, rank))
          << "seed " << seed << " rank " << rank;
    }
    const cv::Mat view = image(cv::Rect(13, 7, 301, 250));  // not continuous
    std::size_t view_finite = 0;
    for (auto it = view.begin<float>(); it != view.end<float>(); ++it) view_finite += std::isfinite(*it) ? 1 : 0;
    EXPECT_EQ(finite_percentile(view, 0.5),
              sorted_rank(view, static_cast<std::size_t>(0.5 * static_cast<double>(view_finite - 1))));
    EXPECT_EQ(finite_percentile(view, 1.0), sorted_rank(view, view_finite - 1));
  }
}

TEST(PercentileTest, ImagesWithoutFiniteValuesGiveNaNAndOtherTypesAreRefused) {
  const cv::Mat none(4, 5, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_TRUE(std::isnan(finite_percentile(none, 0.5)));
  EXPECT_EQ(finite_percentile(cv::Mat(1, 1, CV_32F, cv::Scalar(-2.5f)), 0.9), -2.5f);
  EXPECT_THROW(finite_percentile(cv::Mat(3, 3, CV_8U), 0.5), std::invalid_argument);
  EXPECT_THROW(finite_value_of_rank(cv::Mat(2, 2, CV_32F, cv::Scalar(1.0f)), [](std::size_t n) { return n; }),
               std::invalid_argument);
}

}  // namespace
}  // namespace rfrecon
