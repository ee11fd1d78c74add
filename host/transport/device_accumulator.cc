// The transport accumulator on one OpenCL device: kernels/transport/decode.cl and compress.cl, dot frames gathered
// into batches of RF_FRAME_BATCH on the device before each compression launch.
#include <array>
#include <stdexcept>
#include <string>

#include "host/cl/kernel_launch.h"
#include "host/transport/accumulator.h"

namespace rfrecon::transport {

namespace {

class DeviceAccumulator final : public TransportAccumulator {
 public:
  DeviceAccumulator(const TransportSetup& setup, cl::DeviceContext& device, cl::ProgramCache& programs,
                    KernelEntry entry, const std::string& build_options)
      : setup_(setup), device_(device), entry_(entry), n_(setup.camera_size.area()) {
    if (setup.entries_per_pixel < 1) throw std::invalid_argument("transport: K must be at least 1");
    const ::cl::Program decode = programs.get(device, "transport/decode.cl", build_options);
    const ::cl::Program compress =
        programs.get(device, "transport/compress.cl", transport_build_options(setup.entries_per_pixel, build_options));
    gray_pair_ = cl::make_kernel(decode, "gray_pair", entry);
    gray_finalize_ = cl::make_kernel(decode, "gray_finalize", entry);
    dot_frames_ = cl::make_kernel(compress, "dot_frames", entry);
    finalize_ = cl::make_kernel(compress, "finalize", entry);

    const std::size_t slots = n_ * static_cast<std::size_t>(setup.entries_per_pixel);
    const ::cl::Context& context = device.context();
    frame_a_ = cl::make_buffer<float>(context, n_);
    frame_b_ = cl::make_buffer<float>(context, n_);
    if (setup.dot_spacing > 0) batch_ = cl::make_buffer<float>(context, kBatch * n_);
    white_ = cl::make_buffer<float>(context, n_);
    black_ = cl::make_buffer<float>(context, n_);
    correspondence_ = cl::make_buffer<float>(context, 2 * n_);
    // Initial contents copied from the host (portable: some runtimes, oclgrind included, track clEnqueueFillBuffer
    // contents as uninitialized).
    gray_x_ = initialized<cl_uint>(0, n_);
    gray_y_ = initialized<cl_uint>(0, n_);
    flags_ = initialized<cl_uchar>(0, n_);
    indices_ = initialized<cl_int>(-1, slots);
    weights_ = initialized<float>(0.0f, slots);
    energy_ = initialized<float>(0.0f, n_);
  }

  void add_gray_pair(GrayAxis axis, int bit, const cv::Mat& pattern, const cv::Mat& inverse) override {
    upload(frame_a_, pattern);
    upload(frame_b_, inverse);
    cl::set_args(gray_pair_, frame_a_, frame_b_, static_cast<cl_uint>(gray_bit_mask(setup_, axis, bit)),
                 setup_.thresholds.white, axis == GrayAxis::kColumns ? gray_x_ : gray_y_, flags_, count());
    run(gray_pair_);
  }

  void finish_gray(const cv::Mat& white, const cv::Mat& black) override {
    upload(white_, white);
    upload(black_, black);
    cl::set_args(gray_finalize_, white_, black_, setup_.thresholds.black, setup_.projector_size.width,
                 setup_.projector_size.height, gray_x_, gray_y_, flags_, count());
    run(gray_finalize_);
  }

  void add_dot_frame(int offset_x, int offset_y, const cv::Mat& frame) override {
    check_dot_offsets(setup_, offset_x, offset_y);
    upload(batch_, frame, pending_ * n_);
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
    CompressedTransport t;
    t.setup = setup_;
    const std::size_t slots = n_ * static_cast<std::size_t>(setup_.entries_per_pixel);
    t.indices = cl::download<std::int32_t>(device_.queue(), indices_, slots);
    t.weights = cl::download<float>(device_.queue(), weights_, slots);
    t.correspondence = cl::download<float>(device_.queue(), correspondence_, 2 * n_);
    t.gray_x = cl::download<std::uint32_t>(device_.queue(), gray_x_, n_);
    t.gray_y = cl::download<std::uint32_t>(device_.queue(), gray_y_, n_);
    t.flags = cl::download<std::uint8_t>(device_.queue(), flags_, n_);
    t.direct_energy = cl::download<float>(device_.queue(), energy_, n_);
    return t;
  }

 private:
  cl_uint count() const { return static_cast<cl_uint>(n_); }

  template <typename T>
  ::cl::Buffer initialized(T value, std::size_t elements) const {
    return cl::upload(device_.context(), std::vector<T>(elements, value), CL_MEM_READ_WRITE);
  }

  void upload(const ::cl::Buffer& buffer, const cv::Mat& frame, std::size_t offset = 0) {
    if (frame.type() != CV_32FC1 || frame.size() != setup_.camera_size || !frame.isContinuous()) {
      throw std::invalid_argument("transport: frames must be continuous CV_32FC1 of the camera size");
    }
    cl::write_buffer(device_.queue(), buffer, frame.ptr<float>(), n_, true, offset);
  }

  // One launch over the pending frames; offsets of unused batch slots stay 0 (the kernel skips those frames).
  void compress_batch() {
    const ::cl::Buffer offsets = cl::upload(device_.context(), offsets_.data(), offsets_.size());
    cl::set_args(dot_frames_, batch_, static_cast<cl_int>(pending_), offsets, setup_.dot_spacing,
                 setup_.projector_size.width, setup_.projector_size.height, setup_.thresholds.noise, black_, flags_,
                 gray_x_, gray_y_, indices_, weights_, energy_, count());
    run(dot_frames_);
    pending_ = 0;
    offsets_.fill(0);
  }

  void run(const ::cl::Kernel& kernel) {
    cl::enqueue_kernel(device_.queue(), kernel, entry_, n_);
    RF_CL_CHECK(device_.queue().finish());
  }

  static constexpr std::size_t kBatch = RF_FRAME_BATCH;

  TransportSetup setup_;
  cl::DeviceContext& device_;
  KernelEntry entry_;
  std::size_t n_;
  ::cl::Kernel gray_pair_, gray_finalize_, dot_frames_, finalize_;
  ::cl::Buffer frame_a_, frame_b_, batch_, white_, black_, gray_x_, gray_y_, flags_, indices_, weights_, energy_,
      correspondence_;
  std::size_t pending_ = 0;                      // frames in batch_ not yet compressed
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
