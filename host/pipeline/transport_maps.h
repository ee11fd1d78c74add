// Pictures of what the transport stage decoded (`rfrecon transport --maps DIR`): each camera pixel's projector
// coordinate as colour, and why each pixel without one has none, each with its legend and counts.
#pragma once

#include <filesystem>

#include <opencv2/core.hpp>

#include "host/transport/pixel_outcomes.h"
#include "host/transport/transport_types.h"

namespace rfrecon::pipeline {

// CV_8UC3 (BGR): the camera grid, red rising with the projector column and green with the row (sub-pixel
// correspondences), black where there is none; the legend panel of outputs::with_legend to its right.
cv::Mat draw_decoded_map(const transport::CompressedTransport& transport);

// CV_8UC3 (BGR): the camera grid, one colour per transport::PixelOutcome; the legend panel to its right gives each
// outcome's share of the camera's pixels.
cv::Mat draw_outcome_map(const transport::CompressedTransport& transport, const transport::PixelOutcomeCounts& counts);

// decoded.png and outcomes.png into `directory` (a staging directory: written whole or not at all by the caller).
void write_transport_maps(const transport::CompressedTransport& transport, const transport::PixelOutcomeCounts& counts,
                          const std::filesystem::path& directory);

}  // namespace rfrecon::pipeline
