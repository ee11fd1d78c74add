// Captures from a directory, from frames in memory or from a callback, and the protocol's manifest and patterns.
#include <utility>

#include "host/capture/frame_source.h"
#include "host/capture/pattern_files.h"
#include "host/capture/protocol.h"
#include "host/core/errors.h"
#include "host/core/limits.h"
#include "host/transport/compute_transport.h"
#include "rfrecon/rfrecon.h"

namespace rfrecon {

Capture Capture::from_directory(const std::filesystem::path& dir, const std::string& layout, cv::Size projector_size,
                                int bit_depth) {
  Capture capture;
  capture.manifest_ =
      transport::open_capture(dir, layout, projector_size, capture::FramePaths::kInsideCapture, bit_depth);
  capture.name_ = dir.string();
  capture.dir_ = dir;
  return capture;
}

Capture Capture::from_frames(Manifest manifest, std::vector<cv::Mat> frames, std::string name) {
  if (frames.size() != manifest.frames.size()) {
    throw InputError(name + ": " + std::to_string(frames.size()) + " frames for a manifest of " +
                     std::to_string(manifest.frames.size()));
  }
  auto shared = std::make_shared<const std::vector<cv::Mat>>(std::move(frames));
  return from_callback(
      std::move(manifest), [shared](std::size_t index) { return (*shared)[index]; }, std::move(name));
}

Capture Capture::from_callback(Manifest manifest, std::function<cv::Mat(std::size_t index)> frame, std::string name) {
  if (!frame) throw InputError(name + ": no frame function");
  Capture capture;
  capture.manifest_ = std::move(manifest);
  capture.name_ = std::move(name);
  capture.frame_ = std::move(frame);
  return capture;
}

cv::Mat Capture::frame(std::size_t index) const {
  if (index >= manifest_.frames.size()) {
    throw InputError(name_ + ": frame " + std::to_string(index) + " of a manifest of " +
                     std::to_string(manifest_.frames.size()) + " frames");
  }
  const capture::FrameSource source =
      frame_ ? capture::FrameSource::from_callback(frame_, name_) : capture::FrameSource(dir_);
  return source.load(manifest_, index, capture::FrameForm::kRaw);
}

Manifest make_manifest(cv::Size projector_size, cv::Size camera_size, int bit_depth, int dot_spacing,
                       const std::string& family, const std::map<std::string, int>& parameters) {
  check_image_size(projector_size, "make_manifest: projector");
  check_image_size(camera_size, "make_manifest: camera");
  Manifest manifest;
  manifest.family = family;
  manifest.projector_size = projector_size;
  manifest.camera_size = camera_size;
  manifest.bit_depth = bit_depth;
  manifest.dot_spacing = dot_spacing;
  manifest.parameters = parameters;
  try {
    manifest.frames = capture::protocol_frames(capture::protocol_options(manifest));
  } catch (const InputError& error) {
    throw InputError(std::string("make_manifest: ") + error.what());
  }
  capture::validate_manifest(manifest, "make_manifest");
  return manifest;
}

cv::Mat pattern_image(const Manifest& manifest, std::size_t index) {
  if (index >= manifest.frames.size()) {
    throw InputError("pattern_image: frame " + std::to_string(index) + " of a manifest of " +
                     std::to_string(manifest.frames.size()) + " frames");
  }
  return capture::render_pattern(manifest.frames[index].pattern, capture::protocol_options(manifest));
}

}  // namespace rfrecon
