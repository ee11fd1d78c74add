// Streams a capture's frames into a compressed T, one step at a time, as the capture's decoding family plans them
// (host/transport/decoding_family.h). Implementations: each family's plain C++ reference and its OpenCL kernels.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "host/transport/transport_types.h"

namespace rfrecon::transport {

// The op of the step that ends a capture: finish() returns T.
inline constexpr int kFinishStep = -1;

// One call on an accumulator: the frames it takes and what the family does with them.
struct TransportStep {
  int op = kFinishStep;             // the family's operation (e.g. a Gray code pair, a dot frame)
  std::vector<std::size_t> frames;  // indices into the manifest's frames, in the order the operation takes them
  std::array<int, 2> args{};        // the operation's arguments (e.g. axis and bit, a dot's offset)
  const char* stage = "finalize";   // the timing stage; consecutive steps of one stage share a kernel launch
};

class TransportAccumulator {
 public:
  virtual ~TransportAccumulator() = default;
  // One step but the last: `frames` are its frames (camera images of setup.camera_size, of setup.frame_depth: linear
  // CV_32F or raw samples that setup.samples makes linear); white and black are the capture's, linear CV_32F.
  virtual void add(const TransportStep& step, const std::vector<cv::Mat>& frames, const cv::Mat& white,
                   const cv::Mat& black) = 0;
  // After the last step: the whole compressed T.
  virtual CompressedTransport finish() = 0;
};

}  // namespace rfrecon::transport
