// Where a capture's frames come from: the files its manifest names, or a function that hands them over (a camera
// SDK, frames already in memory). Either way they come out linearised, or raw and checked, the same way.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <opencv2/core.hpp>

#include "host/capture/manifest.h"

namespace rfrecon::capture {

class FrameSource {
 public:
  // Frame `index` of the manifest as the camera gave it: one channel, CV_8U or CV_16U as the manifest's bit_depth
  // says, of the camera size. Called by one thread at a time (the source holds a lock around it); the transport stage
  // asks for white and black first, then for each frame once, in its order with one reader thread and in any order
  // within the read-ahead window with more; an index is asked for again only after a device failed mid-run
  // (compute_transport_on_devices). It throws to end the run. An image over memory it does not own (a cv::Mat made
  // over a camera SDK's buffer) or not continuous is copied; one it owns must stay unchanged until dropped, as the
  // kernels may read a raw frame after later calls.
  using RawFrame = std::function<cv::Mat(std::size_t index)>;

  // The files of the manifest inside (or relative to) `capture_dir`: what `rfrecon transport` reads. Implicit: a
  // capture directory is a frame source wherever one is taken.
  FrameSource(std::filesystem::path capture_dir);
  // Frames from `raw_frame`; `name` stands for the source in error messages ("camera SDK", "frames in memory").
  static FrameSource from_callback(RawFrame raw_frame, std::string name);

  // The same source, calling `check` before every frame it loads (from the reading thread): a check that throws ends
  // the run as a failed read does (a library caller's cancellation).
  FrameSource with_check(std::function<void()> check) const;
  // Frame `index`, linearised (CV_32F, [0, 1]: capture::linearize_frame) or raw (checked: check_raw_frame). Throws
  // InputError naming the file, or the source and frame, when it is missing, unreadable, mis-sized or of the wrong
  // bit depth. Thread-safe.
  cv::Mat load(const CaptureManifest& manifest, std::size_t index, FrameForm form = FrameForm::kLinear) const;

  // The frame's name in messages: its path, or "<name> frame <index> (<file>)".
  std::string describe(const CaptureManifest& manifest, std::size_t index) const;
  // The source's name in messages: the capture directory, or the callback's name.
  std::string name() const;

 private:
  FrameSource() = default;

  std::filesystem::path capture_dir_;
  RawFrame raw_frame_;
  std::string name_;
  std::shared_ptr<std::mutex> callback_lock_;
  std::function<void()> check_;
};

}  // namespace rfrecon::capture
