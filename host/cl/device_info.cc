// Queries device properties through the OpenCL C++ bindings.
#include "host/cl/device_info.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include <nlohmann/json.hpp>

#include "host/cl/error.h"

namespace rfrecon::cl {

namespace {
template <cl_device_info Name>
auto device_param(const ::cl::Device& device) {
  typename ::cl::detail::param_traits<::cl::detail::cl_device_info, Name>::param_type value{};
  RF_CL_CHECK_CODE(device.getInfo(Name, &value), "clGetDeviceInfo");
  return value;
}

std::string without_trailing_nul_or_space(std::string text) {
  while (!text.empty() && (text.back() == '\0' || std::isspace(static_cast<unsigned char>(text.back())))) {
    text.pop_back();
  }
  return text;
}

bool contains_ci(std::string haystack, std::string needle) {
  auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
  };
  return lower(std::move(haystack)).find(lower(std::move(needle))) != std::string::npos;
}
}  // namespace

DeviceInfo query_device_info(const ::cl::Platform& platform, const ::cl::Device& device, int index) {
  DeviceInfo info;
  info.index = index;
  std::string text;
  RF_CL_CHECK_CODE(platform.getInfo(CL_PLATFORM_NAME, &text), "clGetPlatformInfo(CL_PLATFORM_NAME)");
  info.platform_name = without_trailing_nul_or_space(text);
  RF_CL_CHECK_CODE(platform.getInfo(CL_PLATFORM_VENDOR, &text), "clGetPlatformInfo(CL_PLATFORM_VENDOR)");
  info.platform_vendor = without_trailing_nul_or_space(text);
  info.device_name = without_trailing_nul_or_space(device_param<CL_DEVICE_NAME>(device));
  info.device_vendor = without_trailing_nul_or_space(device_param<CL_DEVICE_VENDOR>(device));
  info.driver_version = without_trailing_nul_or_space(device_param<CL_DRIVER_VERSION>(device));
  const cl_device_type type = device_param<CL_DEVICE_TYPE>(device);
  if (type & CL_DEVICE_TYPE_CPU) {
    info.kind = DeviceKind::kCpu;
  } else if (type & CL_DEVICE_TYPE_GPU) {
    info.kind = DeviceKind::kGpu;
  } else if (type & CL_DEVICE_TYPE_ACCELERATOR) {
    info.kind = DeviceKind::kAccelerator;
  }
  info.compute_units = device_param<CL_DEVICE_MAX_COMPUTE_UNITS>(device);
  info.global_mem_bytes = device_param<CL_DEVICE_GLOBAL_MEM_SIZE>(device);
  info.local_mem_bytes = device_param<CL_DEVICE_LOCAL_MEM_SIZE>(device);
  info.max_alloc_bytes = device_param<CL_DEVICE_MAX_MEM_ALLOC_SIZE>(device);
  info.max_work_group_size = device_param<CL_DEVICE_MAX_WORK_GROUP_SIZE>(device);
  info.opencl_c_version = without_trailing_nul_or_space(device_param<CL_DEVICE_OPENCL_C_VERSION>(device));
  info.fp64 = device_param<CL_DEVICE_DOUBLE_FP_CONFIG>(device) != 0;
  const std::string extensions = device_param<CL_DEVICE_EXTENSIONS>(device);
  info.fp16 = extensions.find("cl_khr_fp16") != std::string::npos;
  info.compiler_available = device_param<CL_DEVICE_COMPILER_AVAILABLE>(device) == CL_TRUE;
  info.profiling = (device_param<CL_DEVICE_QUEUE_PROPERTIES>(device) & CL_QUEUE_PROFILING_ENABLE) != 0;
  info.host_unified_memory = device_param<CL_DEVICE_HOST_UNIFIED_MEMORY>(device) == CL_TRUE;
  info.intel_fpga = contains_ci(info.platform_name, "FPGA") && contains_ci(info.platform_vendor, "Intel");
  info.xilinx_fpga = contains_ci(info.platform_vendor, "Xilinx") || contains_ci(info.platform_name, "Xilinx");
  info.fpga_emulation = detect_fpga_emulation(info);
  return info;
}

std::string detect_fpga_emulation(const DeviceInfo& info) {
  const auto variable = [](const char* name) {
    const char* value = std::getenv(name);
    return std::string(value != nullptr ? value : "");
  };
  if (info.intel_fpga && (contains_ci(info.platform_name, "Emulat") || contains_ci(info.device_name, "Emulat") ||
                          !variable("CL_CONTEXT_EMULATOR_DEVICE_INTELFPGA").empty())) {
    return "emulator";
  }
  if (info.xilinx_fpga) return variable("XCL_EMULATION_MODE");
  return "";
}

const char* to_string(DeviceKind kind) {
  switch (kind) {
    case DeviceKind::kCpu:
      return "CPU";
    case DeviceKind::kGpu:
      return "GPU";
    case DeviceKind::kAccelerator:
      return "accelerator";
    case DeviceKind::kOther:
      break;
  }
  return "other";
}

std::string describe(const DeviceInfo& info) {
  return info.platform_name + ": " + info.device_name + " (" + to_string(info.kind) + ", " +
         std::to_string(info.compute_units) + " CU)";
}

void to_json(nlohmann::json& json, const DeviceInfo& info) {
  json = nlohmann::json{{"index", info.index},
                        {"platform", info.platform_name},
                        {"platform_vendor", info.platform_vendor},
                        {"device", info.device_name},
                        {"device_vendor", info.device_vendor},
                        {"driver_version", info.driver_version},
                        {"type", to_string(info.kind)},
                        {"compute_units", info.compute_units},
                        {"global_mem_bytes", info.global_mem_bytes},
                        {"local_mem_bytes", info.local_mem_bytes},
                        {"max_alloc_bytes", info.max_alloc_bytes},
                        {"max_work_group_size", info.max_work_group_size},
                        {"opencl_c_version", info.opencl_c_version},
                        {"fp64", info.fp64},
                        {"fp16", info.fp16},
                        {"compiler_available", info.compiler_available},
                        {"profiling", info.profiling},
                        {"host_unified_memory", info.host_unified_memory}};
}

}  // namespace rfrecon::cl
