// The transport accumulator on one OpenCL device: kernels/transport/decode.cl and compress.cl. The transport's own
// arrays are the kernels' state; NDRange entries read each frame where it lies, single work-item ones take batches.
#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "host/cl/kernel_launch.h"
#include "host/transport/accumulator.h"
#include "kernels/common/lanes.h"
#include "kernels/transport/gray_decode.h"

namespace rfrecon::transport {

namespace {

class DeviceAccumulator final : public TransportAccumulator {
 public:
  DeviceAccumulator(const TransportSetup& setup, cl::DeviceContext& device, cl::ProgramCache& programs,
                    KernelEntry entry, const std::string& build_options)
      : setup_(setup),
        device_(device),
        entry_(entry),
        n_(setup.camera_size.area()),
        state_(make_empty_transport(setup)),
        gray_batch_(entry == KernelEntry::kSingleWorkItem ? kGrayBatch : 1) {
    if (setup.entries_per_pixel < 1) throw std::invalid_argument("transport: K must be at least 1");
    const ::cl::Program decode = programs.get(device, "transport/decode.cl", build_options);
    const ::cl::Program compress =
        programs.get(device, "transport/compress.cl", transport_build_options(setup.entries_per_pixel, build_options));
    gray_pairs_ = cl::make_kernel(decode, "gray_pairs", entry);
    gray_finalize_ = cl::make_kernel(decode, "gray_finalize", entry);
    dot_frames_ = cl::make_kernel(compress, "dot_frames", entry);
    finalize_ = cl::make_kernel(compress, "finalize", entry);

    const ::cl::Context& context = device.context();
    // Single work-item entries take a launch's frames in one buffer (dot frames, or Gray pairs' two frames each); the
    // NDRange entries read each frame where it lies (borrow).
    if (entry_ == KernelEntry::kSingleWorkItem) {
      const std::size_t batch_frames = std::max<std::size_t>(setup.dot_spacing > 0 ? kBatch : 0, 2 * gray_batch_);
      batch_ = cl::make_buffer<float>(context, batch_frames * n_);
      pairs_buffer_ = cl::make_buffer<cl_uint>(context, pairs_.size());
    }
    white_ = cl::make_buffer<float>(context, n_);
    black_ = cl::make_buffer<float>(context, n_);
    // The transport's own arrays, in their initial state, are the kernels' state: no copy in or out on runtimes that
    // run kernels on host memory.
    gray_x_ = cl::share(context, state_.gray_x);
    gray_y_ = cl::share(context, state_.gray_y);
    flags_ = cl::share(context, state_.flags);
    indices_ = cl::share(context, state_.indices);
    weights_ = cl::share(context, state_.weights);
    energy_ = cl::share(context, state_.direct_energy);
    correspondence_ = cl::share(context, state_.correspondence);
  }

  void add_gray_pair(GrayAxis axis, int bit, const cv::Mat& pattern, const cv::Mat& inverse) override {
    const cl_uint mask = gray_bit_mask(setup_, axis, bit);
    if (entry_ != KernelEntry::kSingleWorkItem) {  // this pair alone, read where it lies, into its axis' code word
      const ::cl::Buffer pattern_buffer = borrow(pattern);  // kernel arguments do not hold their buffers
      const ::cl::Buffer inverse_buffer = borrow(inverse);
      cl::set_args(gray_pairs_, pattern_buffer, inverse_buffer, mask, setup_.thresholds.white,
                   axis == GrayAxis::kColumns ? gray_x_ : gray_y_, flags_, count());
      run(gray_pairs_);  // waits: the frames may go once it returns
      return;
    }
    upload(batch_, pattern, 2 * gray_pending_ * n_);
    upload(batch_, inverse, (2 * gray_pending_ + 1) * n_);
    pairs_[2 * gray_pending_] = mask;
    pairs_[2 * gray_pending_ + 1] = axis == GrayAxis::kColumns ? 0 : 1;
    if (++gray_pending_ == gray_batch_) decode_batch();
  }

  void finish_gray(const cv::Mat& white, const cv::Mat& black) override {
    if (gray_pending_ > 0) decode_batch();
    upload(white_, white);
    upload(black_, black);
    cl::set_args(gray_finalize_, white_, black_, setup_.thresholds.black, setup_.projector_size.width,
                 setup_.projector_size.height, gray_x_, gray_y_, flags_, count());
    run(gray_finalize_);
  }

  void add_dot_frame(int offset_x, int offset_y, const cv::Mat& frame) override {
    check_dot_offsets(setup_, offset_x, offset_y);
    if (entry_ == KernelEntry::kSingleWorkItem) {
      upload(batch_, frame, pending_ * n_);
    } else {  // lent until the batch is compressed: the header keeps the frame's memory alive
      lent_[pending_] = {frame, borrow(frame)};
    }
    offsets_[2 * pending_] = offset_x;
    offsets_[2 * pending_ + 1] = offset_y;
    if (++pending_ == kBatch) compress_batch();
  }

  CompressedTransport finish() override {
    if (pending_ > 0) compress_batch();
    cl::set_args(finalize_, white_, black_, setup_.dot_spacing > 0 ? 1 : 0, setup_.projector_size.width,
                 setup_.thresholds.noise, flags_, gray_x_, gray_y_, indices_, weights_, energy_, correspondence_,
                 count());
    run(finalize_);
    for (const auto* buffer : {&gray_x_, &gray_y_, &flags_, &indices_, &weights_, &energy_, &correspondence_}) {
      cl::sync_to_host(device_.queue(), *buffer);
    }
    gray_x_ = gray_y_ = flags_ = indices_ = weights_ = energy_ = correspondence_ = ::cl::Buffer();
    return std::move(state_);
  }

 private:
  cl_uint count() const { return static_cast<cl_uint>(n_); }

  void check_frame(const cv::Mat& frame) const {
    if (frame.type() != CV_32FC1 || frame.size() != setup_.camera_size || !frame.isContinuous()) {
      throw std::invalid_argument("transport: frames must be continuous CV_32FC1 of the camera size");
    }
  }

  void upload(const ::cl::Buffer& buffer, const cv::Mat& frame, std::size_t offset = 0) {
    check_frame(frame);
    cl::write_buffer(device_.queue(), buffer, frame.ptr<float>(), n_, true, offset);
  }

  // The frame's own memory as a buffer: no copy on runtimes that run kernels on host memory (cl::borrow).
  ::cl::Buffer borrow(const cv::Mat& frame) const {
    check_frame(frame);
    return cl::borrow(device_.context(), frame.ptr<float>(), n_);
  }

  // One single work-item launch over the pending Gray pairs; unused slots stay 0 (the kernel skips those pairs).
  void decode_batch() {
    // Not blocking: the in-order queue writes it before the launch, and run() waits for both before pairs_ changes.
    cl::write_buffer(device_.queue(), pairs_buffer_, pairs_.data(), pairs_.size(), false);
    cl::set_args(gray_pairs_, batch_, static_cast<cl_int>(gray_pending_), pairs_buffer_, setup_.thresholds.white,
                 gray_x_, gray_y_, flags_, count());
    run(gray_pairs_);
    gray_pending_ = 0;
    pairs_.fill(0);
  }

  // One launch over the pending frames; offsets of unused batch slots stay 0 (the kernel skips those frames).
  void compress_batch() {
    const ::cl::Buffer offsets = cl::upload(device_.context(), offsets_.data(), offsets_.size());
    cl_uint frame_arguments = 1;
    if (entry_ == KernelEntry::kSingleWorkItem) {
      cl::set_args(dot_frames_, batch_);
    } else {
      for (std::size_t f = 0; f < kBatch; ++f) cl::set_args_from(dot_frames_, f, lent_[f < pending_ ? f : 0].buffer);
      frame_arguments = kBatch;
    }
    cl::set_args_from(dot_frames_, frame_arguments, static_cast<cl_int>(pending_), offsets, setup_.dot_spacing,
                      setup_.projector_size.width, setup_.projector_size.height, setup_.thresholds.noise, black_,
                      flags_, gray_x_, gray_y_, indices_, weights_, energy_, count());
    run(dot_frames_, entry_ == KernelEntry::kNdRange ? (n_ + RF_LANES - 1) / RF_LANES : n_);
    for (auto& lent : lent_) {  // each buffer released before its frame's memory may go
      lent.buffer = ::cl::Buffer();
      lent.frame.release();
    }
    pending_ = 0;
    offsets_.fill(0);
  }

  // Runs kernel over `items` (NDRange: work-items; default one per pixel) and waits for it.
  void run(const ::cl::Kernel& kernel) { run(kernel, n_); }
  void run(const ::cl::Kernel& kernel, std::size_t items) {
    cl::enqueue_kernel(device_.queue(), kernel, entry_, items);
    RF_CL_CHECK(device_.queue().finish());
  }

  static constexpr std::size_t kBatch = RF_FRAME_BATCH;
  static constexpr std::size_t kGrayBatch = RF_GRAY_PAIR_BATCH;

  TransportSetup setup_;
  cl::DeviceContext& device_;
  KernelEntry entry_;
  std::size_t n_;
  CompressedTransport state_;  // the kernels' state, shared with them (cl::share) until finish() returns it
  // Gray pairs per decode launch: a whole batch on FPGA boards (single work-item: one read-modify-write of each
  // pixel's code words in DDR per batch), one on CPUs and GPUs, which decode a pair while its frames are still in
  // cache (batched, PoCL's decode took twice as long: a launch reads 16 frames spread over the 84 MB batch).
  std::size_t gray_batch_;
  ::cl::Kernel gray_pairs_, gray_finalize_, dot_frames_, finalize_;
  // Single work-item entries: the batch of Gray pairs or of dot frames. All Gray pairs come before finish_gray, which
  // decodes the last batch before the first dot frame (the call order of TransportAccumulator).
  ::cl::Buffer batch_, pairs_buffer_, white_, black_, gray_x_, gray_y_, flags_, indices_, weights_, energy_,
      correspondence_;
  std::size_t gray_pending_ = 0;                    // Gray pairs in batch_ not yet decoded
  std::array<cl_uint, 2 * kGrayBatch> pairs_ = {};  // their (bit mask, axis)
  // A dot frame lent to the NDRange entry: the frame and a buffer over its memory (destroyed first).
  struct LentFrame {
    cv::Mat frame;
    ::cl::Buffer buffer;
  };
  std::array<LentFrame, kBatch> lent_;
  std::size_t pending_ = 0;                      // dot frames in batch_ or lent_ not yet compressed
  std::array<cl_int, 2 * kBatch> offsets_ = {};  // their (x, y) dot offsets
};

}  // namespace

std::unique_ptr<TransportAccumulator> make_device_accumulator(TransportSetup setup, cl::DeviceContext& device,
                                                              cl::ProgramCache& programs, KernelEntry entry,
                                                              const std::string& build_options) {
  check_kernel_dot_spacing(setup.dot_spacing);
  setup.thresholds = resolve_thresholds(setup.thresholds, 8);
  return std::make_unique<DeviceAccumulator>(setup, device, programs, entry, build_options);
}

}  // namespace rfrecon::transport
