// OpenCV's Gray-code decoding and triangulation on an rfrecon capture.
#include "bench/opencv_graycode.h"

#include <string>

#include <opencv2/calib3d.hpp>
#include <opencv2/structured_light.hpp>

#include "host/capture/graycode_patterns.h"
#include "host/capture/manifest.h"
#include "host/core/errors.h"

namespace rfrecon::bench {

namespace {
cv::Mat frame_8bit(const std::filesystem::path& capture_dir, const capture::CaptureManifest& manifest,
                   const capture::Pattern& pattern) {
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    const capture::Pattern& p = manifest.frames[i].pattern;
    if (p.kind == pattern.kind && p.bit == pattern.bit && p.inverse == pattern.inverse) {
      cv::Mat frame;
      capture::load_frame(capture_dir, manifest, i).convertTo(frame, CV_8U, 255.0);
      return frame;
    }
  }
  throw InputError((capture_dir / capture::kManifestFileName).string() + ": no '" + pattern.kind + "' frame of bit " +
                   std::to_string(pattern.bit) + (pattern.inverse ? " (inverse)" : "") +
                   ", which OpenCV's Gray-code sequence needs");
}
}  // namespace

OpencvGrayFrames opencv_gray_frames(const std::filesystem::path& capture_dir) {
  const capture::CaptureManifest manifest = capture::read_manifest(capture_dir);
  if (manifest.family != capture::kDefaultFamily) {
    throw InputError((capture_dir / capture::kManifestFileName).string() + ": the family '" + manifest.family +
                     "' is not Gray code ('" + capture::kDefaultFamily + "')");
  }
  OpencvGrayFrames frames;
  frames.projector_size = manifest.projector_size;
  for (const capture::Pattern& pattern : capture::opencv_graycode_protocol(manifest.projector_size)) {
    cv::Mat frame = frame_8bit(capture_dir, manifest, pattern);
    if (pattern.kind == capture::pattern_kind::kWhite) {
      frames.white = frame;
    } else if (pattern.kind == capture::pattern_kind::kBlack) {
      frames.black = frame;
    } else {
      frames.patterns.push_back(frame);
    }
  }
  return frames;
}

OpencvCorrespondences opencv_gray_decode(const OpencvGrayFrames& frames, int black_dn, int white_dn) {
  cv::structured_light::GrayCodePattern::Params params;
  params.width = frames.projector_size.width;
  params.height = frames.projector_size.height;
  const auto graycode = cv::structured_light::GrayCodePattern::create(params);
  graycode->setBlackThreshold(black_dn);
  graycode->setWhiteThreshold(white_dn);
  const cv::Mat lit = (frames.white - frames.black) > black_dn;
  OpencvCorrespondences result;
  for (int v = 0; v < lit.rows; ++v) {
    for (int u = 0; u < lit.cols; ++u) {
      cv::Point projector(-1, -1);
      if (lit.at<unsigned char>(v, u) != 0 && !graycode->getProjPixel(frames.patterns, u, v, projector)) {
        result.camera_px.emplace_back(static_cast<float>(u), static_cast<float>(v));
        result.projector_px.emplace_back(static_cast<float>(projector.x), static_cast<float>(projector.y));
      }
    }
  }
  return result;
}

std::vector<cv::Point3f> opencv_triangulate(const calib::StereoRig& rig, const OpencvCorrespondences& correspondences) {
  std::vector<cv::Point3f> points;
  if (correspondences.camera_px.empty()) return points;
  const cv::Mat camera_from_camera = cv::Mat::eye(3, 4, CV_64F);
  cv::Mat proj_from_cam(3, 4, CV_64F);
  cv::hconcat(rig.proj_from_cam_rotation, rig.proj_from_cam_translation_mm, proj_from_cam);
  std::vector<cv::Point2f> camera_rays, projector_rays;
  cv::undistortPoints(correspondences.camera_px, camera_rays, rig.camera_matrix, rig.dist_coeffs);
  cv::undistortPoints(correspondences.projector_px, projector_rays, rig.projector_matrix, rig.projector_dist_coeffs);
  cv::Mat homogeneous;
  cv::triangulatePoints(camera_from_camera, proj_from_cam, camera_rays, projector_rays, homogeneous);
  cv::convertPointsFromHomogeneous(homogeneous.t(), points);
  return points;
}

}  // namespace rfrecon::bench
