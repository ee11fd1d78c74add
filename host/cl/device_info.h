// What rfrecon needs to know about an OpenCL device, queried once and printable as text or JSON.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "host/cl/opencl.h"

namespace rfrecon::cl {

enum class DeviceKind { kCpu, kGpu, kAccelerator, kOther };

struct DeviceInfo {
  int index = -1;  // position in enumerate_devices(), stable for one machine configuration
  std::string platform_name;
  std::string platform_vendor;
  std::string device_name;
  std::string device_vendor;
  std::string driver_version;
  DeviceKind kind = DeviceKind::kOther;
  std::uint32_t compute_units = 0;
  std::uint64_t global_mem_bytes = 0;
  std::uint64_t local_mem_bytes = 0;
  std::uint64_t max_alloc_bytes = 0;
  std::size_t max_work_group_size = 0;
  std::string opencl_c_version;
  bool fp64 = false;
  bool fp16 = false;
  bool compiler_available = true;    // false on FPGA boards: programs must come from a precompiled binary
  bool profiling = false;            // queues can time commands
  bool host_unified_memory = false;  // kernels run on the host's memory: a borrowed host range needs no copy
  bool intel_fpga = false;           // platform is Intel's FPGA SDK (aoc binaries)
  bool xilinx_fpga = false;          // platform is AMD/Xilinx XRT (v++ binaries)
  // The emulation an FPGA device is: "" for a board (and any other device), "emulator" for Intel's emulator, "sw_emu"
  // or "hw_emu" for XRT's (detect_fpga_emulation).
  std::string fpga_emulation;
};

DeviceInfo query_device_info(const ::cl::Platform& platform, const ::cl::Device& device, int index);

// What `info` (an FPGA device) emulates: "emulator" on Intel's FPGA emulation platform or device, or with
// CL_CONTEXT_EMULATOR_DEVICE_INTELFPGA set (the legacy emulator of SDK 19.x); XCL_EMULATION_MODE's value on XRT; ""
// otherwise.
std::string detect_fpga_emulation(const DeviceInfo& info);

const char* to_string(DeviceKind kind);

// "pocl 3.1: pthread-skylake (CPU, 2 CU)"
std::string describe(const DeviceInfo& info);

void to_json(nlohmann::json& json, const DeviceInfo& info);

}  // namespace rfrecon::cl
