// Checks made on frames while they are captured, so that a dropped or late frame is captured again rather than
// reconstructed: a camera that hands back the same frame twice, and a Gray pair that does not add up to white + black.
#pragma once

#include <opencv2/core.hpp>

namespace rfrecon::acquire {

// At most this share of lit pixels may disagree in a Gray pair (pair_mismatch_share) before the pair is captured
// again: by linearity pattern + inverse = white + black at every pixel, whatever the scene, so only noise, the
// cursor or a frame that shows another pattern make it fail.
inline constexpr double kMaxPairMismatchShare = 0.02;

// Whether two raw frames are identical sample for sample: no sensor gives that twice, a stream that repeats a
// buffer does.
bool same_frame(const cv::Mat& a, const cv::Mat& b);

// The share of pixels that are lit: white - black above capture::CaptureChecks::kLitLevel, white below 0.98
// (unsaturated); frames linear CV_32F in [0, 1]. Under 0.1 % the camera does not see the projector, or the white and
// black frames show something else (frames shown late).
double lit_share(const cv::Mat& white, const cv::Mat& black);

// The share of lit pixels (white - black above capture::CaptureChecks::kLitLevel, white below 0.98) where
// |pattern + inverse - white - black| exceeds a quarter of white - black; frames linear CV_32F in [0, 1]. NaN when
// fewer than 0.1 % of the pixels are lit (nothing to judge by).
double pair_mismatch_share(const cv::Mat& white, const cv::Mat& black, const cv::Mat& pattern, const cv::Mat& inverse);

}  // namespace rfrecon::acquire
