// Builds OpenCL programs from embedded sources or precompiled binaries, once per device and source.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/opencl.h"

namespace rfrecon::cl {

// Directory of precompiled kernel binaries (FPGA bitstreams); read when a ProgramCache is made without one.
inline constexpr const char* kBinaryDirEnv = "RFRECON_KERNEL_BINARY_DIR";

// The lines prepended to every source built for this device: a comment naming it, RF_TARGET_INTEL_FPGA or
// RF_TARGET_XILINX_FPGA on those boards (kernels/common/target.h), then `#line 1`.
std::string device_preamble(const DeviceInfo& info);

// "selfcheck/axpy.cl" on an Intel FPGA -> "selfcheck_axpy.aocx"; ".xclbin" on Xilinx; ".bin" elsewhere.
std::string binary_file_name(std::string_view kernel_path, const DeviceInfo& info);

// The device's program binary, as clGetProgramInfo(CL_PROGRAM_BINARIES) returns it.
std::vector<unsigned char> program_binary(const ::cl::Program& program);

// Writes program_binary(program) to path atomically.
void save_program_binary(const ::cl::Program& program, const std::filesystem::path& path);

class ProgramCache {
 public:
  // binary_dir: where binaries are looked up; empty means $RFRECON_KERNEL_BINARY_DIR (possibly unset).
  explicit ProgramCache(std::filesystem::path binary_dir = {});

  // The built program for an embedded kernel file. Devices without an online compiler (FPGA boards), and
  // accelerators when a binary directory is set, load binary_dir/binary_file_name(...); others build the
  // embedded source after device_preamble(). Throws BuildError with the log when the build fails.
  ::cl::Program get(DeviceContext& device, std::string_view kernel_path, std::string_view options = {});

  // Builds OpenCL C text directly (the preamble is prepended); cached by device and source hash.
  ::cl::Program build_source(DeviceContext& device, std::string_view name, std::string_view source,
                             std::string_view options = {});

  // clCreateProgramWithBinary + clBuildProgram from a file; throws std::runtime_error naming an unreadable file.
  ::cl::Program build_binary(DeviceContext& device, const std::filesystem::path& path, std::string_view options = {});

  // True when get() would load a binary for this device rather than build from source.
  bool uses_binary(const DeviceInfo& info) const;
  const std::filesystem::path& binary_dir() const { return binary_dir_; }

  // Number of distinct programs built so far (for tests of the cache).
  std::size_t size() const;

 private:
  using Key = std::pair<cl_context, std::uint64_t>;  // programs belong to a context, not a device
  ::cl::Program cached_or_built(DeviceContext& device, std::uint64_t hash, std::string_view name,
                                const std::function<::cl::Program()>& create, std::string_view options);

  std::filesystem::path binary_dir_;
  mutable std::mutex mutex_;
  std::map<Key, ::cl::Program> programs_;
};

}  // namespace rfrecon::cl
