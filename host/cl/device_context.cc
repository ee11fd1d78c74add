// Platform and device enumeration and per-device context/queue creation.
#include "host/cl/device_context.h"

#include <cstddef>
#include <mutex>

#include <pthread.h>

#include "host/cl/error.h"

namespace rfrecon::cl {

bool reserve_private_bytes(std::size_t bytes) noexcept {
#ifdef __GLIBC__
  static std::mutex mutex;
  const std::scoped_lock lock(mutex);
  const std::size_t wanted = bytes + (std::size_t{8} << 20);  // address space: pages are committed when touched
  pthread_attr_t attributes;
  if (pthread_getattr_default_np(&attributes) != 0) return true;
  std::size_t size = 0;
  if (pthread_attr_getstacksize(&attributes, &size) == 0 && size < wanted &&
      pthread_attr_setstacksize(&attributes, wanted) == 0) {
    pthread_setattr_default_np(&attributes);
  }
  pthread_attr_destroy(&attributes);
#else
  (void)bytes;
#endif
  return true;
}

std::vector<DeviceEntry> enumerate_devices() {
  std::vector<::cl::Platform> platforms;
  const cl_int status = ::cl::Platform::get(&platforms);
  if (status == CL_PLATFORM_NOT_FOUND_KHR || platforms.empty()) return {};
  RF_CL_CHECK_CODE(status, "clGetPlatformIDs");
  std::vector<DeviceEntry> entries;
  for (const auto& platform : platforms) {
    std::vector<::cl::Device> devices;
    const cl_int device_status = platform.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    if (device_status == CL_DEVICE_NOT_FOUND) continue;
    RF_CL_CHECK_CODE(device_status, "clGetDeviceIDs");
    for (const auto& device : devices) {
      const int index = static_cast<int>(entries.size());
      entries.push_back({platform, device, query_device_info(platform, device, index)});
    }
  }
  return entries;
}

DeviceContext::DeviceContext(const DeviceEntry& entry) : info_(entry.info), device_(entry.device) {
  cl_int status = CL_SUCCESS;
  const cl_context_properties properties[] = {CL_CONTEXT_PLATFORM,
                                              reinterpret_cast<cl_context_properties>(entry.platform()), 0};
  context_ = ::cl::Context(device_, properties, nullptr, nullptr, &status);
  RF_CL_CHECK_CODE(status, "clCreateContext");
  const cl_command_queue_properties queue_properties = info_.profiling ? CL_QUEUE_PROFILING_ENABLE : 0;
  queue_ = ::cl::CommandQueue(context_, device_, queue_properties, &status);
  RF_CL_CHECK_CODE(status, "clCreateCommandQueue");
}

}  // namespace rfrecon::cl
