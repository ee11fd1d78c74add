// Batches of frames, and white and black, on one OpenCL device for the transport kernels.
#include "host/transport/device_frames.h"

#include <stdexcept>
#include <string>

#include "host/capture/manifest.h"
#include "kernels/common/lanes.h"

namespace rfrecon::transport {

DeviceFrames::DeviceFrames(const TransportSetup& setup, cl::DeviceContext& device, KernelEntry entry, std::size_t slots,
                           std::size_t private_bytes)
    : setup_(setup),
      device_(device),
      entry_(entry),
      n_(setup.camera_size.area()),
      work_group_(cl::private_work_group(device.info(), private_bytes)) {
  if (slots > kSlots) throw std::invalid_argument("DeviceFrames: more slots than RF_FRAME_BATCH");
  if (entry_ == KernelEntry::kSingleWorkItem) {
    pixel_major_.create(static_cast<int>(n_), static_cast<int>(kSlots), CV_32F);
    batch_ = cl::make_buffer<float>(device.context(), kSlots * n_);
    white_ = cl::make_buffer<float>(device.context(), n_);
    black_ = cl::make_buffer<float>(device.context(), n_);
  }
}

void DeviceFrames::add(std::size_t slot, const cv::Mat& frame) {
  if (entry_ == KernelEntry::kNdRange) {
    lent_[slot] = {frame, borrow(frame, setup_.frame_depth)};
  } else {
    check_frame(frame, setup_.frame_depth);
    const cv::Mat linear = setup_.frame_depth == CV_32F ? frame : capture::linearize_samples(frame, setup_.samples);
    linear.reshape(1, static_cast<int>(n_)).copyTo(pixel_major_.col(static_cast<int>(slot)));
  }
}

cl_uint DeviceFrames::set_arguments(::cl::Kernel& kernel, std::size_t count) {
  if (entry_ == KernelEntry::kSingleWorkItem) {
    cl::write_buffer(device_.queue(), batch_, pixel_major_.ptr<float>(), kSlots * n_, true);
    cl::set_args(kernel, batch_);
    return 1;
  }
  for (std::size_t f = 0; f < kSlots; ++f) cl::set_args_from(kernel, f, lent_[f < count ? f : 0].buffer);
  const bool raw = setup_.frame_depth != CV_32F;
  cl::set_args_from(kernel, kSlots, raw ? setup_.samples.black : 0.0f, raw ? setup_.samples.scale : 1.0f);
  return kSlots + 2;
}

void DeviceFrames::run_batch(const ::cl::Kernel& kernel) {
  run(kernel, lanes_items());
  for (auto& lent : lent_) {  // each buffer released before its frame's memory may go
    lent.buffer = ::cl::Buffer();
    lent.frame.release();
  }
}

void DeviceFrames::run_dot_frames(::cl::Kernel& kernel, std::size_t frames,
                                  const std::array<cl_int, 2 * kSlots>& offsets, bool fresh,
                                  const DotRowBuffers& rows) {
  const ::cl::Buffer offsets_buffer = cl::upload(device_.context(), offsets.data(), offsets.size());
  cl_uint next = set_arguments(kernel, frames);
  if (entry_ == KernelEntry::kNdRange) cl::set_args_from(kernel, next++, static_cast<cl_int>(fresh));
  cl::set_args_from(kernel, next, static_cast<cl_int>(frames), offsets_buffer, setup_.dot_spacing,
                    setup_.projector_size.width, setup_.projector_size.height, setup_.thresholds.noise, black_,
                    rows.flags, rows.projector_x, rows.projector_y, rows.indices, rows.weights, rows.energy, count());
  run_batch(kernel);
}

void DeviceFrames::set_white_black(const cv::Mat& white, const cv::Mat& black) {
  if (entry_ == KernelEntry::kSingleWorkItem) {
    upload(white_, white);
    upload(black_, black);
  } else {  // lent until release(): the headers keep their memory alive
    white_frame_ = white;
    black_frame_ = black;
    white_ = borrow(white, CV_32F);
    black_ = borrow(black, CV_32F);
  }
}

void DeviceFrames::release() {
  white_ = black_ = batch_ = ::cl::Buffer();
  pixel_major_.release();
  white_frame_.release();  // after the buffers over it
  black_frame_.release();
}

void DeviceFrames::run(const ::cl::Kernel& kernel, std::size_t items) {
  cl::enqueue_kernel(device_.queue(), kernel, entry_, items, {work_group_});
  RF_CL_CHECK(device_.queue().finish());
}

std::size_t DeviceFrames::lanes_items() const {
  return entry_ == KernelEntry::kNdRange ? (n_ + RF_LANES - 1) / RF_LANES : n_;
}

// Gray, dot and phase frames are of setup_.frame_depth, white and black CV_32F.
void DeviceFrames::check_frame(const cv::Mat& frame, int depth) const {
  if (frame.type() != CV_MAKETYPE(depth, 1) || frame.size() != setup_.camera_size || !frame.isContinuous()) {
    throw std::invalid_argument("transport: frames must be continuous single-channel " +
                                cv::typeToString(CV_MAKETYPE(depth, 1)) + " of the camera size");
  }
}

void DeviceFrames::upload(const ::cl::Buffer& buffer, const cv::Mat& linear, std::size_t offset) {
  check_frame(linear, CV_32F);
  cl::write_buffer(device_.queue(), buffer, linear.ptr<float>(), n_, true, offset);
}

::cl::Buffer DeviceFrames::borrow(const cv::Mat& frame, int depth) const {
  check_frame(frame, depth);
  return cl::borrow(device_.context(), frame.data, n_ * frame.elemSize());
}

}  // namespace rfrecon::transport
