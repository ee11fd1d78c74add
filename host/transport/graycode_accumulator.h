// The graycode family's accumulators: Gray code pairs, then white/black, then dot frames, one at a time. Two
// implementations share this interface: the plain C++ reference and the OpenCL kernels on one device.
#pragma once

#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "host/cl/device_context.h"
#include "host/cl/program_cache.h"
#include "host/transport/accumulator.h"
#include "host/transport/dot_rows.h"
#include "host/transport/transport_types.h"

namespace rfrecon::transport {

enum class GrayAxis { kColumns, kRows };

// The graycode family's steps (TransportStep::op): a Gray pair (frames pattern and inverse; args axis, bit), the end of
// the Gray code (no frames), a dot frame (args: its offset).
enum GraycodeStep : int { kGrayPairStep, kFinishGrayStep, kDotStep };

// Frames are camera images of setup.camera_size: white and black linear CV_32F (host/capture/manifest.h load_frame),
// Gray and dot frames of setup.frame_depth (linear CV_32F, or raw samples that setup.samples makes linear).
// Call order: add_gray_pair for every pair (any order), finish_gray, add_dot_frame for every offset, finish; add()
// makes the same calls from the family's steps.
class GraycodeAccumulator : public TransportAccumulator {
 public:
  void add(const TransportStep& step, const std::vector<cv::Mat>& frames, const cv::Mat& white,
           const cv::Mat& black) final;
  // One Gray code pair; `bit` counts from the most significant (OpenCV order).
  virtual void add_gray_pair(GrayAxis axis, int bit, const cv::Mat& pattern, const cv::Mat& inverse) = 0;
  // Shadow mask from white/black, Gray -> binary, range check. Keeps black for the dot frames.
  virtual void finish_gray(const cv::Mat& white, const cv::Mat& black) = 0;
  // One dot-grid frame lighting projector pixels with x % s == offset_x and y % s == offset_y.
  virtual void add_dot_frame(int offset_x, int offset_y, const cv::Mat& frame) = 0;
  // finish(): correspondences (and the single entry of Gray-only captures), then the whole compressed T.
};

// The bit mask of Gray bit `bit` (0 = most significant) in an axis code word.
std::uint32_t gray_bit_mask(const TransportSetup& setup, GrayAxis axis, int bit);

// The binary number of a Gray code word.
std::uint32_t gray_to_binary(std::uint32_t gray);

// Automatic white and noise thresholds (<= 0) are resolved for an 8-bit camera here; compute_transport
// resolves them for the capture's bit depth before it makes an accumulator.
std::unique_ptr<GraycodeAccumulator> make_reference_accumulator(TransportSetup setup);

// Kernels of kernels/transport/decode.cl and compress.cl; the ELL state stays on the device until finish(). Dot
// frames are compressed RF_FRAME_BATCH at a time (the last batch at finish()), Gray pairs decoded RF_GRAY_PAIR_BATCH
// at a time (the last batch at finish_gray()). Raw frames are made linear in the NDRange kernels, on the host for the
// single work-item ones. build_options are added to the programs' (tests build the single work-item entries with an
// FPGA target macro on PoCL). `storage`: an earlier transport whose memory the state reuses (make_empty_decoding).
std::unique_ptr<GraycodeAccumulator> make_device_accumulator(TransportSetup setup, cl::DeviceContext& device,
                                                             cl::ProgramCache& programs, KernelEntry entry,
                                                             const std::string& build_options = {},
                                                             CompressedTransport storage = {});

}  // namespace rfrecon::transport
