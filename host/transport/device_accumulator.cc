// The transport accumulator on one OpenCL device: kernels/transport/decode.cl and compress.cl.
#include <stdexcept>
#include <string>

#include "host/cl/error.h"
#include "host/transport/accumulator.h"

namespace rfrecon::transport {

namespace {

template <typename T>
::cl::Buffer make_buffer(cl::DeviceContext& device, std::size_t count) {
  cl_int status = CL_SUCCESS;
  ::cl::Buffer buffer(device.context(), CL_MEM_READ_WRITE, count * sizeof(T), nullptr, &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer");
  return buffer;
}

// Initial contents written from the host (portable: some runtimes, oclgrind included, track clEnqueueFillBuffer
// contents as uninitialized).
template <typename T>
void fill(cl::DeviceContext& device, ::cl::Buffer& buffer, T value, std::size_t count) {
  const std::vector<T> host(count, value);
  RF_CL_CHECK(device.queue().enqueueWriteBuffer(buffer, CL_TRUE, 0, count * sizeof(T), host.data()));
}

template <typename T>
std::vector<T> download(cl::DeviceContext& device, const ::cl::Buffer& buffer, std::size_t count) {
  std::vector<T> host(count);
  RF_CL_CHECK(device.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(T), host.data()));
  return host;
}

class DeviceAccumulator final : public TransportAccumulator {
 public:
  DeviceAccumulator(const TransportSetup& setup, cl::DeviceContext& device, cl::ProgramCache& programs,
                    KernelEntry entry)
      : setup_(setup), device_(device), single_(entry == KernelEntry::kSingleWorkItem), n_(setup.camera_size.area()) {
    if (setup.entries_per_pixel < 1) throw std::invalid_argument("transport: K must be at least 1");
    const std::string suffix = single_ ? "_single" : "_ndrange";
    const ::cl::Program decode = programs.get(device, "transport/decode.cl");
    const ::cl::Program compress =
        programs.get(device, "transport/compress.cl", "-DRF_K=" + std::to_string(setup.entries_per_pixel));
    cl_int status = CL_SUCCESS;
    gray_pair_ = ::cl::Kernel(decode, ("gray_pair" + suffix).c_str(), &status);
    RF_CL_CHECK_CODE(status, "clCreateKernel(gray_pair)");
    gray_finalize_ = ::cl::Kernel(decode, ("gray_finalize" + suffix).c_str(), &status);
    RF_CL_CHECK_CODE(status, "clCreateKernel(gray_finalize)");
    dot_frame_ = ::cl::Kernel(compress, ("dot_frame" + suffix).c_str(), &status);
    RF_CL_CHECK_CODE(status, "clCreateKernel(dot_frame)");
    finalize_ = ::cl::Kernel(compress, ("finalize" + suffix).c_str(), &status);
    RF_CL_CHECK_CODE(status, "clCreateKernel(finalize)");

    const std::size_t slots = n_ * static_cast<std::size_t>(setup.entries_per_pixel);
    frame_a_ = make_buffer<float>(device, n_);
    frame_b_ = make_buffer<float>(device, n_);
    white_ = make_buffer<float>(device, n_);
    black_ = make_buffer<float>(device, n_);
    gray_x_ = make_buffer<cl_uint>(device, n_);
    gray_y_ = make_buffer<cl_uint>(device, n_);
    flags_ = make_buffer<cl_uchar>(device, n_);
    indices_ = make_buffer<cl_int>(device, slots);
    weights_ = make_buffer<float>(device, slots);
    energy_ = make_buffer<float>(device, n_);
    correspondence_ = make_buffer<float>(device, 2 * n_);
    fill<cl_uint>(device, gray_x_, 0, n_);
    fill<cl_uint>(device, gray_y_, 0, n_);
    fill<cl_uchar>(device, flags_, 0, n_);
    fill<cl_int>(device, indices_, -1, slots);
    fill<float>(device, weights_, 0.0f, slots);
    fill<float>(device, energy_, 0.0f, n_);
  }

  void add_gray_pair(GrayAxis axis, int bit, const cv::Mat& pattern, const cv::Mat& inverse) override {
    upload(frame_a_, pattern);
    upload(frame_b_, inverse);
    set_args(gray_pair_, frame_a_, frame_b_, static_cast<cl_uint>(gray_bit_mask(setup_, axis, bit)),
             setup_.thresholds.white, axis == GrayAxis::kColumns ? gray_x_ : gray_y_, flags_, count());
    run(gray_pair_);
  }

  void finish_gray(const cv::Mat& white, const cv::Mat& black) override {
    upload(white_, white);
    upload(black_, black);
    set_args(gray_finalize_, white_, black_, setup_.thresholds.black, setup_.projector_size.width,
             setup_.projector_size.height, gray_x_, gray_y_, flags_, count());
    run(gray_finalize_);
  }

  void add_dot_frame(int offset_x, int offset_y, const cv::Mat& frame) override {
    upload(frame_a_, frame);
    set_args(dot_frame_, frame_a_, black_, offset_x, offset_y, setup_.dot_spacing, setup_.projector_size.width,
             setup_.projector_size.height, setup_.thresholds.noise, flags_, gray_x_, gray_y_, indices_, weights_,
             energy_, count());
    run(dot_frame_);
  }

  CompressedTransport finish() override {
    set_args(finalize_, white_, black_, setup_.dot_spacing > 0 ? 1 : 0, setup_.projector_size.width,
             setup_.thresholds.noise, flags_, gray_x_, gray_y_, indices_, weights_, energy_, correspondence_, count());
    run(finalize_);
    CompressedTransport t;
    t.setup = setup_;
    const std::size_t slots = n_ * static_cast<std::size_t>(setup_.entries_per_pixel);
    t.indices = download<std::int32_t>(device_, indices_, slots);
    t.weights = download<float>(device_, weights_, slots);
    t.correspondence = download<float>(device_, correspondence_, 2 * n_);
    t.gray_x = download<std::uint32_t>(device_, gray_x_, n_);
    t.gray_y = download<std::uint32_t>(device_, gray_y_, n_);
    t.flags = download<std::uint8_t>(device_, flags_, n_);
    t.direct_energy = download<float>(device_, energy_, n_);
    return t;
  }

 private:
  cl_uint count() const { return static_cast<cl_uint>(n_); }

  void upload(::cl::Buffer& buffer, const cv::Mat& frame) {
    if (frame.type() != CV_32FC1 || frame.size() != setup_.camera_size || !frame.isContinuous()) {
      throw std::invalid_argument("transport: frames must be continuous CV_32FC1 of the camera size");
    }
    RF_CL_CHECK(device_.queue().enqueueWriteBuffer(buffer, CL_TRUE, 0, n_ * sizeof(float), frame.ptr<float>()));
  }

  template <typename... Args>
  static void set_args(::cl::Kernel& kernel, const Args&... args) {
    cl_uint index = 0;
    (RF_CL_CHECK(kernel.setArg(index++, args)), ...);
  }

  void run(::cl::Kernel& kernel) {
    const auto global = single_ ? ::cl::NDRange(1) : ::cl::NDRange(n_);
    const auto local = single_ ? ::cl::NDRange(1) : ::cl::NullRange;
    RF_CL_CHECK(device_.queue().enqueueNDRangeKernel(kernel, ::cl::NullRange, global, local));
    RF_CL_CHECK(device_.queue().finish());
  }

  TransportSetup setup_;
  cl::DeviceContext& device_;
  bool single_;
  std::size_t n_;
  ::cl::Kernel gray_pair_, gray_finalize_, dot_frame_, finalize_;
  ::cl::Buffer frame_a_, frame_b_, white_, black_, gray_x_, gray_y_, flags_, indices_, weights_, energy_,
      correspondence_;
};

}  // namespace

std::unique_ptr<TransportAccumulator> make_device_accumulator(TransportSetup setup, cl::DeviceContext& device,
                                                              cl::ProgramCache& programs, KernelEntry entry) {
  setup.thresholds = resolve_thresholds(setup.thresholds, 8);
  return std::make_unique<DeviceAccumulator>(setup, device, programs, entry);
}

}  // namespace rfrecon::transport
