// Per-pixel loops over an image's rows (or tiles) on every core (cv::parallel_for_), for work where each row writes
// only its own pixels, so the result does not depend on how the rows are split.
#pragma once

#include <algorithm>
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

// Runs pixel(y, x) for every pixel of a rows x cols image, in tiles of kTile x kTile pixels, rows of tiles on every
// core. For loops that look their inputs up along a rotation of the image (a rectification): the pixels of a tile
// read a small patch of the rotated source, where a whole row would cross it, a page per pixel when it is turned by
// 90 degrees.
template <typename Pixel>
void for_each_pixel_in_tiles(int rows, int cols, const Pixel& pixel) {
  constexpr int kTile = 32;
  for_each_row((rows + kTile - 1) / kTile, [&](int tile_row) {
    const int y_begin = tile_row * kTile, y_end = std::min(rows, y_begin + kTile);
    for (int x_begin = 0; x_begin < cols; x_begin += kTile) {
      const int x_end = std::min(cols, x_begin + kTile);
      for (int y = y_begin; y < y_end; ++y) {
        for (int x = x_begin; x < x_end; ++x) pixel(y, x);
      }
    }
  });
}

// A new image of `type` with every element `value`, its rows filled on every core.
inline cv::Mat filled_on_every_core(cv::Size size, int type, const cv::Scalar& value) {
  cv::Mat image(size, type);
  for_each_row(size.height, [&](int y) { image.row(y).setTo(value); });
  return image;
}

// Runs count_row(y) for every y in [0, rows) and returns the sum of the counts they return.
template <typename CountRow>
int count_over_rows(int rows, const CountRow& count_row) {
  std::atomic<int> total{0};
  for_each_row(rows, [&](int y) { total += count_row(y); });
  return total;
}

}  // namespace rfrecon
