// Running a kernel through either entry, and moving host arrays to and from buffers: the one copy of each idiom.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "host/cl/device_info.h"
#include "host/cl/error.h"
#include "host/cl/kernel_entry.h"
#include "host/cl/opencl.h"

namespace rfrecon::cl {

// The entry's kernel of a file: "<base>_ndrange" or "<base>_single".
std::string kernel_name(std::string_view base, KernelEntry entry);

// That kernel of program; throws ClError naming it.
::cl::Kernel make_kernel(const ::cl::Program& program, std::string_view base, KernelEntry entry);

// Sets kernel's arguments from index `first` on, in order.
template <typename... Args>
void set_args_from(::cl::Kernel& kernel, cl_uint first, const Args&... args) {
  [[maybe_unused]] cl_uint index = first;
  (RF_CL_CHECK(kernel.setArg(index++, args)), ...);
}

// Sets all of kernel's arguments, in order from index 0.
template <typename... Args>
void set_args(::cl::Kernel& kernel, const Args&... args) {
  set_args_from(kernel, 0, args...);
}

struct LaunchOptions {
  // 0: NDRange(items), work-groups left to the runtime. Otherwise work-groups of this size and the global size
  // rounded up to a multiple of it (the kernel skips ids >= its item count).
  std::size_t work_group = 0;
  const std::vector<::cl::Event>* wait = nullptr;  // run after these events
  ::cl::Event* done = nullptr;                     // receives the kernel's completion event
};

// CPU runtimes (PoCL) keep a work-group's private arrays on one worker thread's stack, and their own choice of
// work-group (up to 4096 work-items) overflows it for kernels with large arrays (the compression at K = 64). The
// largest work-group whose private arrays, `private_bytes_per_item` each, stay within kCpuWorkGroupPrivateBytes: a
// power of two, at least 1 and at most the device's limit. 0 (the runtime's choice) on GPUs and accelerators, whose
// runtimes size work-groups from the kernel's real private memory.
inline constexpr std::size_t kCpuWorkGroupPrivateBytes = std::size_t{1} << 20;
std::size_t private_work_group(const DeviceInfo& device, std::size_t private_bytes_per_item);

// Enqueues kernel for `items` items: one work-item per item (kNdRange) or one work-item in all (kSingleWorkItem,
// global and local size 1: the kernel loops over the items).
void enqueue_kernel(::cl::CommandQueue& queue, const ::cl::Kernel& kernel, KernelEntry entry, std::size_t items,
                    const LaunchOptions& options = {});

namespace detail {
// bytes == 0 makes a buffer of min_bytes (zero-sized buffers are invalid), copied from fill when it is not null.
::cl::Buffer create_buffer(const ::cl::Context& context, cl_mem_flags flags, std::size_t bytes, const void* host,
                           std::size_t min_bytes, const void* fill);
void write_bytes(::cl::CommandQueue& queue, const ::cl::Buffer& buffer, const void* data, std::size_t bytes,
                 bool blocking, std::size_t offset_bytes);
void read_bytes(::cl::CommandQueue& queue, const ::cl::Buffer& buffer, void* data, std::size_t bytes);
::cl::Buffer host_ptr_buffer(const ::cl::Context& context, cl_mem_flags flags, void* data, std::size_t bytes);
}  // namespace detail

// A buffer of `count` elements of T (at least one), contents undefined.
template <typename T>
::cl::Buffer make_buffer(const ::cl::Context& context, std::size_t count, cl_mem_flags flags = CL_MEM_READ_WRITE) {
  return detail::create_buffer(context, flags, count * sizeof(T), nullptr, sizeof(T), nullptr);
}

// A new buffer holding a copy of data[0, count) (CL_MEM_COPY_HOST_PTR is added to flags). An empty range gets one
// zero element, never read by the kernels.
template <typename T>
::cl::Buffer upload(const ::cl::Context& context, const T* data, std::size_t count,
                    cl_mem_flags flags = CL_MEM_READ_ONLY) {
  const T zero{};
  return detail::create_buffer(context, flags, count * sizeof(T), data, sizeof(T), &zero);
}
template <typename T>
::cl::Buffer upload(const ::cl::Context& context, const std::vector<T>& host, cl_mem_flags flags = CL_MEM_READ_ONLY) {
  return upload(context, host.data(), host.size(), flags);
}

// A read-only buffer over the caller's data[0, count) (CL_MEM_USE_HOST_PTR, count > 0): CPU runtimes that run
// kernels on host memory (PoCL) read it in place, without a copy; others copy it when a kernel needs it. Keep data
// alive and unchanged until every command reading the buffer has run.
template <typename T>
::cl::Buffer borrow(const ::cl::Context& context, const T* data, std::size_t count) {
  // The kernels only read it (CL_MEM_READ_ONLY), so the const_cast never leads to a write.
  return detail::host_ptr_buffer(context, CL_MEM_READ_ONLY, const_cast<T*>(data), count * sizeof(T));
}

// A read-write buffer over the caller's data[0, count) (CL_MEM_USE_HOST_PTR, count > 0), initial contents and all:
// runtimes that run kernels on host memory (PoCL) work on it in place, others on a copy. The host must leave data
// alone while the buffer lives, until sync_to_host() has made it hold the kernels' results.
template <typename T>
::cl::Buffer share(const ::cl::Context& context, std::vector<T>& data) {
  return detail::host_ptr_buffer(context, CL_MEM_READ_WRITE, data.data(), data.size() * sizeof(T));
}

// Waits for the queue, then makes the host memory of a share()d buffer hold its contents (a map and unmap: no copy
// where the kernels ran on that memory).
void sync_to_host(::cl::CommandQueue& queue, const ::cl::Buffer& buffer);

// Writes data[0, count) to buffer from element `offset` on; nothing for count 0. A non-blocking write reads data
// later: keep it alive until the queue has run the write.
template <typename T>
void write_buffer(::cl::CommandQueue& queue, const ::cl::Buffer& buffer, const T* data, std::size_t count,
                  bool blocking = true, std::size_t offset = 0) {
  detail::write_bytes(queue, buffer, data, count * sizeof(T), blocking, offset * sizeof(T));
}

// Blocking reads of the first `count` elements of buffer: into data, or into a new vector.
template <typename T>
void read_buffer(::cl::CommandQueue& queue, const ::cl::Buffer& buffer, T* data, std::size_t count) {
  detail::read_bytes(queue, buffer, data, count * sizeof(T));
}
template <typename T>
std::vector<T> download(::cl::CommandQueue& queue, const ::cl::Buffer& buffer, std::size_t count) {
  std::vector<T> host(count);
  read_buffer(queue, buffer, host.data(), count);
  return host;
}

// A buffer reused for inputs of varying size (tiles): reallocated only when a larger one is asked for.
class GrowingBuffer {
 public:
  // The buffer, at least `bytes` (and 4) bytes large; flags apply when it is reallocated.
  ::cl::Buffer& at_least(const ::cl::Context& context, std::size_t bytes, cl_mem_flags flags);
  const ::cl::Buffer& buffer() const { return buffer_; }
  // A buffer over data[0, count) instead (cl::borrow), until the next at_least reallocates.
  template <typename T>
  void lend(const ::cl::Context& context, const T* data, std::size_t count) {
    buffer_ = borrow(context, data, count);
    capacity_ = 0;
  }

 private:
  ::cl::Buffer buffer_;
  std::size_t capacity_ = 0;
};

}  // namespace rfrecon::cl
