// The transport accumulator on one OpenCL device: kernels/transport/decode.cl and compress.cl. The transport's own
// arrays are the kernels' state; NDRange entries read each frame where it lies (raw samples made linear in the
// kernels), single work-item ones take batches of linear frames.
#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <utility>

#include "host/cl/kernel_launch.h"
#include "host/transport/device_frames.h"
#include "host/transport/graycode_accumulator.h"
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
        // Single work-item entries take a launch's frames in one buffer (dot frames, or Gray pairs' two frames each).
        frames_(setup, device, entry, setup.dot_spacing > 0 ? kBatch : 2 * kGrayBatch,
                transport_private_bytes(setup.entries_per_pixel)),
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
    pairs_buffer_ = cl::make_buffer<cl_uint>(context, pairs_.size());
    // The transport's own arrays, in their initial state, are the kernels' state: no copy in or out on runtimes that
    // run kernels on host memory. T's rows come with the first dot frame or finish() (share_rows).
    code_x_ = cl::share(context, state_.pixel_x);
    code_y_ = cl::share(context, state_.pixel_y);
    flags_ = cl::share(context, state_.flags);
    energy_ = cl::share(context, state_.direct_energy);
    correspondence_ = cl::share(context, state_.correspondence);
  }

  void add_gray_pair(GrayAxis axis, int bit, const cv::Mat& pattern, const cv::Mat& inverse) override {
    frames_.add(2 * gray_pending_, pattern);
    frames_.add(2 * gray_pending_ + 1, inverse);
    pairs_[2 * gray_pending_] = gray_bit_mask(setup_, axis, bit);
    pairs_[2 * gray_pending_ + 1] = axis == GrayAxis::kColumns ? 0 : 1;
    if (++gray_pending_ == kGrayBatch) decode_batch();
  }

  void finish_gray(const cv::Mat& white, const cv::Mat& black) override {
    if (gray_pending_ > 0) decode_batch();
    frames_.set_white_black(white, black);
    cl::set_args(gray_finalize_, frames_.white(), frames_.black(), setup_.thresholds.black, setup_.projector_size.width,
                 setup_.projector_size.height, code_x_, code_y_, flags_, frames_.count());
    frames_.run(gray_finalize_, frames_.lanes_items());
  }

  void add_dot_frame(int offset_x, int offset_y, const cv::Mat& frame) override {
    check_dot_offsets(setup_, offset_x, offset_y);
    frames_.add(pending_, frame);
    offsets_[2 * pending_] = offset_x;
    offsets_[2 * pending_ + 1] = offset_y;
    if (++pending_ == kBatch) compress_batch();
  }

  CompressedTransport finish() override {
    if (pending_ > 0) compress_batch();
    share_rows();
    cl::set_args(finalize_, frames_.white(), frames_.black(), setup_.dot_spacing > 0 ? 1 : 0,
                 setup_.projector_size.width, setup_.thresholds.noise, flags_, code_x_, code_y_, indices_, weights_,
                 energy_, correspondence_, frames_.count());
    frames_.run(finalize_, frames_.count());
    for (const auto* buffer : {&code_x_, &code_y_, &flags_, &indices_, &weights_, &energy_, &correspondence_}) {
      cl::sync_to_host(device_.queue(), *buffer);
    }
    code_x_ = code_y_ = flags_ = indices_ = weights_ = energy_ = correspondence_ = ::cl::Buffer();
    frames_.release();
    return std::move(state_);
  }

 private:
  // One launch over the pending Gray pairs; unused slots stay 0 (the kernel skips those pairs).
  void decode_batch() {
    // Not blocking: the in-order queue writes it before the launch, and run() waits for both before pairs_ changes.
    cl::write_buffer(device_.queue(), pairs_buffer_, pairs_.data(), pairs_.size(), false);
    const cl_uint next = frames_.set_arguments(gray_pairs_, 2 * gray_pending_);
    cl::set_args_from(gray_pairs_, next, static_cast<cl_int>(gray_pending_), pairs_buffer_, setup_.thresholds.white,
                      code_x_, code_y_, flags_, frames_.count());
    frames_.run_batch(gray_pairs_);
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
    frames_.run_dot_frames(dot_frames_, pending_, offsets_, fresh,
                           {flags_, code_x_, code_y_, indices_, weights_, energy_});
    pending_ = 0;
    offsets_.fill(0);
  }

  static constexpr std::size_t kBatch = RF_FRAME_BATCH;
  static constexpr std::size_t kGrayBatch = RF_GRAY_PAIR_BATCH;

  TransportSetup setup_;
  cl::DeviceContext& device_;
  KernelEntry entry_;
  // The batch of Gray pairs (pair p: frames 2p and 2p + 1) or of dot frames. All Gray pairs come before finish_gray,
  // which decodes the last batch before the first dot frame (the call order of TransportAccumulator).
  DeviceFrames frames_;
  CompressedTransport state_;  // the kernels' state, shared with them (cl::share) until finish() returns it
  ::cl::Kernel gray_pairs_, gray_finalize_, dot_frames_, finalize_;
  ::cl::Buffer pairs_buffer_, code_x_, code_y_, flags_, indices_, weights_, energy_, correspondence_;
  std::size_t gray_pending_ = 0;                               // Gray pairs in the batch not yet decoded
  std::array<cl_uint, 2 * kGrayBatch> pairs_ = {};             // their (bit mask, axis)
  std::size_t pending_ = 0;                                    // dot frames in the batch not yet compressed
  std::array<cl_int, 2 * DeviceFrames::kSlots> offsets_ = {};  // their (x, y) dot offsets
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
