// Several exposures of one pattern merged into one linear frame, so that a shiny part's highlights (saturated at a
// long exposure) and its dark flanks (lost in noise at a short one) are both measured (docs/capture.md, "HDR").
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "host/capture/manifest.h"

namespace rfrecon::acquire {

// What merged frames are stored as: 16-bit linear samples, 65535 = full scale of the shortest exposure.
inline constexpr int kMergedBitDepth = 16;

// The camera fields of a manifest of merged frames: 16 bits, black level 0, linear response.
void set_merged_format(capture::CaptureManifest& manifest);

// Merges raw frames of one pattern (`raw[i]` exposed `exposures_us[i]`, in any order; read with `camera`'s bit depth,
// black level and response) into CV_16U in units of the shortest exposure's full scale: at each pixel,
// t_min * sum(linear_i) / sum(t_i) over the exposures that are not at the top code (the maximum-likelihood estimate
// under shot noise); a pixel saturated in every exposure is 65535, which later stages treat as saturated.
cv::Mat merge_exposures(const std::vector<cv::Mat>& raw, const std::vector<double>& exposures_us,
                        const capture::CaptureManifest& camera);

}  // namespace rfrecon::acquire
