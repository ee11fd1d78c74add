// Which Gray-code-only pixels are decoded, from each pixel's own noise and contrast: a pixel with one undecided bit
// per axis lies between two adjacent codes and gets a position between them instead of none (docs/method.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "host/transport/graycode_accumulator.h"

namespace rfrecon::transport {

struct GrayDecisionOptions {
  // A bit is decided when |pattern - inverse| exceeds every one of: noise_sigmas times the pixel's measured noise of
  // that difference, contrast_fraction of its own white - black, and the setup's white threshold (an absolute floor).
  double noise_sigmas = 3.0;
  double contrast_fraction = 0.02;
  // The noise is measured per pixel from the spread of pattern + inverse over the pairs (it equals white + black for
  // a linear camera, so its spread is the noise of pattern - inverse), averaged over a window of this many pixels
  // square so that each estimate rests on a few hundred samples.
  int noise_window_px = 5;
};

// Why a lit pixel has no correspondence, or how it got one; counts of each over the camera image.
struct GrayDecisionCounts {
  std::size_t lit = 0;            // not kFlagShadow
  std::size_t decided = 0;        // an integer code: every bit decided, or the undecided one's flip past the edge
  std::size_t between_codes = 0;  // one undecided bit on some axis, between two adjacent codes
  std::size_t undecided = 0;      // two or more undecided bits on an axis, or one whose codes are not adjacent
  std::size_t out_of_range = 0;   // decoded outside the projector
  std::size_t no_signal = 0;      // decoded, but white - black at or below the noise threshold: no entry
  std::size_t decoded() const { return decided + between_codes; }
  GrayDecisionCounts& operator+=(const GrayDecisionCounts& other) {
    lit += other.lit;
    decided += other.decided;
    between_codes += other.between_codes;
    undecided += other.undecided;
    out_of_range += other.out_of_range;
    no_signal += other.no_signal;
    return *this;
  }
};

// Fed every Gray pair (linear CV_32FC1 frames of the camera size, in any order), keeps per pixel and axis the two
// smallest |pattern - inverse| and the signed difference and bit of the smallest, and the first two moments of
// pattern + inverse - white - black: O(camera pixels) whatever the number of pairs.
class GrayDecision {
 public:
  // `white` and `black`: the capture's linear CV_32FC1 frames of the camera size (cv::Mat headers share their data).
  GrayDecision(const cv::Mat& white, const cv::Mat& black, GrayDecisionOptions options = {});

  // `mask`: the pair's bit in its axis code word (gray_bit_mask).
  void add_gray_pair(GrayAxis axis, std::uint32_t mask, const cv::Mat& pattern, const cv::Mat& inverse);

  // Decides every lit pixel of a Gray-code-only transport anew from its codes (the accumulators' sign decisions):
  // sets kFlagValid, kFlagLowContrast, kFlagOutOfRange and kFlagNoSignal, the correspondence (an integer code, or
  // between two adjacent codes by the undecided bit's pattern - inverse relative to white - black; NaN where none) and
  // T's single entry per row with its direct energy. Returns the counts.
  GrayDecisionCounts decide(CompressedTransport& transport) const;

 private:
  struct Margins {
    std::vector<float> smallest;         // |pattern - inverse| of the weakest bit
    std::vector<float> smallest_signed;  // pattern - inverse of that bit
    std::vector<std::uint32_t> mask;     // that bit's mask
    std::vector<float> second;           // |pattern - inverse| of the second weakest bit
  };

  cv::Mat white_;
  cv::Mat black_;
  GrayDecisionOptions options_;
  std::array<Margins, 2> margins_;  // [0: columns, 1: rows]
  cv::Mat sum_;                     // CV_32F: sum over pairs of pattern + inverse - white - black
  cv::Mat sum_squares_;             // CV_32F: and of its square
  int pairs_ = 0;
};

}  // namespace rfrecon::transport
