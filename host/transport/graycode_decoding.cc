// The graycode family's plan of accumulator calls, its accumulators and its host refinement.
#include "host/transport/graycode_decoding.h"

#include <map>
#include <optional>
#include <utility>

#include "host/capture/graycode_patterns.h"
#include "host/transport/gray_subpixel.h"
#include "host/transport/graycode_accumulator.h"

namespace rfrecon::transport {

void GraycodeAccumulator::add(const TransportStep& step, const std::vector<cv::Mat>& frames, const cv::Mat& white,
                              const cv::Mat& black) {
  switch (step.op) {
    case kGrayPairStep:
      add_gray_pair(static_cast<GrayAxis>(step.args[0]), step.args[1], frames.at(0), frames.at(1));
      break;
    case kFinishGrayStep:
      finish_gray(white, black);
      break;
    case kDotStep:
      add_dot_frame(step.args[0], step.args[1], frames.at(0));
      break;
    default:
      throw std::invalid_argument("GraycodeAccumulator::add: not a graycode step");
  }
}

namespace {

// Gray pairs (columns then rows, most significant bit first), finish_gray, dot frames in manifest order, finish: the
// order GraycodeAccumulator requires. capture::validate_manifest has checked that the sequence is complete.
std::vector<TransportStep> plan_graycode(const capture::CaptureManifest& manifest) {
  std::map<std::pair<GrayAxis, int>, std::pair<std::size_t, std::size_t>> pairs;  // -> (pattern, inverse)
  std::vector<TransportStep> dots;
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    const auto& pattern = manifest.frames[i].pattern;
    if (capture::is_gray(pattern)) {
      const GrayAxis axis = pattern.kind == capture::pattern_kind::kGrayColumn ? GrayAxis::kColumns : GrayAxis::kRows;
      auto& pair = pairs[{axis, pattern.bit}];
      (pattern.inverse ? pair.second : pair.first) = i;
    } else if (pattern.kind == capture::pattern_kind::kDot) {
      dots.push_back({kDotStep, {i}, {pattern.dot_offset_x, pattern.dot_offset_y}, "compress"});
    }
  }
  std::vector<TransportStep> steps;
  for (const auto& [key, frames] : pairs) {
    steps.push_back(
        {kGrayPairStep, {frames.first, frames.second}, {static_cast<int>(key.first), key.second}, "decode"});
  }
  steps.push_back({kFinishGrayStep, {}, {}, "decode"});
  steps.insert(steps.end(), dots.begin(), dots.end());
  steps.push_back({});
  return steps;
}

// Which pixels of Gray-code-only captures are decoded (GrayDecision) and their sub-pixel correspondences
// (GraySubpixel); captures with the dot grid keep their dot centroids.
class GraySubpixelRefinement final : public TransportRefinement {
 public:
  GraySubpixelRefinement(const TransportSetup& setup, const cv::Mat& white, const cv::Mat& black)
      : setup_(setup), decision_(white, black), gray_(setup.camera_size) {}

  void add(const TransportStep& step, const std::vector<cv::Mat>& frames) override {
    if (step.op != kGrayPairStep) return;
    const bool linear = setup_.frame_depth == CV_32F;
    const cv::Mat pattern = linear ? frames[0] : capture::linearize_samples(frames[0], setup_.samples);
    const cv::Mat inverse = linear ? frames[1] : capture::linearize_samples(frames[1], setup_.samples);
    const auto axis = static_cast<GrayAxis>(step.args[0]);
    decision_.add_gray_pair(axis, gray_bit_mask(setup_, axis, step.args[1]), pattern, inverse);
    gray_.add_gray_pair(axis, pattern, inverse);
  }

  std::optional<GrayDecisionCounts> refine(CompressedTransport& transport) override {
    const GrayDecisionCounts counts = decision_.decide(transport);
    gray_.refine(transport);
    return counts;
  }

 private:
  TransportSetup setup_;
  GrayDecision decision_;
  GraySubpixel gray_;
};

class GraycodeDecoding final : public DecodingFamily {
 public:
  std::string name() const override { return capture::kDefaultFamily; }

  std::vector<TransportStep> plan(const capture::CaptureManifest& manifest) const override {
    return plan_graycode(manifest);
  }

  std::vector<cl::ProgramRequest> programs(const TransportSetup& setup, KernelEntry entry) const override {
    return transport_programs(setup, entry);
  }

  std::unique_ptr<TransportAccumulator> make_reference(const TransportSetup& setup) const override {
    return make_reference_accumulator(setup);
  }

  std::unique_ptr<TransportAccumulator> make_device(const TransportSetup& setup, cl::DeviceContext& device,
                                                    cl::ProgramCache& programs, KernelEntry entry,
                                                    CompressedTransport storage) const override {
    return make_device_accumulator(setup, device, programs, entry, {}, std::move(storage));
  }

  std::unique_ptr<TransportRefinement> refinement(const TransportSetup& setup, const cv::Mat& white,
                                                  const cv::Mat& black) const override {
    if (setup.dot_spacing != 0) return nullptr;
    return std::make_unique<GraySubpixelRefinement>(setup, white, black);
  }
};

}  // namespace

std::shared_ptr<const DecodingFamily> graycode_decoding() { return std::make_shared<const GraycodeDecoding>(); }

}  // namespace rfrecon::transport
