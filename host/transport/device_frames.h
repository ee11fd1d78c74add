// Frames handed to a transport kernel on one OpenCL device, a batch of up to RF_FRAME_BATCH per launch: the single
// work-item entries take a batch's frames linear in one buffer, pixel-major (kernels/common/frame_samples.h: pixel c's
// samples side by side, so that a board reads them in one wide word), the NDRange entries read
// each frame where it lies (cl::borrow, no copy on runtimes that run kernels on host memory) as RF_FRAME_BATCH buffer
// arguments, raw samples made linear in the kernel (kernels/common/frame_batch.h). Also white and black, which the
// finalizing kernels read: copied (single work-item) or lent until release().
#pragma once

#include <array>
#include <cstddef>

#include <opencv2/core.hpp>

#include "host/cl/device_context.h"
#include "host/cl/kernel_launch.h"
#include "host/transport/transport_types.h"
#include "kernels/common/params.h"

namespace rfrecon::transport {

// The buffers of T's state that compress.cl's dot_frames reads (flags, the decoded projector pixel) and fills.
struct DotRowBuffers {
  ::cl::Buffer flags, projector_x, projector_y, indices, weights, energy;
};

class DeviceFrames {
 public:
  static constexpr std::size_t kSlots = RF_FRAME_BATCH;

  // `slots` frames at most per batch; `private_bytes`: each NDRange work-item's private memory
  // (cl::private_work_group).
  DeviceFrames(const TransportSetup& setup, cl::DeviceContext& device, KernelEntry entry, std::size_t slots,
               std::size_t private_bytes);

  // Frame `slot` of the batch, of setup.frame_depth.
  void add(std::size_t slot, const cv::Mat& frame);
  // Sets kernel's first arguments to the batch's frames: the batch buffer (uploaded here), or the `count` lent frames
  // then frame 0 again in the unused slots and the samples' linear map. Returns the index of the next argument.
  cl_uint set_arguments(::cl::Kernel& kernel, std::size_t count);
  // Runs kernel over the batch's pixels and waits; then releases the lent frames, each buffer before its frame.
  void run_batch(const ::cl::Kernel& kernel);
  // Runs compress.cl's dot_frames (kernel) over the batch's `frames` dot frames, `offsets` their (x, y) offsets
  // (unused slots 0), into T's rows, as run_batch; `fresh` (NDRange entries): the first batch, which writes every row.
  void run_dot_frames(::cl::Kernel& kernel, std::size_t frames, const std::array<cl_int, 2 * kSlots>& offsets,
                      bool fresh, const DotRowBuffers& rows);

  // White and black (linear CV_32F) for the finalizing kernels: white() and black() until release().
  void set_white_black(const cv::Mat& white, const cv::Mat& black);
  const ::cl::Buffer& white() const { return white_; }
  const ::cl::Buffer& black() const { return black_; }
  void release();

  // Runs kernel over `items` (NDRange: work-items, in work-groups whose private arrays fit a CPU runtime's stack)
  // and waits for it.
  void run(const ::cl::Kernel& kernel, std::size_t items);
  // The items of a kernel taking RF_LANES pixels per work-item: work-items (NDRange) or pixels (single work-item).
  std::size_t lanes_items() const;
  cl_uint count() const { return static_cast<cl_uint>(n_); }

 private:
  void check_frame(const cv::Mat& frame, int depth) const;
  void upload(const ::cl::Buffer& buffer, const cv::Mat& linear, std::size_t offset = 0);
  ::cl::Buffer borrow(const cv::Mat& frame, int depth) const;

  TransportSetup setup_;
  cl::DeviceContext& device_;
  KernelEntry entry_;
  std::size_t n_;
  std::size_t work_group_;  // NDRange work-group size (cl::private_work_group), 0: the runtime's choice
  // NDRange entries: the memory that white_ and black_ lend to the kernels (declared before them: outlives them).
  cv::Mat white_frame_, black_frame_;
  ::cl::Buffer batch_, white_, black_;
  cv::Mat pixel_major_;  // single work-item entries: the batch as batch_ takes it, n rows of kSlots samples
  // A frame lent to the NDRange entries: the frame and a buffer over its memory (destroyed first).
  struct LentFrame {
    cv::Mat frame;
    ::cl::Buffer buffer;
  };
  std::array<LentFrame, kSlots> lent_;
};

}  // namespace rfrecon::transport
