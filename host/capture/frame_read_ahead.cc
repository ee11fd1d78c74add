// A bounded window of frame groups read by a pool of threads and handed over in order.
#include "host/capture/frame_read_ahead.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace rfrecon::capture {

FrameReadAhead::FrameReadAhead(const FrameSource& source, const CaptureManifest& manifest,
                               std::vector<std::vector<std::size_t>> groups, int readers, std::size_t depth,
                               FrameForm form)
    : source_(source),
      manifest_(manifest),
      groups_(std::move(groups)),
      depth_(std::max<std::size_t>(depth, 1)),
      form_(form),
      slots_(groups_.size()) {
  if (readers < 1) throw std::invalid_argument("FrameReadAhead: readers must be at least 1");
  for (int r = 0; r < readers; ++r) readers_.emplace_back([this] { read_groups(); });
}

FrameReadAhead::~FrameReadAhead() {
  {
    const std::lock_guard<std::mutex> guard(lock_);
    stop_ = true;
  }
  changed_.notify_all();
  for (auto& reader : readers_) reader.join();
}

void FrameReadAhead::read_groups() {
  for (;;) {
    std::size_t group = 0;
    {
      std::unique_lock<std::mutex> guard(lock_);
      changed_.wait(guard, [&] { return stop_ || next_read_ >= groups_.size() || next_read_ < next_take_ + depth_; });
      if (stop_ || next_read_ >= groups_.size()) return;
      group = next_read_++;
    }
    Slot slot;
    try {
      for (const std::size_t index : groups_[group]) slot.frames.push_back(source_.load(manifest_, index, form_));
    } catch (...) {
      slot.error = std::current_exception();
    }
    {
      const std::lock_guard<std::mutex> guard(lock_);
      if (slot.error) stop_ = true;  // the run ends at this group: read nothing after it
      slot.ready = true;
      slots_[group] = std::move(slot);
    }
    changed_.notify_all();
  }
}

std::vector<cv::Mat> FrameReadAhead::take(std::size_t i) {
  if (i != next_take_ || i >= groups_.size()) throw std::logic_error("FrameReadAhead: groups are taken in order");
  std::unique_lock<std::mutex> guard(lock_);
  // A failed read stops the readers, so a group after it may never come: wait only while it can.
  changed_.wait(guard, [&] { return slots_[i].ready || (stop_ && i >= next_read_); });
  if (!slots_[i].ready) throw std::logic_error("FrameReadAhead: group after a failed read");
  Slot slot = std::move(slots_[i]);
  next_take_ = i + 1;
  guard.unlock();
  changed_.notify_all();
  if (slot.error) std::rethrow_exception(slot.error);
  return std::move(slot.frames);
}

}  // namespace rfrecon::capture
