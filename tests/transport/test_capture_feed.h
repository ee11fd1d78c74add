// Feeds in-memory capture frames to a TransportAccumulator in protocol order (the all-at-once path of the tests).
#pragma once

#include <vector>

#include "host/capture/manifest.h"
#include "host/transport/accumulator.h"

namespace rfrecon::transport::testing {

// Linear frames (8-bit readings / 255) of `frames`.
std::vector<cv::Mat> linearize(const std::vector<cv::Mat>& frames);

// Gray pairs, white/black, dot frames, finish: the whole capture held in memory.
CompressedTransport feed_all(TransportAccumulator& accumulator, const std::vector<capture::Pattern>& sequence,
                             const std::vector<cv::Mat>& linear_frames);

// The setup of a capture of `frames` (camera size of the first frame).
TransportSetup setup_for(const std::vector<cv::Mat>& frames, cv::Size projector_size, int dot_spacing, int k);

}  // namespace rfrecon::transport::testing
