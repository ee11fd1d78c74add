// The transport accumulator on one OpenCL device: kernels/transport/decode.cl and compress.cl. The transport's own
// arrays are the kernels' state; NDRange entries read each frame where it lies (raw samples made linear in the
// kernels), single work-item ones take batches of linear frames.
#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <utility>

#include "host/capture/manifest.h"
#include "host/cl/kernel_launch.h"
#include "host/transport/graycode_accumulator.h"
#include "kernels/common/lanes.h"
#include "kernels/transport/gray_decode.h"

namespace rfrecon::transport {

namespace {

class DeviceAccumulator final : public GraycodeAccumulator {
 public:
  DeviceAccumulator(const TransportSetup& setup, cl::DeviceContext& device, cl::ProgramCache& programs,
                    KernelEntry entry, const std::string& build_options, CompressedTransport storage)
      : setup_(setup),
        device_(device),
        entry_(entry),
        n_(setup.camera_size.area()),
        work_group_(cl::private_work_group(device.info(), transport_private_bytes(setup.entries_per_pixel))),
        state_(make_empty_decoding(setup, std::move(storage))) {
    if (setup.entries_per_pixel < 1) throw std::invalid_argument("transport: K must be at least 1");
    const std::vector<cl::ProgramRequest> requests = transport_programs(setup, entry, build_options);
    const ::cl::Program decode = programs.get(device, requests[0].kernel_path, requests[0].options);
    const ::cl::Program compress = programs.get(device, requests[1].kernel_path, requests[1].options);
    gray_pairs_ = cl::make_kernel(decode, "gray_pairs", entry);
    gray_finalize_ = cl::make_kernel(decode, "gray_finalize", entry);
    dot_frames_ = cl::make_kernel(compress, "dot_frames", entry);
    finalize_ = cl::make_kernel(compress, "finalize", entry);

    const ::cl::Context& context = device.context();
    // Single work-item entries take a launch's frames in one buffer (dot frames, or Gray pairs' two frames each) and
    // copies of white and black; the NDRange entries read each frame where it lies (lend).
    if (entry_ == KernelEntry::kSingleWorkItem) {
      batch_ = cl::make_buffer<float>(context, (setup.dot_spacing > 0 ? kBatch : 2 * kGrayBatch) * n_);
      white_ = cl::make_buffer<float>(context, n_);
      black_ = cl::make_buffer<float>(context, n_);
    }
    pairs_buffer_ = cl::make_buffer<cl_uint>(context, pairs_.size());
    // The transport's own arrays, in their initial state, are the kernels' state: no copy in or out on runtimes that
    // run kernels on host memory. T's rows come with the first dot frame or finish() (share_rows).
    gray_x_ = cl::share(context, state_.gray_x);
    gray_y_ = cl::share(context, state_.gray_y);
    flags_ = cl::share(context, state_.flags);
    energy_ = cl::share(context, state_.direct_energy);
    correspondence_ = cl::share(context, state_.correspondence);
  }

  void add_gray_pair(GrayAxis axis, int bit, const cv::Mat& pattern, const cv::Mat& inverse) override {
    add_to_batch(2 * gray_pending_, pattern);
    add_to_batch(2 * gray_pending_ + 1, inverse);
    pairs_[2 * gray_pending_] = gray_bit_mask(setup_, axis, bit);
    pairs_[2 * gray_pending_ + 1] = axis == GrayAxis::kColumns ? 0 : 1;
    if (++gray_pending_ == kGrayBatch) decode_batch();
  }

  void finish_gray(const cv::Mat& white, const cv::Mat& black) override {
    if (gray_pending_ > 0) decode_batch();
    if (entry_ == KernelEntry::kSingleWorkItem) {
      upload(white_, white);
      upload(black_, black);
    } else {  // lent until finish(): the headers keep their memory alive
      white_frame_ = white;
      black_frame_ = black;
      white_ = borrow(white, CV_32F);
      black_ = borrow(black, CV_32F);
    }
    cl::set_args(gray_finalize_, white_, black_, setup_.thresholds.black, setup_.projector_size.width,
                 setup_.projector_size.height, gray_x_, gray_y_, flags_, count());
    run(gray_finalize_, lanes_items());
  }

  void add_dot_frame(int offset_x, int offset_y, const cv::Mat& frame) override {
    check_dot_offsets(setup_, offset_x, offset_y);
    add_to_batch(pending_, frame);
    offsets_[2 * pending_] = offset_x;
    offsets_[2 * pending_ + 1] = offset_y;
    if (++pending_ == kBatch) compress_batch();
  }

  CompressedTransport finish() override {
    if (pending_ > 0) compress_batch();
    share_rows();
    cl::set_args(finalize_, white_, black_, setup_.dot_spacing > 0 ? 1 : 0, setup_.projector_size.width,
                 setup_.thresholds.noise, flags_, gray_x_, gray_y_, indices_, weights_, energy_, correspondence_,
                 count());
    run(finalize_);
    for (const auto* buffer : {&gray_x_, &gray_y_, &flags_, &indices_, &weights_, &energy_, &correspondence_}) {
      cl::sync_to_host(device_.queue(), *buffer);
    }
    gray_x_ = gray_y_ = flags_ = indices_ = weights_ = energy_ = correspondence_ = white_ = black_ = ::cl::Buffer();
    white_frame_.release();  // after the buffers over it
    black_frame_.release();
    return std::move(state_);
  }

 private:
  cl_uint count() const { return static_cast<cl_uint>(n_); }

  // Gray and dot frames are of setup_.frame_depth, white and black CV_32F.
  void check_frame(const cv::Mat& frame, int depth) const {
    if (frame.type() != CV_MAKETYPE(depth, 1) || frame.size() != setup_.camera_size || !frame.isContinuous()) {
      throw std::invalid_argument("transport: frames must be continuous single-channel " +
                                  cv::typeToString(CV_MAKETYPE(depth, 1)) + " of the camera size");
    }
  }

  void upload(const ::cl::Buffer& buffer, const cv::Mat& linear, std::size_t offset = 0) {
    check_frame(linear, CV_32F);
    cl::write_buffer(device_.queue(), buffer, linear.ptr<float>(), n_, true, offset);
  }

  // The frame's own memory as a buffer: no copy on runtimes that run kernels on host memory (cl::borrow).
  ::cl::Buffer borrow(const cv::Mat& frame, int depth) const {
    check_frame(frame, depth);
    return cl::borrow(device_.context(), frame.data, n_ * frame.elemSize());
  }

  // Frame `slot` of the batch: copied into batch_, linear (single work-item), or lent until the batch has run, the
  // header keeping the frame's memory alive (NDRange).
  void add_to_batch(std::size_t slot, const cv::Mat& frame) {
    if (entry_ == KernelEntry::kNdRange) {
      lent_[slot] = {frame, borrow(frame, setup_.frame_depth)};
    } else if (setup_.frame_depth == CV_32F) {
      upload(batch_, frame, slot * n_);
    } else {
      check_frame(frame, setup_.frame_depth);
      upload(batch_, capture::linearize_samples(frame, setup_.samples), slot * n_);
    }
  }

  // Sets kernel's first arguments to the batch's frames: batch_, or the `count` lent frames then frame 0 again in the
  // unused slots and the samples' linear map. Returns the index of the next argument.
  cl_uint set_frame_arguments(::cl::Kernel& kernel, std::size_t count) {
    if (entry_ == KernelEntry::kSingleWorkItem) {
      cl::set_args(kernel, batch_);
      return 1;
    }
    for (std::size_t f = 0; f < kBatch; ++f) cl::set_args_from(kernel, f, lent_[f < count ? f : 0].buffer);
    const bool raw = setup_.frame_depth != CV_32F;
    cl::set_args_from(kernel, kBatch, raw ? setup_.samples.black : 0.0f, raw ? setup_.samples.scale : 1.0f);
    return kBatch + 2;
  }

  // Runs kernel over the batch's pixels (NDRange: RF_LANES per work-item), waits, and releases the lent frames, each
  // buffer before its frame's memory may go.
  void run_batch(const ::cl::Kernel& kernel) {
    run(kernel, lanes_items());
    for (auto& lent : lent_) {  // each buffer released before its frame's memory may go
      lent.buffer = ::cl::Buffer();
      lent.frame.release();
    }
  }

  // One launch over the pending Gray pairs; unused slots stay 0 (the kernel skips those pairs).
  void decode_batch() {
    // Not blocking: the in-order queue writes it before the launch, and run() waits for both before pairs_ changes.
    cl::write_buffer(device_.queue(), pairs_buffer_, pairs_.data(), pairs_.size(), false);
    const cl_uint next = set_frame_arguments(gray_pairs_, 2 * gray_pending_);
    cl::set_args_from(gray_pairs_, next, static_cast<cl_int>(gray_pending_), pairs_buffer_, setup_.thresholds.white,
                      gray_x_, gray_y_, flags_, count());
    run_batch(gray_pairs_);
    gray_pending_ = 0;
    pairs_.fill(0);
  }

  // T's rows, shared with the kernels once: empty, or with `kernel_empties` only sized (the NDRange entry's first
  // batch writes every row).
  void share_rows(bool kernel_empties = false) {
    if (indices_() != nullptr) return;
    if (kernel_empties) {
      size_rows(state_);
    } else {
      add_empty_rows(state_);
    }
    indices_ = cl::share(device_.context(), state_.indices);
    weights_ = cl::share(device_.context(), state_.weights);
  }

  // One launch over the pending frames; offsets of unused batch slots stay 0 (the kernel skips those frames).
  void compress_batch() {
    const bool fresh = entry_ == KernelEntry::kNdRange && indices_() == nullptr;
    share_rows(fresh);
    const ::cl::Buffer offsets = cl::upload(device_.context(), offsets_.data(), offsets_.size());
    cl_uint next = set_frame_arguments(dot_frames_, pending_);
    if (entry_ == KernelEntry::kNdRange) cl::set_args_from(dot_frames_, next++, static_cast<cl_int>(fresh));
    cl::set_args_from(dot_frames_, next, static_cast<cl_int>(pending_), offsets, setup_.dot_spacing,
                      setup_.projector_size.width, setup_.projector_size.height, setup_.thresholds.noise, black_,
                      flags_, gray_x_, gray_y_, indices_, weights_, energy_, count());
    run_batch(dot_frames_);
    pending_ = 0;
    offsets_.fill(0);
  }

  // The items of a kernel taking RF_LANES pixels per work-item: work-items (NDRange) or pixels (single work-item).
  std::size_t lanes_items() const { return entry_ == KernelEntry::kNdRange ? (n_ + RF_LANES - 1) / RF_LANES : n_; }

  // Runs kernel over `items` (NDRange: work-items, in work-groups whose private arrays fit a CPU runtime's stack;
  // default one per pixel) and waits for it.
  void run(const ::cl::Kernel& kernel) { run(kernel, n_); }
  void run(const ::cl::Kernel& kernel, std::size_t items) {
    cl::enqueue_kernel(device_.queue(), kernel, entry_, items, {work_group_});
    RF_CL_CHECK(device_.queue().finish());
  }

  static constexpr std::size_t kBatch = RF_FRAME_BATCH;
  static constexpr std::size_t kGrayBatch = RF_GRAY_PAIR_BATCH;

  TransportSetup setup_;
  cl::DeviceContext& device_;
  KernelEntry entry_;
  std::size_t n_;
  std::size_t work_group_;     // NDRange work-group size (cl::private_work_group), 0: the runtime's choice
  CompressedTransport state_;  // the kernels' state, shared with them (cl::share) until finish() returns it
  // NDRange entries: the memory that white_ and black_ lend to the kernels (declared before them: outlives them).
  cv::Mat white_frame_, black_frame_;
  ::cl::Kernel gray_pairs_, gray_finalize_, dot_frames_, finalize_;
  // Single work-item entries: the batch of Gray pairs or of dot frames. All Gray pairs come before finish_gray, which
  // decodes the last batch before the first dot frame (the call order of TransportAccumulator).
  ::cl::Buffer batch_, pairs_buffer_, white_, black_, gray_x_, gray_y_, flags_, indices_, weights_, energy_,
      correspondence_;
  // A frame lent to the NDRange entries: the frame and a buffer over its memory (destroyed first).
  struct LentFrame {
    cv::Mat frame;
    ::cl::Buffer buffer;
  };
  std::array<LentFrame, kBatch> lent_;              // the batch's frames (Gray pair p: 2p and 2p + 1)
  std::size_t gray_pending_ = 0;                    // Gray pairs in batch_ or lent_ not yet decoded
  std::array<cl_uint, 2 * kGrayBatch> pairs_ = {};  // their (bit mask, axis)
  std::size_t pending_ = 0;                         // dot frames in batch_ or lent_ not yet compressed
  std::array<cl_int, 2 * kBatch> offsets_ = {};     // their (x, y) dot offsets
};

}  // namespace

std::unique_ptr<GraycodeAccumulator> make_device_accumulator(TransportSetup setup, cl::DeviceContext& device,
                                                             cl::ProgramCache& programs, KernelEntry entry,
                                                             const std::string& build_options,
                                                             CompressedTransport storage) {
  check_kernel_dot_spacing(setup.dot_spacing);
  setup.thresholds = resolve_thresholds(setup.thresholds, 8);
  return std::make_unique<DeviceAccumulator>(setup, device, programs, entry, build_options, std::move(storage));
}

}  // namespace rfrecon::transport
