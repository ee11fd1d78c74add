// Plain C++ reference of the graycode family's transport kernels (decode.cl, compress.cl), written as simple loops;
// its dot rows are host/transport/dot_rows.h's.
#include <cmath>
#include <stdexcept>
#include <string>

#include "host/capture/graycode_patterns.h"
#include "host/capture/manifest.h"
#include "host/capture/protocol.h"
#include "host/transport/dot_rows.h"
#include "host/transport/graycode_accumulator.h"

namespace rfrecon::transport {

std::uint32_t gray_bit_mask(const TransportSetup& setup, GrayAxis axis, int bit) {
  const int n = axis == GrayAxis::kColumns ? setup.projector_size.width : setup.projector_size.height;
  const int bits = capture::gray_bits(n);
  if (bit < 0 || bit >= bits) throw std::invalid_argument("Gray code bit out of range");
  return 1u << (bits - 1 - bit);
}

std::uint32_t gray_to_binary(std::uint32_t gray) {
  std::uint32_t binary = 0;
  for (; gray != 0; gray >>= 1) binary ^= gray;
  return binary;
}

namespace {

void check_frame(const cv::Mat& frame, int depth, const TransportSetup& setup) {
  if (frame.type() != CV_MAKETYPE(depth, 1) || frame.size() != setup.camera_size || !frame.isContinuous()) {
    throw std::invalid_argument("transport: frames must be continuous single-channel " +
                                cv::typeToString(CV_MAKETYPE(depth, 1)) + " of the camera size");
  }
}

// White or black: linear CV_32F.
const float* pixels(const cv::Mat& frame, const TransportSetup& setup) {
  check_frame(frame, CV_32F, setup);
  return frame.ptr<float>();
}

// A Gray or dot frame of setup.frame_depth, linear: as it is, or raw samples through setup.samples.
cv::Mat linear_frame(const cv::Mat& frame, const TransportSetup& setup) {
  check_frame(frame, setup.frame_depth, setup);
  return setup.frame_depth == CV_32F ? frame : capture::linearize_samples(frame, setup.samples);
}

class ReferenceAccumulator final : public GraycodeAccumulator {
 public:
  explicit ReferenceAccumulator(const TransportSetup& setup) : t_(make_empty_transport(setup)) {}

  void add_gray_pair(GrayAxis axis, int bit, const cv::Mat& pattern, const cv::Mat& inverse) override {
    const std::uint32_t mask = gray_bit_mask(t_.setup, axis, bit);
    const cv::Mat pattern_linear = linear_frame(pattern, t_.setup);
    const cv::Mat inverse_linear = linear_frame(inverse, t_.setup);
    const float* p = pattern_linear.ptr<float>();
    const float* inv = inverse_linear.ptr<float>();
    auto& code = axis == GrayAxis::kColumns ? t_.pixel_x : t_.pixel_y;
    for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
      if (p[c] > inv[c]) code[c] |= mask;
      if (std::fabs(p[c] - inv[c]) <= t_.setup.thresholds.white) t_.flags[c] |= kFlagLowContrast;
    }
  }

  void finish_gray(const cv::Mat& white, const cv::Mat& black) override {
    const float* w = pixels(white, t_.setup);
    const float* b = pixels(black, t_.setup);
    white_ = white.clone();
    black_ = black.clone();
    for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
      t_.pixel_x[c] = gray_to_binary(t_.pixel_x[c]);
      t_.pixel_y[c] = gray_to_binary(t_.pixel_y[c]);
      if (w[c] - b[c] <= t_.setup.thresholds.black) t_.flags[c] |= kFlagShadow;
      if (t_.pixel_x[c] >= static_cast<std::uint32_t>(t_.setup.projector_size.width) ||
          t_.pixel_y[c] >= static_cast<std::uint32_t>(t_.setup.projector_size.height)) {
        t_.flags[c] |= kFlagOutOfRange;
      }
      if ((t_.flags[c] & (kFlagShadow | kFlagLowContrast | kFlagOutOfRange)) == 0) t_.flags[c] |= kFlagValid;
    }
  }

  void add_dot_frame(int offset_x, int offset_y, const cv::Mat& frame) override {
    const cv::Mat linear = linear_frame(frame, t_.setup);
    add_dot_frame_to_rows(t_, offset_x, offset_y, linear.ptr<float>(), black_.ptr<float>());
  }

  // Gray code only: the single entry of the pixel's decoded projector pixel, white - black.
  CompressedTransport finish() override {
    const int width = t_.setup.projector_size.width;
    const float* w = white_.ptr<float>();
    const float* b = black_.ptr<float>();
    const bool gray_only = t_.setup.dot_spacing == 0;
    for (std::size_t c = 0; gray_only && c < t_.camera_pixels(); ++c) {
      if ((t_.flags[c] & kFlagValid) == 0 || !(w[c] - b[c] > t_.setup.thresholds.noise)) continue;
      const std::size_t row = c * static_cast<std::size_t>(t_.k());
      t_.indices[row] = static_cast<std::int32_t>(t_.pixel_y[c] * static_cast<std::uint32_t>(width) + t_.pixel_x[c]);
      t_.weights[row] = w[c] - b[c];
      t_.direct_energy[c] = w[c] - b[c];
    }
    finish_rows(t_, true);
    return std::move(t_);
  }

 private:
  CompressedTransport t_;
  cv::Mat white_;
  cv::Mat black_;
};

}  // namespace

std::unique_ptr<GraycodeAccumulator> make_reference_accumulator(TransportSetup setup) {
  setup.thresholds = resolve_thresholds(setup.thresholds, 8);
  return std::make_unique<ReferenceAccumulator>(setup);
}

}  // namespace rfrecon::transport
