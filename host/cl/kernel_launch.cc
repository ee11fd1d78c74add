// Kernel names and sizes of the two entries, and the buffer calls behind the templates of kernel_launch.h.
#include "host/cl/kernel_launch.h"

#include <algorithm>
#include <stdexcept>

namespace rfrecon::cl {

std::string kernel_name(std::string_view base, KernelEntry entry) {
  return std::string(base) + (entry == KernelEntry::kSingleWorkItem ? "_single" : "_ndrange");
}

::cl::Kernel make_kernel(const ::cl::Program& program, std::string_view base, KernelEntry entry) {
  const std::string name = kernel_name(base, entry);
  cl_int status = CL_SUCCESS;
  ::cl::Kernel kernel(program, name.c_str(), &status);
  RF_CL_CHECK_CODE(status, ("clCreateKernel(" + name + ")").c_str());
  return kernel;
}

void enqueue_kernel(::cl::CommandQueue& queue, const ::cl::Kernel& kernel, KernelEntry entry, std::size_t items,
                    const LaunchOptions& options) {
  ::cl::NDRange global(1);
  ::cl::NDRange local(1);
  if (entry == KernelEntry::kNdRange) {
    const std::size_t group = options.work_group;
    global = ::cl::NDRange(group == 0 ? items : (items + group - 1) / group * group);
    local = group == 0 ? ::cl::NullRange : ::cl::NDRange(group);
  }
  RF_CL_CHECK(queue.enqueueNDRangeKernel(kernel, ::cl::NullRange, global, local, options.wait, options.done));
}

std::size_t private_work_group(const DeviceInfo& device, std::size_t private_bytes_per_item) {
  if (device.kind != DeviceKind::kCpu) return 0;
  const std::size_t fitting = kCpuWorkGroupPrivateBytes / std::max<std::size_t>(private_bytes_per_item, 1);
  const std::size_t limit = std::max<std::size_t>(std::min(fitting, device.max_work_group_size), 1);
  std::size_t group = 1;
  while (group * 2 <= limit) group *= 2;
  return group;
}

namespace detail {

::cl::Buffer create_buffer(const ::cl::Context& context, cl_mem_flags flags, std::size_t bytes, const void* host,
                           std::size_t min_bytes, const void* fill) {
  if (bytes == 0) {
    bytes = min_bytes;
    host = fill;
  }
  if (host != nullptr) flags |= CL_MEM_COPY_HOST_PTR;
  cl_int status = CL_SUCCESS;
  ::cl::Buffer buffer(context, flags, bytes, const_cast<void*>(host), &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer");
  return buffer;
}

::cl::Buffer host_ptr_buffer(const ::cl::Context& context, cl_mem_flags flags, void* data, std::size_t bytes) {
  if (bytes == 0 || data == nullptr) throw std::invalid_argument("cl::borrow/share: an empty range");
  cl_int status = CL_SUCCESS;
  ::cl::Buffer buffer(context, flags | CL_MEM_USE_HOST_PTR, bytes, data, &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer (CL_MEM_USE_HOST_PTR)");
  return buffer;
}

}  // namespace detail

void sync_to_host(::cl::CommandQueue& queue, const ::cl::Buffer& buffer) {
  cl_int status = CL_SUCCESS;
  const auto bytes = buffer.getInfo<CL_MEM_SIZE>(&status);
  RF_CL_CHECK_CODE(status, "clGetMemObjectInfo(CL_MEM_SIZE)");
  void* mapped = queue.enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes, nullptr, nullptr, &status);
  RF_CL_CHECK_CODE(status, "clEnqueueMapBuffer");
  RF_CL_CHECK(queue.enqueueUnmapMemObject(buffer, mapped));
  RF_CL_CHECK(queue.finish());
}

namespace detail {

void write_bytes(::cl::CommandQueue& queue, const ::cl::Buffer& buffer, const void* data, std::size_t bytes,
                 bool blocking, std::size_t offset_bytes) {
  if (bytes > 0) {
    RF_CL_CHECK(queue.enqueueWriteBuffer(buffer, blocking ? CL_TRUE : CL_FALSE, offset_bytes, bytes, data));
  }
}

void read_bytes(::cl::CommandQueue& queue, const ::cl::Buffer& buffer, void* data, std::size_t bytes) {
  if (bytes > 0) RF_CL_CHECK(queue.enqueueReadBuffer(buffer, CL_TRUE, 0, bytes, data));
}

}  // namespace detail

::cl::Buffer& GrowingBuffer::at_least(const ::cl::Context& context, std::size_t bytes, cl_mem_flags flags) {
  bytes = std::max<std::size_t>(bytes, 4);
  if (bytes > capacity_) {
    buffer_ = detail::create_buffer(context, flags, bytes, nullptr, 0, nullptr);
    capacity_ = bytes;
  }
  return buffer_;
}

}  // namespace rfrecon::cl
