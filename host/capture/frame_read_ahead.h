// Frames read ahead of their use by a pool of reader threads, a bounded number of groups at a time.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

#include "host/capture/frame_source.h"

namespace rfrecon::capture {

class FrameReadAhead {
 public:
  // `groups[i]` lists the manifest indices of the frames taken together as group i (a Gray pair, a dot frame, or
  // none). `readers` threads read the groups in order, at most `depth` of them ahead of the next one taken, so at
  // most `depth` groups' frames are in memory; frames come in `form`. `source` and `manifest` must outlive this
  // object.
  FrameReadAhead(const FrameSource& source, const CaptureManifest& manifest,
                 std::vector<std::vector<std::size_t>> groups, int readers, std::size_t depth,
                 FrameForm form = FrameForm::kLinear);
  // Stops the readers after the frames they are reading; frames not taken are dropped.
  ~FrameReadAhead();
  FrameReadAhead(const FrameReadAhead&) = delete;
  FrameReadAhead& operator=(const FrameReadAhead&) = delete;

  // Group i's frames, once read; groups are taken in order 0, 1, 2... Rethrows the reader's error for that group.
  std::vector<cv::Mat> take(std::size_t i);

 private:
  struct Slot {
    bool ready = false;
    std::vector<cv::Mat> frames;
    std::exception_ptr error;
  };
  void read_groups();

  const FrameSource& source_;
  const CaptureManifest& manifest_;
  const std::vector<std::vector<std::size_t>> groups_;
  const std::size_t depth_;
  const FrameForm form_;
  std::mutex lock_;
  std::condition_variable changed_;
  std::vector<Slot> slots_;
  std::size_t next_read_ = 0;  // the next group a reader claims
  std::size_t next_take_ = 0;  // the next group take() returns
  bool stop_ = false;          // set by the destructor and by a failed read
  std::vector<std::thread> readers_;
};

}  // namespace rfrecon::capture
