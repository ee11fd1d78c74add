// Selection by rank in two passes on every core: a histogram of the values' top 16 bits (in an order-preserving
// key) finds the bucket holding the rank, then nth_element runs over that bucket's values alone.
#include "host/core/percentile.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace rfrecon {

namespace {

// Ordered as the floats are: the sign bit set for positive values, every bit flipped for negative ones.
std::uint32_t order_key(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return (bits & 0x80000000U) != 0 ? ~bits : bits | 0x80000000U;
}

std::uint32_t bucket_of(float value) { return order_key(value) >> 16; }

// Runs visit(begin, end) over [0, total) in one stripe per thread, so that each keeps its partial result in one piece.
template <typename Visit>
void for_each_stripe(int total, const Visit& visit) {
  cv::parallel_for_(
      cv::Range(0, total), [&](const cv::Range& range) { visit(range.start, range.end); },
      static_cast<double>(std::max(1, cv::getNumThreads())));
}

}  // namespace

float finite_value_of_rank(const cv::Mat& image, const std::function<std::size_t(std::size_t)>& rank_of) {
  if (image.type() != CV_32FC1) throw std::invalid_argument("finite_value_of_rank: the image must be CV_32FC1");
  const cv::Mat continuous = image.isContinuous() ? image : image.clone();
  const float* values = continuous.ptr<float>();
  const int total = static_cast<int>(continuous.total());
  constexpr std::size_t kBuckets = std::size_t{1} << 16;
  std::mutex mutex;
  std::vector<std::size_t> counts(kBuckets, 0);
  for_each_stripe(total, [&](int begin, int end) {
    std::vector<std::size_t> stripe_counts(kBuckets, 0);
    for (int i = begin; i < end; ++i) {
      if (std::isfinite(values[i])) ++stripe_counts[bucket_of(values[i])];
    }
    const std::lock_guard<std::mutex> lock(mutex);
    for (std::size_t b = 0; b < kBuckets; ++b) counts[b] += stripe_counts[b];
  });
  std::size_t finite = 0;
  for (const std::size_t count : counts) finite += count;
  if (finite == 0) return std::numeric_limits<float>::quiet_NaN();
  const std::size_t rank = rank_of(finite);
  if (rank >= finite) throw std::invalid_argument("finite_value_of_rank: rank past the finite values");
  std::uint32_t bucket = 0;
  std::size_t below = 0;  // finite values in the buckets before `bucket`
  while (below + counts[bucket] <= rank) below += counts[bucket++];
  std::vector<float> in_bucket;
  in_bucket.reserve(counts[bucket]);
  for_each_stripe(total, [&](int begin, int end) {
    std::vector<float> stripe_values;
    for (int i = begin; i < end; ++i) {
      if (std::isfinite(values[i]) && bucket_of(values[i]) == bucket) stripe_values.push_back(values[i]);
    }
    const std::lock_guard<std::mutex> lock(mutex);
    in_bucket.insert(in_bucket.end(), stripe_values.begin(), stripe_values.end());
  });
  const auto at = in_bucket.begin() + static_cast<std::ptrdiff_t>(rank - below);
  std::nth_element(in_bucket.begin(), at, in_bucket.end());
  return *at;
}

float finite_percentile(const cv::Mat& image, double fraction) {
  return finite_value_of_rank(image, [fraction](std::size_t finite) {
    return static_cast<std::size_t>(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(finite - 1));
  });
}

double percentile_of(std::vector<double> values, double fraction) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto at = values.begin() +
                  static_cast<std::ptrdiff_t>(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

}  // namespace rfrecon
