// Program building, binary round-trips and the per-device program cache.
#include "host/cl/program_cache.h"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <future>
#include <iterator>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

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

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  if (const std::string macro = target_macro(info); !macro.empty()) text += "#define " + macro + " 1\n";
  text += "#line 1\n";
  return text;
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

ProgramCache::ProgramCache(std::filesystem::path binary, ProgramStore store)
    : binary_location_(std::move(binary)), store_(std::move(store)) {
  for (const char* variable : {kBinaryEnv, kBinaryDirEnv}) {
    const char* env = std::getenv(variable);
    if (binary_location_.empty() && env != nullptr && *env != '\0') binary_location_ = env;
  }
}

bool ProgramCache::uses_binary(const DeviceInfo& info) const {
  return !info.compiler_available || (!binary_location_.empty() && info.kind == DeviceKind::kAccelerator);
}

::cl::Program ProgramCache::get(DeviceContext& device, std::string_view kernel_path, std::string_view options) {
  if (uses_binary(device.info())) {
    if (binary_location_.empty()) {
      throw ClError("loading kernels/" + std::string(kernel_path), CL_COMPILER_NOT_AVAILABLE, __FILE__, __LINE__,
                    describe(device.info()) + " has no OpenCL compiler: build the board binary with the hw/ flows " +
                        "(docs/fpga.md) and set " + kBinaryEnv + " to it");
    }
    const BoardProgram& board = board_program(device);
    check_options_match_manifest(board.manifest, options);
    return board.program;
  }
  // The embedded source does not change while the process runs: a request seen before skips its resolution and hash.
  const Request request{device.context()(), std::string(kernel_path) + '\n' + std::string(options)};
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = requests_.find(request); it != requests_.end()) return it->second;
  }
  ::cl::Program program = build_source(device, kernel_path, resolve_kernel_source(kernel_path), options);
  const std::lock_guard<std::mutex> lock(mutex_);
  return requests_.emplace(request, std::move(program)).first->second;
}

const ProgramCache::BoardProgram& ProgramCache::board_program(DeviceContext& device) {
  const std::lock_guard<std::mutex> lock(board_mutex_);
  if (const auto it = boards_.find(device.context()()); it != boards_.end()) return it->second;
  const std::filesystem::path binary = find_board_binary(binary_location_);
  BinaryManifest manifest = check_binary_manifest(binary, host_manifest_expectation(device.info()));
  if (!manifest.extra_flags.empty()) {
    spdlog::info("kernel binary {} was compiled with the extra flags {}", binary.string(), manifest.extra_flags.dump());
  }
  ::cl::Program program = build_binary(device, binary);
  return boards_.emplace(device.context()(), BoardProgram{std::move(manifest), std::move(program)}).first->second;
}

::cl::Program ProgramCache::build_source(DeviceContext& device, std::string_view name, std::string_view source,
                                         std::string_view options) {
  const std::string full = device_preamble(device.info()) + std::string(source);
  // The store's key names the device and its driver besides the source and options: a binary is for one of each.
  const DeviceInfo& info = device.info();
  const std::uint64_t store_key =
      fnv1a(options, fnv1a(full, fnv1a(info.platform_name + '\n' + info.device_name + '\n' + info.driver_version)));
  return cached_or_built(
      device, fnv1a(full), name,
      [&] {
        cl_int status = CL_SUCCESS;
        ::cl::Program program(device.context(), full, false, &status);
        RF_CL_CHECK_CODE(status, "clCreateProgramWithSource");
        return program;
      },
      options, store_key);
}

::cl::Program ProgramCache::load_stored(DeviceContext& device, std::uint64_t key, std::string_view options) {
  const auto bytes = store_.load(key);
  if (!bytes) return {};
  cl_int status = CL_SUCCESS;
  std::vector<cl_int> binary_status(1, CL_SUCCESS);
  ::cl::Program program(device.context(), {device.device()}, ::cl::Program::Binaries{*bytes}, &binary_status, &status);
  const std::string opts(options);
  if (status == CL_SUCCESS && binary_status.front() == CL_SUCCESS &&
      program.build(std::vector<::cl::Device>{device.device()}, opts.c_str()) == CL_SUCCESS) {
    return program;
  }
  spdlog::debug("program cache: the stored binary {:016x} does not load on {}; building from source", key,
                describe(device.info()));
  return {};
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
      options, 0);
}

::cl::Program ProgramCache::cached_or_built(DeviceContext& device, std::uint64_t hash, std::string_view name,
                                            const std::function<::cl::Program()>& create, std::string_view options,
                                            std::uint64_t store_key) {
  const Key key{device.context()(), fnv1a(options, hash)};
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = programs_.find(key); it != programs_.end()) return it->second;
  }
  const auto start = std::chrono::steady_clock::now();
  ::cl::Program program = store_key != 0 ? load_stored(device, store_key, options) : ::cl::Program();
  const bool loaded = program() != nullptr;
  if (!loaded) {
    program = create();
    build_or_throw(program, device, name, options);
    if (store_key != 0) store_.save(store_key, program_binary(program));
  }
  const double seconds = seconds_since(start);
  const std::lock_guard<std::mutex> lock(mutex_);
  if (store_key != 0) {
    (loaded ? builds_.loaded : builds_.built) += 1;
    (loaded ? builds_.load_seconds : builds_.build_seconds) += seconds;
  }
  return programs_.emplace(key, std::move(program)).first->second;
}

void to_json(nlohmann::json& json, const ProgramBuilds& builds) {
  json = {{"compiled", builds.built},
          {"loaded", builds.loaded},
          {"compile_seconds", builds.build_seconds},
          {"load_seconds", builds.load_seconds}};
}

std::string describe(const ProgramBuilds& builds, const ProgramStore& store) {
  return std::to_string(builds.built) + " compiled, " + std::to_string(builds.loaded) +
         " loaded from the program cache" +
         (store.enabled() ? " " + store.directory().string() : std::string(" (off)"));
}

ProgramBuilds ProgramCache::builds() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return builds_;
}

std::size_t ProgramCache::size() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return programs_.size();
}

void prepare_programs(std::vector<DeviceContext>& devices, ProgramCache& programs,
                      const std::vector<ProgramRequest>& requests) {
  prepare_programs(devices, programs, [&](std::size_t) { return requests; });
}

void prepare_programs(std::vector<DeviceContext>& devices, ProgramCache& programs,
                      const std::function<std::vector<ProgramRequest>(std::size_t)>& requests_for) {
  std::vector<std::future<void>> builds;
  builds.reserve(devices.size());
  for (std::size_t position = 0; position < devices.size(); ++position) {
    builds.push_back(std::async(std::launch::async, [&, position] {
      DeviceContext& device = devices[position];
      try {
        for (const ProgramRequest& request : requests_for(position)) {
          (void)programs.get(device, request.kernel_path, request.options);
        }
      } catch (const std::exception& error) {
        spdlog::debug("preparing programs on {}: {}", describe(device.info()), error.what());
      }
    }));
  }
  for (auto& build : builds) build.get();
}

}  // namespace rfrecon::cl
