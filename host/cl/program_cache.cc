// Program building, binary round-trips and the per-device program cache.
#include "host/cl/program_cache.h"

#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>

#include "host/cl/error.h"
#include "host/cl/kernel_sources.h"
#include "host/core/atomic_file.h"

namespace rfrecon::cl {

namespace {
// FNV-1a, 64 bit: a stable hash of source text and options for the cache key.
std::uint64_t fnv1a(std::string_view text, std::uint64_t hash = 1469598103934665603ULL) {
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ULL;
  }
  return hash;
}

void build_or_throw(::cl::Program& program, DeviceContext& device, std::string_view name, std::string_view options) {
  const std::string opts(options);
  const cl_int status = program.build(std::vector<::cl::Device>{device.device()}, opts.c_str());
  if (status == CL_SUCCESS) return;
  std::string log;
  program.getBuildInfo(device.device(), CL_PROGRAM_BUILD_LOG, &log);
  throw BuildError(std::string(name), describe(device.info()), status, log, __FILE__, __LINE__);
}
}  // namespace

std::string device_preamble(const DeviceInfo& info) {
  std::string text = "// rfrecon device preamble for " + describe(info) + "\n";
  if (info.intel_fpga) text += "#define RF_TARGET_INTEL_FPGA 1\n";
  if (info.xilinx_fpga) text += "#define RF_TARGET_XILINX_FPGA 1\n";
  text += "#line 1\n";
  return text;
}

std::string binary_file_name(std::string_view kernel_path, const DeviceInfo& info) {
  std::string stem(kernel_path);
  if (const auto dot = stem.rfind(".cl"); dot != std::string::npos && dot + 3 == stem.size()) stem.resize(dot);
  for (char& c : stem) {
    if (c == '/') c = '_';
  }
  if (info.intel_fpga) return stem + ".aocx";
  if (info.xilinx_fpga) return stem + ".xclbin";
  return stem + ".bin";
}

std::vector<unsigned char> program_binary(const ::cl::Program& program) {
  std::vector<std::vector<unsigned char>> binaries;
  RF_CL_CHECK_CODE(program.getInfo(CL_PROGRAM_BINARIES, &binaries), "clGetProgramInfo(CL_PROGRAM_BINARIES)");
  if (binaries.size() != 1 || binaries.front().empty()) {
    throw std::runtime_error("program has no binary for exactly one device (" + std::to_string(binaries.size()) +
                             " binaries)");
  }
  return binaries.front();
}

void save_program_binary(const ::cl::Program& program, const std::filesystem::path& path) {
  const auto bytes = program_binary(program);
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

ProgramCache::ProgramCache(std::filesystem::path binary_dir) : binary_dir_(std::move(binary_dir)) {
  if (binary_dir_.empty()) {
    if (const char* env = std::getenv(kBinaryDirEnv); env != nullptr) binary_dir_ = env;
  }
}

bool ProgramCache::uses_binary(const DeviceInfo& info) const {
  return !info.compiler_available || (!binary_dir_.empty() && info.kind == DeviceKind::kAccelerator);
}

::cl::Program ProgramCache::get(DeviceContext& device, std::string_view kernel_path, std::string_view options) {
  if (uses_binary(device.info())) {
    if (binary_dir_.empty()) {
      throw std::runtime_error(describe(device.info()) + " has no OpenCL compiler: build " +
                               binary_file_name(kernel_path, device.info()) + " from kernels/" +
                               std::string(kernel_path) + " with the vendor's offline compiler (aoc, v++) and set " +
                               kBinaryDirEnv + " to the directory holding it");
    }
    return build_binary(device, binary_dir_ / binary_file_name(kernel_path, device.info()), options);
  }
  return build_source(device, kernel_path, resolve_kernel_source(kernel_path), options);
}

::cl::Program ProgramCache::build_source(DeviceContext& device, std::string_view name, std::string_view source,
                                         std::string_view options) {
  const std::string full = device_preamble(device.info()) + std::string(source);
  return cached_or_built(
      device, fnv1a(full), name,
      [&] {
        cl_int status = CL_SUCCESS;
        ::cl::Program program(device.context(), full, false, &status);
        RF_CL_CHECK_CODE(status, "clCreateProgramWithSource");
        return program;
      },
      options);
}

::cl::Program ProgramCache::build_binary(DeviceContext& device, const std::filesystem::path& path,
                                         std::string_view options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read kernel binary " + path.string());
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty()) throw std::runtime_error("kernel binary " + path.string() + " is empty");
  const std::string_view view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return cached_or_built(
      device, fnv1a(view, fnv1a("binary")), path.string(),
      [&] {
        cl_int status = CL_SUCCESS;
        std::vector<cl_int> binary_status(1, CL_SUCCESS);
        ::cl::Program program(device.context(), {device.device()}, ::cl::Program::Binaries{bytes}, &binary_status,
                              &status);
        if (status == CL_SUCCESS) status = binary_status.front();
        if (status != CL_SUCCESS) {
          throw ClError("clCreateProgramWithBinary(" + path.string() + ")", status, __FILE__, __LINE__,
                        "the binary was not built for " + describe(device.info()));
        }
        return program;
      },
      options);
}

::cl::Program ProgramCache::cached_or_built(DeviceContext& device, std::uint64_t hash, std::string_view name,
                                            const std::function<::cl::Program()>& create, std::string_view options) {
  const Key key{device.context()(), fnv1a(options, hash)};
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = programs_.find(key); it != programs_.end()) return it->second;
  }
  ::cl::Program program = create();
  build_or_throw(program, device, name, options);
  const std::lock_guard<std::mutex> lock(mutex_);
  return programs_.emplace(key, std::move(program)).first->second;
}

std::size_t ProgramCache::size() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return programs_.size();
}

}  // namespace rfrecon::cl
