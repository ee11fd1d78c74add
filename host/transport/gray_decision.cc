// Per-pixel Gray bit margins, the noise of each pixel measured from its pattern + inverse sums, and the decision.
#include "host/transport/gray_decision.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

namespace rfrecon::transport {

namespace {

constexpr float kNoPosition = std::numeric_limits<float>::quiet_NaN();
constexpr float kNoMargin = std::numeric_limits<float>::infinity();

void check_frame(const cv::Mat& frame, cv::Size size) {
  if (frame.type() != CV_32FC1 || frame.size() != size || !frame.isContinuous()) {
    throw std::invalid_argument("gray decision: frames must be continuous CV_32FC1 of the camera size");
  }
}

// One axis of one pixel: its projector coordinate, or none.
enum class AxisOutcome { kDecided, kBetweenCodes, kUndecided, kOutOfRange };

struct AxisDecision {
  AxisOutcome outcome = AxisOutcome::kUndecided;
  float position = kNoPosition;  // projector px, pixel centres at integers
  std::uint32_t code = 0;        // the projector column or row T's entry goes to
};

// `code`: the accumulators' binary code (each bit decided by its sign); `extent`: the projector's size on the axis.
AxisDecision decide_axis(std::uint32_t code, std::uint32_t extent, float smallest, float smallest_signed,
                         std::uint32_t mask, float second, float threshold, float contrast) {
  const int undecided = (smallest <= threshold ? 1 : 0) + (second <= threshold ? 1 : 0);
  if (undecided == 0) {
    if (code >= extent) return {AxisOutcome::kOutOfRange};
    return {AxisOutcome::kDecided, static_cast<float>(code), code};
  }
  if (undecided > 1) return {AxisOutcome::kUndecided};
  // The code with the undecided bit the other way: adjacent only where the pixel lies on that bit's boundary.
  const std::uint32_t gray = code ^ (code >> 1);
  const std::uint32_t other = gray_to_binary(gray ^ mask);
  if (other != code + 1 && other + 1 != code) return {AxisOutcome::kUndecided};
  // A code past the projector's edge is never lit: a pixel between it and the last one lies on the last one.
  if (code >= extent && other >= extent) return {AxisOutcome::kOutOfRange};
  if (code >= extent || other >= extent) {
    const std::uint32_t inside = std::min(code, other);
    return {AxisOutcome::kDecided, static_cast<float>(inside), inside};
  }
  // The pattern lights the code whose Gray word has the bit set: the lit fraction of the pixel's footprint, from
  // pattern - inverse = (2 t - 1) (white - black), moves it from the other code (t = 0) to that one (t = 1).
  const bool code_lit = (gray & mask) != 0;
  const std::uint32_t lit = code_lit ? code : other;
  const std::uint32_t dark = code_lit ? other : code;
  const float t = contrast > 0.0f ? std::clamp(0.5f + 0.5f * smallest_signed / contrast, 0.0f, 1.0f) : 0.5f;
  const float position = static_cast<float>(dark) + t * (static_cast<float>(lit) - static_cast<float>(dark));
  return {AxisOutcome::kBetweenCodes, position, t >= 0.5f ? lit : dark};
}

}  // namespace

GrayDecision::GrayDecision(const cv::Mat& white, const cv::Mat& black, GrayDecisionOptions options)
    : white_(white), black_(black), options_(options) {
  check_frame(black, white.size());
  check_frame(white, black.size());
  const auto n = static_cast<std::size_t>(white.total());
  for (auto& axis : margins_) {
    axis.smallest.assign(n, kNoMargin);
    axis.smallest_signed.assign(n, 0.0f);
    axis.mask.assign(n, 0u);
    axis.second.assign(n, kNoMargin);
  }
  sum_ = cv::Mat::zeros(white.size(), CV_32F);
  sum_squares_ = cv::Mat::zeros(white.size(), CV_32F);
}

void GrayDecision::add_gray_pair(GrayAxis axis, std::uint32_t mask, const cv::Mat& pattern, const cv::Mat& inverse) {
  check_frame(pattern, white_.size());
  check_frame(inverse, white_.size());
  Margins& m = margins_[axis == GrayAxis::kColumns ? 0 : 1];
  const std::size_t width = static_cast<std::size_t>(white_.cols);
  const float* p = pattern.ptr<float>();
  const float* inv = inverse.ptr<float>();
  const float* w = white_.ptr<float>();
  const float* b = black_.ptr<float>();
  float* sum = sum_.ptr<float>();
  float* squares = sum_squares_.ptr<float>();
  // Selects rather than branches: which pair has the smallest margin is random, so a branch is mispredicted. Every
  // image is continuous, so a range of rows is one run of pixels: a lane's width at a time, then the rest one by one.
  const auto update = [&](std::size_t c) {
    const float residual = p[c] + inv[c] - w[c] - b[c];
    sum[c] += residual;
    squares[c] += residual * residual;
    const float difference = p[c] - inv[c];
    const float margin = std::fabs(difference);
    const float smallest = m.smallest[c];
    const bool new_smallest = margin < smallest;
    m.second[c] = new_smallest ? smallest : std::min(margin, m.second[c]);
    m.smallest[c] = new_smallest ? margin : smallest;
    m.smallest_signed[c] = new_smallest ? difference : m.smallest_signed[c];
    m.mask[c] = new_smallest ? mask : m.mask[c];
  };
  const cv::v_uint32x4 mask_lanes = cv::v_setall_u32(mask);
  // Rows in parallel: each pixel's state is its own.
  cv::parallel_for_(cv::Range(0, white_.rows), [&](const cv::Range& rows) {
    const std::size_t end = static_cast<std::size_t>(rows.end) * width;
    std::size_t c = static_cast<std::size_t>(rows.start) * width;
    for (; c + cv::v_float32x4::nlanes <= end; c += cv::v_float32x4::nlanes) {
      const cv::v_float32x4 pattern_lanes = cv::v_load(p + c), inverse_lanes = cv::v_load(inv + c);
      const cv::v_float32x4 residual = pattern_lanes + inverse_lanes - cv::v_load(w + c) - cv::v_load(b + c);
      cv::v_store(sum + c, cv::v_load(sum + c) + residual);
      cv::v_store(squares + c, cv::v_load(squares + c) + residual * residual);
      const cv::v_float32x4 difference = pattern_lanes - inverse_lanes;
      const cv::v_float32x4 margin = cv::v_abs(difference);
      const cv::v_float32x4 smallest = cv::v_load(m.smallest.data() + c);
      const cv::v_float32x4 new_smallest = margin < smallest;
      cv::v_store(m.second.data() + c,
                  cv::v_select(new_smallest, smallest, cv::v_min(margin, cv::v_load(m.second.data() + c))));
      cv::v_store(m.smallest.data() + c, cv::v_select(new_smallest, margin, smallest));
      cv::v_store(m.smallest_signed.data() + c,
                  cv::v_select(new_smallest, difference, cv::v_load(m.smallest_signed.data() + c)));
      cv::v_store(m.mask.data() + c,
                  cv::v_select(cv::v_reinterpret_as_u32(new_smallest), mask_lanes, cv::v_load(m.mask.data() + c)));
    }
    for (; c < end; ++c) update(c);
  });
  ++pairs_;
}

GrayDecisionCounts GrayDecision::decide(CompressedTransport& transport) const {
  if (transport.setup.camera_size != white_.size() || transport.setup.dot_spacing != 0) {
    throw std::invalid_argument("gray decision: a Gray-code-only transport of the frames' camera size");
  }
  // Noise of pattern - inverse per pixel: the variance of pattern + inverse over the pairs, averaged over a window.
  cv::Mat variance = cv::Mat::zeros(white_.size(), CV_32F);
  if (pairs_ > 1) {
    const double n = pairs_;
    cv::Mat mean_square;
    cv::multiply(sum_, sum_, mean_square, 1.0 / n);
    variance = (sum_squares_ - mean_square) / (n - 1.0);
    variance = cv::max(variance, 0.0);
    cv::blur(variance, variance, cv::Size(options_.noise_window_px, options_.noise_window_px), cv::Point(-1, -1),
             cv::BORDER_REFLECT);
  }
  const auto k = static_cast<std::size_t>(transport.k());
  const std::uint32_t extent[2] = {static_cast<std::uint32_t>(transport.setup.projector_size.width),
                                   static_cast<std::uint32_t>(transport.setup.projector_size.height)};
  const float floor = transport.setup.thresholds.white;
  const float noise_threshold = transport.setup.thresholds.noise;
  const int width = white_.cols;
  std::vector<GrayDecisionCounts> row_counts(static_cast<std::size_t>(white_.rows));
  // Rows in parallel: each pixel writes only its own flags, correspondence and row of T.
  cv::parallel_for_(cv::Range(0, white_.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const float* w = white_.ptr<float>(y);
      const float* b = black_.ptr<float>(y);
      const float* var = variance.ptr<float>(y);
      GrayDecisionCounts& counts = row_counts[static_cast<std::size_t>(y)];
      for (int x = 0; x < width; ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x;
        std::uint8_t& flags = transport.flags[c];
        flags &= static_cast<std::uint8_t>(~(kFlagValid | kFlagLowContrast | kFlagOutOfRange | kFlagNoSignal));
        transport.correspondence[2 * c] = kNoPosition;
        transport.correspondence[2 * c + 1] = kNoPosition;
        std::fill_n(transport.indices.begin() + static_cast<std::ptrdiff_t>(c * k), k, -1);
        std::fill_n(transport.weights.begin() + static_cast<std::ptrdiff_t>(c * k), k, 0.0f);
        transport.direct_energy[c] = 0.0f;
        if ((flags & kFlagShadow) != 0) continue;
        ++counts.lit;
        const float contrast = w[x] - b[x];
        const float threshold = std::max({static_cast<float>(options_.noise_sigmas) * std::sqrt(var[x]),
                                          static_cast<float>(options_.contrast_fraction) * contrast, floor});
        AxisDecision axes[2];
        for (int axis = 0; axis < 2; ++axis) {
          const Margins& m = margins_[static_cast<std::size_t>(axis)];
          const std::uint32_t code = axis == 0 ? transport.pixel_x[c] : transport.pixel_y[c];
          axes[axis] = decide_axis(code, extent[axis], m.smallest[c], m.smallest_signed[c], m.mask[c], m.second[c],
                                   threshold, contrast);
        }
        const auto either = [&](AxisOutcome outcome) {
          return axes[0].outcome == outcome || axes[1].outcome == outcome;
        };
        if (either(AxisOutcome::kUndecided)) {
          flags |= kFlagLowContrast | kFlagNoSignal;  // lit and undecided: no entry, as the accumulators flag it
          ++counts.undecided;
          continue;
        }
        if (either(AxisOutcome::kOutOfRange)) {
          flags |= kFlagOutOfRange;
          ++counts.out_of_range;
          continue;
        }
        flags |= kFlagValid;
        if (!(contrast > noise_threshold)) {
          flags |= kFlagNoSignal;
          ++counts.no_signal;
          continue;
        }
        (either(AxisOutcome::kBetweenCodes) ? counts.between_codes : counts.decided) += 1;
        transport.indices[c * k] = static_cast<std::int32_t>(axes[1].code * extent[0] + axes[0].code);
        transport.weights[c * k] = contrast;
        transport.direct_energy[c] = contrast;
        transport.correspondence[2 * c] = axes[0].position;
        transport.correspondence[2 * c + 1] = axes[1].position;
      }
    }
  });
  GrayDecisionCounts total;
  for (const auto& counts : row_counts) total += counts;
  return total;
}

}  // namespace rfrecon::transport
