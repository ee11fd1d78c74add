// Checkerboard corner detection in camera images and in dual (projector-view) images.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::calib {

// The board as the command line gives it, for messages: "--board 9x6 --square 30".
std::string board_options_text(const BoardSpec& board);

// What to check when the board does not fit the images, for messages.
inline constexpr const char* kBoardAdvice =
    "check that --board gives the printed board's inner corners, COLSxROWS (its squares less one each way), --square "
    "the side of one square in mm, and that the images show the whole board sharply";

// The board's inner corners in its own plane (z = 0), in OpenCV's corner order (row by row), in mm.
std::vector<cv::Point3f> board_object_points(const BoardSpec& board);

// An 8-bit image for the detector: CV_8U is kept; 16-bit and float images are scaled so that their 99.5th
// percentile of finite values maps to 255 (robust to a few hot pixels or specular highlights).
cv::Mat to_detection_image(const cv::Mat& image);

// Corner refinement (chosen by measurement on Bouguet's real images and on rendered camera and dual images,
// docs/calibration.md): the image's slow illumination is removed (minus a Gaussian blur of kRefineHighPassSquares
// square sides), it is blurred by kRefineBlurSigmaPx, and a quadratic surface is fitted around each corner with
// Gaussian weights of sigma kSaddleFitRadiusPx / 2; the corner moves to the surface's saddle point until it settles.
inline constexpr double kRefineHighPassSquares = 0.25;
inline constexpr double kRefineBlurSigmaPx = 1.5;
inline constexpr double kSaddleFitRadiusPx = 2.5;

// The board's inner corners in `image` (any depth); empty when the whole board is not found. OpenCV's sector-based
// detector (findChessboardCornersSB; the classic one where it fails) finds them on an 8-bit copy, then the saddle
// fit refines them on the image at full precision.
std::vector<cv::Point2f> find_board_corners(const cv::Mat& image, const BoardSpec& board);

// The widest gap between reached projector pixels that fill_dual_image_holes bridges, in pixels.
inline constexpr int kMaxGapPx = 2;

// A dual image T^T 1 ready for detection: thin gaps of projector pixels that no camera pixel reaches (`reached` is 0
// there: T's column is empty), up to kMaxGapPx wide, are filled by normalised convolution from their reached
// neighbours, so that moire lines (the projector finer than the camera on the board, or a Gray-code-only T) do not
// break the board. Reached pixels keep their values, and wide unreached areas (the background) stay unchanged. An
// area only partly reached (dark squares taken for shadow, speckled) would be filled from its bright neighbours and
// move the corners, so the calibration's T lights every board pixel (transport::view_capture).
cv::Mat fill_dual_image_holes(const cv::Mat& dual, const cv::Mat& reached);

}  // namespace rfrecon::calib
