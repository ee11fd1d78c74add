// The built-in pattern family "graycode": white, black, Gray code of columns and rows with inverses (OpenCV
// GrayCodePattern's images), then an optional s x s dot grid that samples the light transport itself.
#pragma once

#include <memory>

#include <opencv2/core.hpp>

#include "host/capture/pattern_family.h"

namespace rfrecon::capture {

// The family: white, black, then for each column bit (MSB first) the pattern and its inverse, then the same for rows
// (OpenCV GrayCodePattern order), then the dot grid (host/capture/dot_grid.h) of the options' dot_spacing.
std::shared_ptr<const PatternFamily> graycode_family();

// Number of Gray code bits for a projector axis of n pixels: ceil(log2(n)), as OpenCV's GrayCodePattern.
int gray_bits(int n);

// The Gray code value of projector coordinate `coordinate` for bit `bit` (MSB first) of an axis with `bits` bits.
bool gray_code_bit(int coordinate, int bit, int bits);

// Whether a pattern is one of a Gray code pair (either axis).
bool is_gray(const Pattern& pattern);

// OpenCV GrayCodePattern's capture order: its Gray code images (columns then rows, each pattern then inverse),
// then one white and one black frame.
std::vector<Pattern> opencv_graycode_protocol(cv::Size projector_size);

}  // namespace rfrecon::capture
