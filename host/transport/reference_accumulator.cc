// Plain C++ reference of the transport kernels (decode.cl, compress.cl), written as simple loops; the checks of
// dot frames both implementations share.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/capture/graycode_patterns.h"
#include "host/capture/manifest.h"
#include "host/capture/protocol.h"
#include "host/core/errors.h"
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

void check_dot_offsets(const TransportSetup& setup, int offset_x, int offset_y) {
  const int s = setup.dot_spacing;
  if (s <= 0 || offset_x < 0 || offset_x >= s || offset_y < 0 || offset_y >= s) {
    throw std::invalid_argument("transport: dot offsets (" + std::to_string(offset_x) + ", " +
                                std::to_string(offset_y) + ") outside [0, " + std::to_string(s) + ")");
  }
}

void check_kernel_dot_spacing(int dot_spacing) {
  const std::vector<int> supported RF_DOT_SPACINGS;
  if (dot_spacing == 0 || std::find(supported.begin(), supported.end(), dot_spacing) != supported.end()) return;
  std::string list;
  for (const int s : supported) list += (list.empty() ? "" : ", ") + std::to_string(s);
  throw ProcessingError("transport: the capture's dot spacing " + std::to_string(dot_spacing) +
                        " is not one the kernels were built for (RF_DOT_SPACINGS = {" + list +
                        "}; configure with -DRFRECON_DOT_SPACINGS, docs/fpga.md)");
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

// x = offset + s * floor((coordinate - offset + floor(s / 2)) / s): the lit dot nearest to `coordinate`.
int nearest_dot(int coordinate, int offset, int spacing) {
  const int shifted = coordinate - offset + spacing / 2;
  return offset + spacing * static_cast<int>(std::floor(static_cast<double>(shifted) / spacing));
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
    auto& code = axis == GrayAxis::kColumns ? t_.gray_x : t_.gray_y;
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
      t_.gray_x[c] = gray_to_binary(t_.gray_x[c]);
      t_.gray_y[c] = gray_to_binary(t_.gray_y[c]);
      if (w[c] - b[c] <= t_.setup.thresholds.black) t_.flags[c] |= kFlagShadow;
      if (t_.gray_x[c] >= static_cast<std::uint32_t>(t_.setup.projector_size.width) ||
          t_.gray_y[c] >= static_cast<std::uint32_t>(t_.setup.projector_size.height)) {
        t_.flags[c] |= kFlagOutOfRange;
      }
      if ((t_.flags[c] & (kFlagShadow | kFlagLowContrast | kFlagOutOfRange)) == 0) t_.flags[c] |= kFlagValid;
    }
  }

  void add_dot_frame(int offset_x, int offset_y, const cv::Mat& frame) override {
    check_dot_offsets(t_.setup, offset_x, offset_y);
    const cv::Mat linear = linear_frame(frame, t_.setup);
    const float* f = linear.ptr<float>();
    const float* b = black_.ptr<float>();
    const int s = t_.setup.dot_spacing;
    const cv::Size projector = t_.setup.projector_size;
    for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
      const float v = f[c] - b[c];
      if (!compressible(t_.flags[c]) || !(v > t_.setup.thresholds.noise)) continue;
      const int qx = nearest_dot(static_cast<int>(t_.gray_x[c]), offset_x, s);
      const int qy = nearest_dot(static_cast<int>(t_.gray_y[c]), offset_y, s);
      if (qx < 0 || qx >= projector.width || qy < 0 || qy >= projector.height) continue;
      t_.direct_energy[c] += v;
      insert(c, qy * projector.width + qx, v);
    }
  }

  CompressedTransport finish() override {
    const int k_max = t_.k();
    const int width = t_.setup.projector_size.width;
    const float* w = white_.ptr<float>();
    const float* b = black_.ptr<float>();
    for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
      const bool valid = (t_.flags[c] & kFlagValid) != 0;
      const std::size_t row = c * static_cast<std::size_t>(k_max);
      if (valid && t_.setup.dot_spacing == 0 && w[c] - b[c] > t_.setup.thresholds.noise) {
        t_.indices[row] = static_cast<std::int32_t>(t_.gray_y[c] * static_cast<std::uint32_t>(width) + t_.gray_x[c]);
        t_.weights[row] = w[c] - b[c];
        t_.direct_energy[c] = w[c] - b[c];
      }
      float sum = 0.0f;
      float sum_x = 0.0f;
      float sum_y = 0.0f;
      for (int k = 0; k < k_max; ++k) {
        const int q = t_.indices[row + k];
        if (q < 0) continue;
        const int y = q / width;
        sum += t_.weights[row + k];
        sum_x += t_.weights[row + k] * static_cast<float>(q - y * width);
        sum_y += t_.weights[row + k] * static_cast<float>(y);
      }
      if (sum > 0.0f) {
        t_.correspondence[2 * c] = sum_x / sum;
        t_.correspondence[2 * c + 1] = sum_y / sum;
      } else if (compressible(t_.flags[c])) {
        t_.flags[c] |= kFlagNoSignal;
      }
    }
    return std::move(t_);
  }

 private:
  // Keeps the row sorted by decreasing weight; a new entry goes after equal weights, the weakest falls out.
  void insert(std::size_t c, int q, float v) {
    const std::size_t row = c * static_cast<std::size_t>(t_.k());
    int slot = t_.k();
    while (slot > 0 && t_.weights[row + slot - 1] < v) --slot;
    if (slot == t_.k()) return;
    for (int k = t_.k() - 1; k > slot; --k) {
      t_.weights[row + k] = t_.weights[row + k - 1];
      t_.indices[row + k] = t_.indices[row + k - 1];
    }
    t_.weights[row + slot] = v;
    t_.indices[row + slot] = q;
  }

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
