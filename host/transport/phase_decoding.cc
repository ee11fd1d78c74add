// The phase family's plan, its C++ reference accumulator, its programs and the unwrapping.
#include "host/transport/phase_decoding.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "host/capture/pattern_family.h"
#include "host/capture/phase_patterns.h"
#include "host/transport/dot_rows.h"
#include "host/transport/graycode_accumulator.h"
#include "host/transport/phase_accumulators.h"

namespace rfrecon::transport {

namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

// The fraction of a turn in [0, 1) of v turns.
double fraction_of_turn(double v) { return v - std::floor(v); }

bool on_columns(const capture::Pattern& pattern) {
  return pattern.kind == capture::pattern_kind::kOrderColumn || pattern.kind == capture::pattern_kind::kPhaseColumn;
}

// Per camera pixel and axis: the order code's bits, the estimate unwrapped from the longer periods or the coarser
// heterodyne levels' phases, whether every coarser level was contrasted (an order bit's contrast is not asked:
// docs/method.md), and the phase sums of the period being added.
class PhaseAccumulator final : public TransportAccumulator {
 public:
  explicit PhaseAccumulator(const TransportSetup& setup)
      : t_(make_empty_transport(setup)),
        steps_(phase_parameter(setup, capture::kPhaseSteps)),
        order_unit_(order_unit(setup)),
        fringes_(heterodyne_fringes(setup)) {
    for (int axis = 0; axis < 2; ++axis) {
      periods_[axis] = axis_periods(setup, axis);
      order_[axis].assign(t_.camera_pixels(), 0);
      estimate_[axis].assign(t_.camera_pixels(), 0.0);
      turns_[axis].assign(2 * t_.camera_pixels(), 0.0);
      sin_sum_[axis].assign(t_.camera_pixels(), 0.0f);
      cos_sum_[axis].assign(t_.camera_pixels(), 0.0f);
      low_contrast_[axis].assign(t_.camera_pixels(), 0);
    }
  }

  void add(const TransportStep& step, const std::vector<cv::Mat>& frames, const cv::Mat& white,
           const cv::Mat& black) override {
    white_ = white;
    black_ = black;
    const int axis = step.args[0];
    if (step.op == kOrderPairStep) {
      const cv::Mat pattern = linear(frames.at(0));
      const cv::Mat inverse =
          linear(frames.size() > 1 ? frames[1] : order_inverse_frame(t_.setup, frames.at(0), white, black));
      const std::uint32_t mask = order_bit_mask(t_.setup, axis, step.args[1]);
      for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
        const float p = pattern.ptr<float>()[c], q = inverse.ptr<float>()[c];
        if (p > q) order_[axis][c] |= mask;
      }
    } else if (step.op == kPhaseShiftStep) {
      const cv::Mat frame = linear(frames.at(0));
      const auto [sin_delta, cos_delta] = phase_shift(t_.setup, step.args[1]);
      for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
        sin_sum_[axis][c] += frame.ptr<float>()[c] * sin_delta;
        cos_sum_[axis][c] += frame.ptr<float>()[c] * cos_delta;
      }
    } else if (step.op == kPhaseFoldStep) {
      fold(axis, step.args[1]);
    } else if (step.op == kPhaseDotStep) {
      if (!resolved_) resolve();
      const cv::Mat frame = linear(frames.at(0));
      add_dot_frame_to_rows(t_, step.args[0], step.args[1], frame.ptr<float>(), black_.ptr<float>());
    } else {
      throw std::invalid_argument("PhaseAccumulator::add: not a phase step");
    }
  }

  CompressedTransport finish() override {
    if (!resolved_) resolve();
    if (t_.setup.dot_spacing > 0) finish_rows(t_, false);
    return std::move(t_);
  }

 private:
  struct Phase {
    double theta;       // wrapped phase, rad
    double modulation;  // the sinusoid's amplitude B, linear units
  };

  // Every pixel's flags, projector pixel and correspondence from the phases; without the dot grid, T's single entry
  // of that projector pixel, white - black.
  void resolve() {
    resolved_ = true;
    const cv::Size projector = t_.setup.projector_size;
    for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
      const float lit = white_.ptr<float>()[c] - black_.ptr<float>()[c];
      if (!(lit > t_.setup.thresholds.black)) {
        t_.flags[c] = kFlagShadow;
        continue;
      }
      double u[2];
      bool contrasted = true;
      for (int axis = 0; axis < 2; ++axis) {
        const Phase phase = phase_at(axis, c);
        contrasted = contrasted && low_contrast_[axis][c] == 0 && phase.modulation > t_.setup.thresholds.white;
        const double period = periods_[axis].front();
        if (!fringes_.empty()) {
          const double turns[3] = {fraction_of_turn(phase.theta / kTwoPi), turns_[axis][2 * c],
                                   turns_[axis][2 * c + 1]};
          estimate_[axis][c] = heterodyne_estimate(turns, fringes_, axis == 0 ? projector.width : projector.height);
        }
        u[axis] = order_unit_ > 0 ? unwrap_phase(phase.theta, static_cast<int>(gray_to_binary(order_[axis][c])), period,
                                                 order_unit_)
                                  : unwrap_near(phase.theta, estimate_[axis][c], period);
      }
      const long qx = std::lround(u[0]), qy = std::lround(u[1]);
      if (qx < 0 || qx >= projector.width || qy < 0 || qy >= projector.height) {
        t_.flags[c] = kFlagOutOfRange;
        continue;
      }
      // A low-contrast pixel keeps its projector pixel: the dot grid's rows are filled there.
      t_.pixel_x[c] = static_cast<std::uint32_t>(qx);
      t_.pixel_y[c] = static_cast<std::uint32_t>(qy);
      if (!contrasted) {
        t_.flags[c] = kFlagLowContrast;
      } else {
        t_.flags[c] = kFlagValid;
        t_.correspondence[2 * c] = static_cast<float>(u[0]);
        t_.correspondence[2 * c + 1] = static_cast<float>(u[1]);
        if (t_.setup.dot_spacing > 0) continue;
        const std::size_t row = c * static_cast<std::size_t>(t_.k());
        t_.indices[row] = static_cast<std::int32_t>(qy * projector.width + qx);
        t_.weights[row] = lit;
        t_.direct_energy[c] = lit;
      }
    }
  }

  // S = (N/2) B sin(theta), C = (N/2) B cos(theta) of the axis's sums at pixel c.
  Phase phase_at(int axis, std::size_t c) const {
    const double sin_sum = sin_sum_[axis][c], cos_sum = cos_sum_[axis][c];
    return {std::atan2(sin_sum, cos_sum), 2.0 / steps_ * std::hypot(sin_sum, cos_sum)};
  }

  // The sums of period `level` unwrapped near the estimate of the next coarser one (the axis's middle for the
  // coarsest), or with beats kept as turns, then cleared for the next finer period.
  void fold(int axis, int level) {
    const int n = axis == 0 ? t_.setup.projector_size.width : t_.setup.projector_size.height;
    const bool coarsest = level + 1 == static_cast<int>(periods_[axis].size());
    for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
      const Phase phase = phase_at(axis, c);
      if (!(phase.modulation > t_.setup.thresholds.white)) low_contrast_[axis][c] = 1;
      if (!fringes_.empty()) {
        turns_[axis][2 * c + static_cast<std::size_t>(level - 1)] = fraction_of_turn(phase.theta / kTwoPi);
      } else {
        const double estimate = coarsest ? 0.5 * (n - 1) : estimate_[axis][c];
        estimate_[axis][c] = unwrap_near(phase.theta, estimate, periods_[axis].at(level));
      }
      sin_sum_[axis][c] = cos_sum_[axis][c] = 0.0f;
    }
  }

  cv::Mat linear(const cv::Mat& frame) const {
    return frame.depth() == CV_32F ? frame : capture::linearize_samples(frame, t_.setup.samples);
  }

  CompressedTransport t_;
  int steps_;
  int order_unit_;            // the order code's stripe width in half periods; 0 when longer periods or beats unwrap
  std::vector<int> fringes_;  // the heterodyne fringe counts, finest first; empty without beats
  std::vector<double> periods_[2];
  std::vector<std::uint32_t> order_[2];
  std::vector<double> estimate_[2];
  std::vector<double> turns_[2];  // with beats: levels 1 and 2's phases in turns, two per pixel
  std::vector<float> sin_sum_[2];
  std::vector<float> cos_sum_[2];
  std::vector<std::uint8_t> low_contrast_[2];
  cv::Mat white_;
  cv::Mat black_;
  bool resolved_ = false;
};

class PhaseDecoding final : public DecodingFamily {
 public:
  std::string name() const override { return "phase"; }

  // Per axis: its periods' steps from the coarsest, in manifest order within a period, each period but the finest
  // folded after its steps; then the order pairs; then the dot frames in manifest order.
  std::vector<TransportStep> plan(const capture::CaptureManifest& manifest) const override {
    std::map<std::tuple<int, int, bool>, std::size_t> orders;                               // (axis, bit, inverse)
    std::map<std::pair<int, int>, std::vector<TransportStep>, std::greater<>> phase_steps;  // (axis, level) inverted
    std::vector<TransportStep> dots;
    for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
      const auto& pattern = manifest.frames[i].pattern;
      const int axis = on_columns(pattern) ? 0 : 1;
      if (pattern.kind == capture::pattern_kind::kOrderColumn || pattern.kind == capture::pattern_kind::kOrderRow) {
        orders[{axis, pattern.bit, pattern.inverse}] = i;
      } else if (pattern.kind == capture::pattern_kind::kPhaseColumn ||
                 pattern.kind == capture::pattern_kind::kPhaseRow) {
        phase_steps[{1 - axis, pattern.level}].push_back({kPhaseShiftStep, {i}, {axis, pattern.bit}, "decode"});
      } else if (pattern.kind == capture::pattern_kind::kDot) {
        dots.push_back({kPhaseDotStep, {i}, {pattern.dot_offset_x, pattern.dot_offset_y}, "compress"});
      }
    }
    std::vector<TransportStep> steps;
    for (const auto& [key, level_steps] : phase_steps) {
      steps.insert(steps.end(), level_steps.begin(), level_steps.end());
      if (key.second > 0) steps.push_back({kPhaseFoldStep, {}, {1 - key.first, key.second}, "decode"});
    }
    for (const auto& [key, frame] : orders) {
      const auto [axis, bit, inverse] = key;
      if (inverse) continue;
      const auto pair = orders.find({axis, bit, true});
      steps.push_back(
          {kOrderPairStep,
           pair == orders.end() ? std::vector<std::size_t>{frame} : std::vector<std::size_t>{frame, pair->second},
           {axis, bit},
           "decode"});
    }
    steps.insert(steps.end(), dots.begin(), dots.end());
    steps.emplace_back();
    return steps;
  }

  std::vector<cl::ProgramRequest> programs(const TransportSetup& setup, KernelEntry entry) const override {
    return phase_programs(setup, entry);
  }

  std::unique_ptr<TransportAccumulator> make_reference(const TransportSetup& setup) const override {
    return make_phase_reference_accumulator(setup);
  }

  std::unique_ptr<TransportAccumulator> make_device(const TransportSetup& setup, cl::DeviceContext& device,
                                                    cl::ProgramCache& programs, KernelEntry entry,
                                                    CompressedTransport storage) const override {
    return make_phase_device_accumulator(setup, device, programs, entry, {}, std::move(storage));
  }

  std::unique_ptr<TransportRefinement> refinement(const TransportSetup&, const cv::Mat&,
                                                  const cv::Mat&) const override {
    return nullptr;
  }
};

}  // namespace

int phase_parameter(const TransportSetup& setup, const char* name) {
  capture::ProtocolOptions options;
  options.parameters = setup.parameters;
  return capture::family_parameter(capture::pattern_family("phase"), options, name);
}

std::pair<float, float> phase_shift(const TransportSetup& setup, int step) {
  const capture::PhaseConvention convention{phase_parameter(setup, capture::kPhaseOrigin),
                                            phase_parameter(setup, capture::kPhaseReversed) == 1};
  const double delta = capture::phase_shift_radians(step, phase_parameter(setup, capture::kPhaseSteps), convention);
  return {static_cast<float>(std::sin(delta)), static_cast<float>(std::cos(delta))};
}

int order_unit(const TransportSetup& setup) {
  const bool by_order =
      phase_parameter(setup, capture::kPhaseRatio) == 0 && phase_parameter(setup, capture::kPhaseHeterodyne) == 0;
  return by_order ? phase_parameter(setup, capture::kOrderUnit) : 0;
}

cv::Mat order_inverse_frame(const TransportSetup& setup, const cv::Mat& pattern, const cv::Mat& white,
                            const cv::Mat& black) {
  cv::Mat inverse;
  if (setup.frame_depth == CV_32F) {
    inverse = white + black - pattern;
  } else {
    // Raw samples s, linear (s - b) k: white + black - pattern in raw units is 2 b + (white + black) / k - pattern,
    // rounded (white and black came from whole raw samples, so only float rounding is undone).
    cv::Mat raw_sum = (white + black) / setup.samples.scale + 2.0 * setup.samples.black;
    cv::Mat pattern_float;
    pattern.convertTo(pattern_float, CV_32F);
    cv::Mat(raw_sum - pattern_float).convertTo(inverse, setup.frame_depth);
  }
  return inverse;
}

std::vector<int> heterodyne_fringes(const TransportSetup& setup) {
  return capture::phase_heterodyne_fringes(phase_parameter(setup, capture::kPhaseFringes),
                                           phase_parameter(setup, capture::kPhaseHeterodyne));
}

std::vector<double> axis_periods(const TransportSetup& setup, int axis) {
  capture::ProtocolOptions options;
  options.projector_size = setup.projector_size;
  options.family = "phase";
  options.parameters = setup.parameters;
  return capture::phase_periods(options, axis == 0);
}

std::uint32_t order_bit_mask(const TransportSetup& setup, int axis, int bit) {
  const int bits = capture::phase_order_bits(axis == 0 ? setup.projector_size.width : setup.projector_size.height,
                                             phase_parameter(setup, capture::kPhasePeriod), order_unit(setup));
  return 1u << (bits - 1 - bit);
}

std::unique_ptr<TransportAccumulator> make_phase_reference_accumulator(TransportSetup setup) {
  setup.thresholds = resolve_thresholds(setup.thresholds, 8);
  return std::make_unique<PhaseAccumulator>(setup);
}

std::vector<cl::ProgramRequest> phase_programs(const TransportSetup& setup, KernelEntry entry,
                                               const std::string& extra) {
  std::vector<cl::ProgramRequest> requests = transport_programs(setup, entry, extra);
  const cl::ProgramRequest compress = requests[1];
  requests[1] = {"transport/phase.cl", requests[0].options};
  if (setup.dot_spacing > 0) requests.push_back(compress);
  return requests;
}

double unwrap_near(double theta, double estimate, double period) {
  double wrapped = theta / kTwoPi * period;  // in (-P/2, P/2]
  if (wrapped < 0.0) wrapped += period;
  return std::round((estimate - wrapped) / period) * period + wrapped;
}

// Pixels x of stripe h span [h w, (h + 1) w), w = unit P / 2, so coordinates [h w - 0.5, (h + 1) w - 0.5).
double unwrap_phase(double theta, int order, double period, int unit) {
  const double width = 0.5 * unit * period;
  return unwrap_near(theta, order * width + 0.5 * width - 0.5, period);
}

double heterodyne_estimate(const double* turns, const std::vector<int>& fringes, double axis_pixels) {
  const double beat = fraction_of_turn(turns[0] - turns[1]);
  if (fringes.size() == 2) return beat * axis_pixels;
  const double beat_of_beats = fraction_of_turn(beat - fraction_of_turn(turns[1] - turns[2]));
  return unwrap_near(kTwoPi * beat, beat_of_beats * axis_pixels, axis_pixels / (fringes[0] - fringes[1]));
}

std::shared_ptr<const DecodingFamily> phase_decoding() { return std::make_shared<const PhaseDecoding>(); }

}  // namespace rfrecon::transport
