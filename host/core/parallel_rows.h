// Per-pixel loops over an image's rows on every core (cv::parallel_for_), for work where each row writes only its
// own pixels, so the result does not depend on how the rows are split.
#pragma once

#include <atomic>

#include <opencv2/core.hpp>

namespace rfrecon {

// Runs row(y) for every y in [0, rows).
template <typename Row>
void for_each_row(int rows, const Row& row) {
  cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& range) {
    for (int y = range.start; y < range.end; ++y) row(y);
  });
}

// Runs count_row(y) for every y in [0, rows) and returns the sum of the counts they return.
template <typename CountRow>
int count_over_rows(int rows, const CountRow& count_row) {
  std::atomic<int> total{0};
  for_each_row(rows, [&](int y) { total += count_row(y); });
  return total;
}

}  // namespace rfrecon
