// Frames from files or from a callback, linearised the same way.
#include "host/capture/frame_source.h"

#include <utility>

#include "host/core/errors.h"

namespace rfrecon::capture {

FrameSource::FrameSource(std::filesystem::path capture_dir) : capture_dir_(std::move(capture_dir)) {}

FrameSource FrameSource::from_callback(RawFrame raw_frame, std::string name) {
  FrameSource source;
  source.raw_frame_ = std::move(raw_frame);
  source.name_ = std::move(name);
  source.callback_lock_ = std::make_shared<std::mutex>();
  return source;
}

FrameSource FrameSource::with_check(std::function<void()> check) const {
  FrameSource source = *this;
  source.check_ = std::move(check);
  return source;
}

cv::Mat FrameSource::load(const CaptureManifest& manifest, std::size_t index, FrameForm form) const {
  if (check_) check_();
  if (!raw_frame_) return load_frame(capture_dir_, manifest, index, form);
  const std::string label = describe(manifest, index);
  cv::Mat raw;
  {
    const std::lock_guard<std::mutex> lock(*callback_lock_);
    raw = raw_frame_(index);
  }
  if (raw.empty()) throw InputError(label + ": the source returned no image");
  const cv::Mat frame = frame_in_form(raw, manifest, label, form);
  // The kernels read raw frames in place, batches of them after later calls: a buffer the caller reuses is copied.
  return form == FrameForm::kRaw && (raw.u == nullptr || !raw.isContinuous()) ? raw.clone() : frame;
}

std::string FrameSource::describe(const CaptureManifest& manifest, std::size_t index) const {
  if (!raw_frame_) return (capture_dir_ / manifest.frames.at(index).file).string();
  return name_ + " frame " + std::to_string(index) + " (" + manifest.frames.at(index).file + ")";
}

std::string FrameSource::name() const { return raw_frame_ ? name_ : capture_dir_.string(); }

}  // namespace rfrecon::capture
