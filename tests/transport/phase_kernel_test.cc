// The phase family's kernels (kernels/transport/phase.cl, with decode.cl's Gray pairs for the order codes) against
// its C++ reference on the tiny plane capture, through both entries on every device, from linear and from raw 8-bit
// frames (same_phase_transport.h). The reference itself decodes most of the plane to within 0.3 projector pixel of the
// truth, so the comparison is not over empty transports. Tiny sizes: CI reruns these under oclgrind.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "host/capture/phase_patterns.h"
#include "host/cl/device_selection.h"
#include "host/transport/phase_accumulators.h"
#include "kernels/common/params.h"
#include "tests/transport/same_phase_transport.h"
#include "tests/transport/test_capture_feed.h"

namespace rfrecon::transport {
namespace {

constexpr KernelEntry kEntries[] = {KernelEntry::kNdRange, KernelEntry::kSingleWorkItem};

// Unwrapped by the order code: 5 steps of period 4 (one partial batch per axis), RF_FRAME_BATCH + 2 steps of period 6
// (a full and a partial one); by longer periods: ratio 2 (periods 4, 8, 16, 32 of the columns, 4, 8, 16, 28 of the
// rows) and ratio 4 (4, 16, 32 and 4, 16, 28); then a 5 x 5 dot grid (a full and a partial batch of RF_FRAME_BATCH);
// another tool's conventions: sinusoids of origin 270 degrees shifting the other way, an order code of whole periods
// without inverses (period 4 and 6), and ratio 2 ending at the first period that spans the axis (4, 8, 16); heterodyne
// beats of 3 and 2 fringes (periods 5.33 and 8 of the columns, 4 and 6 of the rows) and of 4, 2 and 1 fringes on a
// 24 x 16 projector (6, 12, 24 and 4, 8, 16).
constexpr testing::PhaseParameters kCases[] = {{5, 4},
                                               {RF_FRAME_BATCH + 2, 6},
                                               {4, 4, 2},
                                               {5, 4, 4},
                                               {4, 4, 0, 5},
                                               {3, 4, 0, 0, 270, 1, 2, 0},
                                               {4, 6, 0, 0, 90, 1, 2, 0},
                                               {4, 4, 2, 0, 0, 0, 1, 1, 1},
                                               {4, 4, 0, 0, 0, 0, 1, 1, 0, 3, 1},
                                               {5, 4, 0, 0, 0, 0, 1, 1, 0, 4, 2, 24, 16}};

class PhaseKernelTest : public ::testing::Test {
 protected:
  cl::ProgramCache programs_;
  std::vector<cl::DeviceContext> devices_ = cl::open_devices("");
};

TEST_F(PhaseKernelTest, StepsOrderPairsAndFinalizeMatchReference) {
  for (const auto phase : kCases) {
    SCOPED_TRACE("steps " + std::to_string(phase.steps) + " period " + std::to_string(phase.period) + " ratio " +
                 std::to_string(phase.ratio) + " dots " + std::to_string(phase.dot_spacing) + " origin " +
                 std::to_string(phase.origin_degrees) + " order unit " + std::to_string(phase.order_unit));
    const auto capture = testing::tiny_phase_capture(phase);
    const auto linear = testing::linearize(capture.frames);
    auto setup = testing::phase_setup_for(linear, phase, 3);
    const auto expected =
        testing::feed_plan(*make_phase_reference_accumulator(setup), "phase", capture.sequence, linear, linear);

    std::size_t valid = 0, close = 0;
    for (std::size_t c = 0; c < expected.camera_pixels(); ++c) {
      if ((expected.flags[c] & kFlagValid) == 0) continue;
      ++valid;
      const auto truth = capture.scene.correspondence.at<cv::Vec2f>(static_cast<int>(c));
      close +=
          std::hypot(expected.correspondence[2 * c] - truth[0], expected.correspondence[2 * c + 1] - truth[1]) < 0.3
              ? 1
              : 0;
    }
    ASSERT_GT(valid, expected.camera_pixels() / 2) << "the reference must decode most of the plane";
    EXPECT_GT(close, valid * 9 / 10) << "the reference's correspondences must lie near the truth";
    if (phase.ratio == 0 && phase.heterodyne == 0 && phase.order_unit == 1) {
      // A pixel whose order pair is too weak to decide lies at that stripe's edge: it is decoded, and as close.
      const float white = resolve_thresholds(setup.thresholds, 8).white;
      std::size_t undecided = 0, undecided_close = 0;
      for (std::size_t c = 0; c < expected.camera_pixels(); ++c) {
        bool weak = false;
        for (std::size_t f = 0; f + 1 < capture.sequence.size(); ++f) {
          const auto& pattern = capture.sequence[f];
          if ((pattern.kind != capture::pattern_kind::kOrderColumn &&
               pattern.kind != capture::pattern_kind::kOrderRow) ||
              pattern.inverse) {
            continue;
          }
          weak = weak || std::abs(linear[f].ptr<float>()[c] - linear[f + 1].ptr<float>()[c]) <= white;
        }
        if (!weak || (expected.flags[c] & kFlagValid) == 0) continue;
        ++undecided;
        const auto truth = capture.scene.correspondence.at<cv::Vec2f>(static_cast<int>(c));
        undecided_close +=
            std::hypot(expected.correspondence[2 * c] - truth[0], expected.correspondence[2 * c + 1] - truth[1]) < 0.3
                ? 1
                : 0;
      }
      EXPECT_GT(undecided, 0U) << "some decoded pixel must straddle an order stripe's edge";
      EXPECT_EQ(undecided_close, undecided) << "an order pair undecided at its edge must not move the correspondence";
    }
    if (phase.dot_spacing > 0) {
      // Each decoded pixel's strongest dot is the one nearest its correspondence: within half the spacing per axis.
      std::size_t near_dot = 0;
      for (std::size_t c = 0; c < expected.camera_pixels(); ++c) {
        const int q = expected.indices[c * static_cast<std::size_t>(expected.k())];
        if ((expected.flags[c] & kFlagValid) == 0 || q < 0) continue;
        const float dx = static_cast<float>(q % phase.projector_width) - expected.correspondence[2 * c];
        const float dy = static_cast<float>(q / phase.projector_width) - expected.correspondence[2 * c + 1];
        near_dot += std::abs(dx) <= 0.5f * phase.dot_spacing + 0.5f && std::abs(dy) <= 0.5f * phase.dot_spacing + 0.5f;
      }
      EXPECT_GT(near_dot, valid * 9 / 10) << "the dot frames must fill the rows at the phases' projector pixels";
    }

    setup.frame_depth = CV_8U;
    setup.samples = {0.0f, 1.0f / 255.0f};
    for (auto& device : devices_) {
      for (const auto entry : kEntries) {
        SCOPED_TRACE(cl::describe(device.info()) + (entry == KernelEntry::kNdRange ? " ndrange" : " single"));
        setup.frame_depth = CV_32F;
        auto accumulator = make_phase_device_accumulator(setup, device, programs_, entry);
        testing::expect_same_phase_transport(
            testing::feed_plan(*accumulator, "phase", capture.sequence, linear, linear), expected);
        setup.frame_depth = CV_8U;  // raw samples: linear in the NDRange kernels, on the host for the single ones
        auto raw = make_phase_device_accumulator(setup, device, programs_, entry);
        testing::expect_same_phase_transport(
            testing::feed_plan(*raw, "phase", capture.sequence, capture.frames, linear), expected);
      }
    }
  }
}

}  // namespace
}  // namespace rfrecon::transport
