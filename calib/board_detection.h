// Checkerboard corner detection in camera images and in dual (projector-view) images.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::calib {

// The board's inner corners in its own plane (z = 0), in OpenCV's corner order (row by row), in mm.
std::vector<cv::Point3f> board_object_points(const BoardSpec& board);

// An 8-bit image for the detector: CV_8U is kept; 16-bit and float images are scaled so that their 99.5th
// percentile of finite values maps to 255 (robust to a few hot pixels or specular highlights).
cv::Mat to_detection_image(const cv::Mat& image);

// Half side of the cornerSubPix window, in board squares (chosen by measurement on rendered camera and dual images: 0.2
// to 0.45 give the same camera error, dual images need 0.3 to 0.4).
inline constexpr double kRefineWindowSquares = 0.35;
// Gaussian blur before the refinement, px: it averages noise and the fill of dual-image gaps (chosen end to end: 1.0
// leaves a 2.1 px projector principal point error with a camera coarser than the projector, 1.5 leaves 1.9 px).
inline constexpr double kRefineBlurSigmaPx = 1.5;

// The board's inner corners in `image` (any depth); empty when the whole board is not found. OpenCV's sector-based
// detector (findChessboardCornersSB; the classic one where it fails) finds them on an 8-bit copy, then cornerSubPix
// refines them on the image at full precision, in a window of kRefineWindowSquares square sides.
std::vector<cv::Point2f> find_board_corners(const cv::Mat& image, const BoardSpec& board);

// The widest gap between reached projector pixels that fill_dual_image_holes bridges, in pixels.
inline constexpr int kMaxGapPx = 2;

// A dual image T^T 1 ready for detection: thin gaps of projector pixels that no camera pixel reaches (`reached` is 0
// there: T's column is empty), up to kMaxGapPx wide, are filled by normalised convolution from their reached
// neighbours, so that moire lines (the projector finer than the camera on the board, or a Gray-code-only T) do not
// break the board. Reached pixels keep their values, and wide unreached areas (dark squares whose transport is
// below the noise threshold, the background) stay unchanged, so edges do not move.
cv::Mat fill_dual_image_holes(const cv::Mat& dual, const cv::Mat& reached);

}  // namespace rfrecon::calib
