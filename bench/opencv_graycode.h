// OpenCV's Gray-code pipeline, the peer rfrecon's benchmarks and accuracy tables set it against: GrayCodePattern's
// decoding of a capture's Gray pairs (integer projector pixels) and cv::triangulatePoints through the rig.
#pragma once

#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::bench {

// A capture's frames as OpenCV takes them: 8-bit, the Gray pairs in GrayCodePattern's order.
struct OpencvGrayFrames {
  cv::Size projector_size;
  cv::Mat white, black;
  std::vector<cv::Mat> patterns;
};

// The white, black and Gray-code frames of a graycode-family capture (with or without its dot grid), each matched by
// its pattern to capture::opencv_graycode_protocol's order. Throws InputError naming the manifest when the capture is
// of another family or lacks a frame of that sequence.
OpencvGrayFrames opencv_gray_frames(const std::filesystem::path& capture_dir);

// Camera pixels (pixel centres at integers) and the projector pixel GrayCodePattern::getProjPixel decodes for each.
struct OpencvCorrespondences {
  std::vector<cv::Point2f> camera_px, projector_px;
};

// getProjPixel at every lit pixel (white - black > black_dn); GrayCodePattern refuses a pixel whose pattern and inverse
// differ by less than white_dn. rfrecon's defaults are black_dn 10 and white_dn 5 in 8-bit numbers.
OpencvCorrespondences opencv_gray_decode(const OpencvGrayFrames& frames, int black_dn, int white_dn);

// cv::undistortPoints of both sides and cv::triangulatePoints through `rig`: one camera-frame point (mm) a
// correspondence.
std::vector<cv::Point3f> opencv_triangulate(const calib::StereoRig& rig, const OpencvCorrespondences& correspondences);

}  // namespace rfrecon::bench
